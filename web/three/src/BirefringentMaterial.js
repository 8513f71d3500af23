// BirefringentMaterial: a MeshPhysicalMaterial whose surface is a thin uniaxial slab, shaded by
// the biref library's GLSL source (shaders/biref_analytic.glsl, entry point biref_shade_slab)
// with the library's look-up table. The physics is all in that source; this file only connects
// three.js's inputs (view ray, normal, tangent frame, light behind and in the mirror direction)
// to it, through onBeforeCompile and customProgramCacheKey (WebGLRenderer).
import {
  DataTexture, FloatType, Matrix3, MeshPhysicalMaterial, NearestFilter, RGBAFormat, Vector3, Vector4,
} from 'three';
import { shaderSource, table, plans, presets } from './biref_data.js';

const OWN_KEYS = ['ordinaryIOR', 'extraordinaryIOR', 'surroundingIOR', 'slabThickness', 'slabThicknessMap', 'opticAxis',
  'opticAxisMap', 'opticAxisSpace', 'polarization', 'polarizationS', 'polarizerDirection', 'analyzer', 'analyzerDirection',
  'method'];
const POLARIZATIONS = { unpolarized: 0, sp: 1, linear: 2 };
// The shader's methods, as the uniform u_pairs (the library's other methods are CPU-only).
const METHODS = { analytic: 0, 'analytic-pairs': 1 };
const ANALYZERS = { none: 0, s: 1, p: 2, linear: 3 };

// The look-up table, the sample plans and their constants: one copy per page, shared by every
// material (uniform objects are shared, not cloned).
let shared = null;
function sharedUniforms() {
  if (shared) return shared;
  const texture = (t) => {
    const tex = new DataTexture(t.texels, t.width, t.height, RGBAFormat, FloatType);
    tex.magFilter = tex.minFilter = NearestFilter;
    tex.generateMipmaps = false;
    tex.needsUpdate = true;
    return tex;
  };
  // The table's constants are the same in every scene the library exported; take any.
  const u = Object.values(presets)[0].uniforms;
  const r = u.u_rgb_from_xyz[1];
  const rgbFromXyz = new Matrix3().set(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]);
  shared = {
    u_lut: { value: texture(table) },
    u_plans: { value: texture(plans) },
    biref_rgb_from_xyz: { value: rgbFromXyz },
    biref_xyz_from_rgb: { value: rgbFromXyz.clone().invert() },
  };
  for (const name of ['u_lut_grid', 'u_lut_band', 'u_lut_edge_lo', 'u_lut_edge_hi', 'u_k_centroid', 'u_plan_grid']) {
    const [comps, v] = u[name];
    shared[name] = { value: comps === 4 ? new Vector4(v[0], v[1], v[2], v[3]) : new Vector3(v[0], v[1], v[2]) };
  }
  return shared;
}

// GLSL added to the vertex shader: the first UV set for the tangent frame and the maps.
const VERTEX_PARS = 'varying vec2 vBirefUv;\n';
const VERTEX_MAIN = 'vBirefUv = uv;\n';

// GLSL added to the fragment shader after three.js's own functions.
const FRAGMENT_PARS = `
uniform vec4 biref_slab;            // eta_o, eta_e, thickness (nm), surrounding index
uniform vec3 biref_axis;            // optic axis in the tangent frame (tangent, bitangent, normal)
uniform vec4 biref_light;           // polarization (0 unpolarized, 1 s/p, 2 linear), s fraction, analyzer (0 none, 1 s, 2 p, 3 linear), axis in object space
uniform vec3 biref_polarizer_dir;   // world space
uniform vec3 biref_analyzer_dir;    // world space
uniform mat3 biref_rgb_from_xyz;    // the library's XYZ (white E) -> linear sRGB
uniform mat3 biref_xyz_from_rgb;
varying vec2 vBirefUv;
#ifdef BIREF_THICKNESSMAP
uniform sampler2D biref_thickness_map;
#endif
#ifdef BIREF_AXISMAP
uniform sampler2D biref_axis_map;
#endif
${shaderSource}

// Unit tangent along increasing u (view space) from screen-space derivatives, orthogonal to n.
vec3 biref_tangent(vec3 pos, vec3 n, vec2 uv)
{
    vec3 dp1 = dFdx(pos), dp2 = dFdy(pos);
    vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
    vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
    vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
    t -= dot(t, n) * n;
    float l = length(t);
    if (l > 1e-20) return t / l;
    /* No usable UVs: any tangent (the optic axis then has no defined azimuth). */
    vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    return normalize(a - dot(a, n) * n);
}
`;

// GLSL run just before three.js writes the fragment: the slab's colour replaces the physical
// material's. Every direction is in view space (the analytic method is rotation invariant).
const FRAGMENT_MAIN = `
{
    vec3 bView = isOrthographic ? vec3(0.0, 0.0, -1.0) : normalize(-vViewPosition); /* eye -> hit */
    vec3 bN = normal;
    /* The optic axis belongs to the material, not to the side it is seen from. */
#ifdef DOUBLE_SIDED
    vec3 bNGeo = normal * faceDirection;
#else
    vec3 bNGeo = normal;
#endif
    vec3 bT = biref_tangent(-vViewPosition, bNGeo, vBirefUv);
    vec3 bB = cross(bNGeo, bT);
    vec3 bAxisLocal = biref_axis;
#ifdef BIREF_AXISMAP
    bAxisLocal = texture2D(biref_axis_map, vBirefUv).xyz * 2.0 - 1.0;
#endif
    /* biref_light.w: 1 when the axis is in object space (a runtime switch: one program less). */
    vec3 bAxis = biref_light.w > 0.5 ? (viewMatrix * modelMatrix * vec4(bAxisLocal, 0.0)).xyz
                                     : bAxisLocal.x * bT + bAxisLocal.y * bB + bAxisLocal.z * bNGeo;
    bAxis = normalize(bAxis);
    float bThick = biref_slab.z;
#ifdef BIREF_THICKNESSMAP
    bThick *= texture2D(biref_thickness_map, vBirefUv).g;
#endif
    BirefLight bL;
    bL.pol_linear = biref_light.x > 1.5 ? 1.0 : 0.0;
    bL.pol_w = biref_light.x > 0.5 ? vec2(biref_light.y, 1.0 - biref_light.y) : vec2(0.5);
    bL.pol_dir = (viewMatrix * vec4(biref_polarizer_dir, 0.0)).xyz; /* the shader projects; |dir| is 1 (setter) */
    bL.filter_linear = biref_light.z > 2.5 ? 1.0 : 0.0;
    bL.mask = biref_light.z > 1.5 ? vec2(0.0, 1.0) : biref_light.z > 0.5 ? vec2(1.0, 0.0) : vec2(1.0);
    bL.filter_dir = (viewMatrix * vec4(biref_analyzer_dir, 0.0)).xyz;
    vec3 bTx, bRx;
    biref_shade_slab(bView, bN, bT, bAxis, vec3(biref_slab.xy, max(bThick, 0.0)), biref_slab.w, bL, bTx, bRx);
    /* Light from behind along the view ray: three.js's transmission target at this pixel (thin
     * wall, no refraction offset). */
    vec3 bBehind = vec3(0.0);
#ifdef USE_TRANSMISSION
    vec4 bNdc = projectionMatrix * viewMatrix * vec4(vWorldPosition, 1.0);
    bBehind = getTransmissionSample(bNdc.xy / bNdc.w * 0.5 + 0.5, material.roughness, material.ior).rgb;
#endif
    /* Light along the mirror direction: the environment map (radiance) and the lights' specular
     * lobes, which three.js computed with a Fresnel factor of one (white metal). */
    vec3 bMirror = radiance + reflectedLight.directSpecular;
    vec3 bXyz = bTx * (biref_xyz_from_rgb * bBehind) + bRx * (biref_xyz_from_rgb * bMirror);
    outgoingLight = max(biref_rgb_from_xyz * bXyz, 0.0) + totalEmissiveRadiance;
}
`;

/**
 * A surface that acts as a thin uniaxial slab (thin-walled: every hit is a locally flat slab of
 * the given thickness), lit from behind through three.js's transmission pass and in front by the
 * environment map and the lights. Units: thickness in nanometres, directions unitless.
 */
export class BirefringentMaterial extends MeshPhysicalMaterial {
  constructor(parameters = {}) {
    super();
    this.isBirefringentMaterial = true; // type stays 'MeshPhysicalMaterial': three.js picks the shader by it
    const s = sharedUniforms();
    this.birefUniforms = {
      ...s,
      biref_slab: { value: new Vector4(1.544, 1.553, 100000, 1.0) },
      biref_axis: { value: new Vector3(1, 0, 0) },
      biref_light: { value: new Vector4(0, 0.5, 0, 0) },
      biref_polarizer_dir: { value: new Vector3(1, 0, 0) },
      biref_analyzer_dir: { value: new Vector3(0, 0, 1) },
      biref_thickness_map: { value: null },
      biref_axis_map: { value: null },
      u_pairs: { value: 0 },
    };
    // The slab decides colour and energy; three.js's physical model supplies only the light:
    // a white metal (Fresnel one) gives the lights' bare specular lobes, transmission one the
    // light behind (thin wall: no volume, no offset).
    this.color.set(0xffffff);
    this.metalness = 1;
    this.roughness = 0;
    this.transmission = 1;
    this.thickness = 0;
    this.setValues(parameters);
  }

  /** Ordinary refractive index η_o. */
  get ordinaryIOR() { return this.birefUniforms.biref_slab.value.x; }
  set ordinaryIOR(v) { this.birefUniforms.biref_slab.value.x = checkIndex('ordinaryIOR', v); }

  /** Extraordinary refractive index η_e. */
  get extraordinaryIOR() { return this.birefUniforms.biref_slab.value.y; }
  set extraordinaryIOR(v) { this.birefUniforms.biref_slab.value.y = checkIndex('extraordinaryIOR', v); }

  /** Refractive index of the medium around the slab (1 = air). */
  get surroundingIOR() { return this.birefUniforms.biref_slab.value.w; }
  set surroundingIOR(v) { this.birefUniforms.biref_slab.value.w = checkIndex('surroundingIOR', v); }

  /** Slab thickness in nanometres (multiplied by slabThicknessMap's green channel if set). */
  get slabThickness() { return this.birefUniforms.biref_slab.value.z; }
  set slabThickness(v) {
    if (!(Number.isFinite(v) && v >= 0)) throw new RangeError(`slabThickness: ${v} is not a thickness in nm >= 0`);
    this.birefUniforms.biref_slab.value.z = v;
  }

  /** Texture whose green channel scales slabThickness (as three.js's thicknessMap), UV set 0. */
  get slabThicknessMap() { return this.birefUniforms.biref_thickness_map.value; }
  set slabThicknessMap(t) {
    if (!!t !== !!this.birefUniforms.biref_thickness_map.value) this.needsUpdate = true;
    this.birefUniforms.biref_thickness_map.value = t || null;
  }

  /** Optic axis in the tangent frame: x along the tangent (increasing u), y the bitangent
   * (normal × tangent), z the normal. Stored normalised. */
  get opticAxis() { return this.birefUniforms.biref_axis.value; }
  set opticAxis(v) { this.birefUniforms.biref_axis.value.copy(unit('opticAxis', v)); }

  /** 'tangent' (default): opticAxis and opticAxisMap are in the tangent frame; 'object': in
   * the mesh's object space (a crystal whose axis does not follow the surface). */
  get opticAxisSpace() { return this.birefUniforms.biref_light.value.w > 0.5 ? 'object' : 'tangent'; }
  set opticAxisSpace(v) {
    if (v !== 'tangent' && v !== 'object') throw new RangeError(`opticAxisSpace: '${v}' is not 'tangent' or 'object'`);
    this.birefUniforms.biref_light.value.w = v === 'object' ? 1 : 0;
  }

  /** Texture of optic axes in the tangent frame, xyz = 2 rgb − 1 (like a normal map; load it
   * with NoColorSpace), UV set 0. Replaces opticAxis where set. */
  get opticAxisMap() { return this.birefUniforms.biref_axis_map.value; }
  set opticAxisMap(t) {
    if (!!t !== !!this.birefUniforms.biref_axis_map.value) this.needsUpdate = true;
    this.birefUniforms.biref_axis_map.value = t || null;
  }

  /** Light reaching the slab: 'unpolarized', 'sp' (fractions relative to each ray's plane of
   * incidence, polarizationS the s fraction) or 'linear' (a world-fixed polarizer along
   * polarizerDirection). Applies to all light the material sees. */
  get polarization() { return keyOf(POLARIZATIONS, this.birefUniforms.biref_light.value.x); }
  set polarization(v) { this.birefUniforms.biref_light.value.x = lookUp('polarization', POLARIZATIONS, v); }

  /** Fraction of s-polarized light for polarization 'sp' (p = 1 − s). */
  get polarizationS() { return this.birefUniforms.biref_light.value.y; }
  set polarizationS(v) {
    if (!(v >= 0 && v <= 1)) throw new RangeError(`polarizationS: ${v} is not a fraction in [0, 1]`);
    this.birefUniforms.biref_light.value.y = v;
  }

  /** World-space direction of a linear polarizer (polarization 'linear'), stored normalised;
   * after changing the returned vector in place, normalise it. */
  get polarizerDirection() { return this.birefUniforms.biref_polarizer_dir.value; }
  set polarizerDirection(v) { this.birefUniforms.biref_polarizer_dir.value.copy(unit('polarizerDirection', v)); }

  /** Analyzer between the slab and the camera: 'none', 's', 'p' (relative to the ray's plane
   * of incidence) or 'linear' (world-fixed, along analyzerDirection). */
  get analyzer() { return keyOf(ANALYZERS, this.birefUniforms.biref_light.value.z); }
  set analyzer(v) { this.birefUniforms.biref_light.value.z = lookUp('analyzer', ANALYZERS, v); }

  /** Spectral integration: 'analytic' (default; the paper's eq. 26) or 'analytic-pairs' (eq. 26
   * plus transmission's sibling and entry pairs, beyond the paper; the library's
   * BIREF_METHOD_ANALYTIC_PAIRS). A uniform: switching costs no shader compile. */
  get method() { return keyOf(METHODS, this.birefUniforms.u_pairs.value); }
  set method(v) { this.birefUniforms.u_pairs.value = lookUp('method', METHODS, v); }

  /** World-space direction of a linear analyzer (analyzer 'linear'), stored normalised. */
  get analyzerDirection() { return this.birefUniforms.biref_analyzer_dir.value; }
  set analyzerDirection(v) { this.birefUniforms.biref_analyzer_dir.value.copy(unit('analyzerDirection', v)); }

  // Material.setValues would copy vectors past the setters: the material's own keys go through them.
  setValues(values) {
    if (values === undefined) return;
    const rest = {};
    for (const [k, v] of Object.entries(values)) {
      if (OWN_KEYS.includes(k)) this[k] = v;
      else rest[k] = v;
    }
    super.setValues(rest);
  }

  onBeforeCompile(shader) {
    Object.assign(shader.uniforms, this.birefUniforms);
    shader.vertexShader = insertAfter(shader.vertexShader, '#include <common>', VERTEX_PARS);
    shader.vertexShader = insertAfter(shader.vertexShader, '#include <uv_vertex>', VERTEX_MAIN);
    const defines = (this.slabThicknessMap ? '#define BIREF_THICKNESSMAP\n' : '') +
      (this.opticAxisMap ? '#define BIREF_AXISMAP\n' : '');
    shader.fragmentShader = insertAfter(shader.fragmentShader, '#include <clipping_planes_pars_fragment>',
      defines + FRAGMENT_PARS);
    shader.fragmentShader = insertBefore(shader.fragmentShader, '#include <opaque_fragment>', FRAGMENT_MAIN);
  }

  customProgramCacheKey() {
    return `biref:${this.slabThicknessMap ? 1 : 0}${this.opticAxisMap ? 1 : 0}`;
  }

  copy(source) {
    super.copy(source);
    if (source.isBirefringentMaterial) {
      for (const k of OWN_KEYS) this[k] = source[k];
    }
    return this;
  }
}

// A finite, non-zero direction, normalised (a copy: the caller's vector is left as it is).
function unit(name, v) {
  const l = v && v.isVector3 ? v.length() : NaN;
  if (!(Number.isFinite(l) && l > 0)) throw new RangeError(`${name}: not a finite non-zero Vector3`);
  return v.clone().divideScalar(l);
}

function checkIndex(name, v) {
  if (!(Number.isFinite(v) && v >= 1 && v <= 10)) throw new RangeError(`${name}: ${v} is not a refractive index in [1, 10]`);
  return v;
}

function lookUp(name, table, v) {
  if (typeof v !== 'string' || !Object.hasOwn(table, v)) throw new RangeError(`${name}: '${v}' is not one of ${Object.keys(table).join(', ')}`);
  return table[v];
}

function keyOf(table, n) { return Object.keys(table).find((k) => table[k] === n); }

function insertAfter(src, anchor, text) {
  if (!src.includes(anchor)) throw new Error(`BirefringentMaterial: this three.js has no '${anchor}' in its physical shader`);
  return src.replace(anchor, `${anchor}\n${text}`);
}

function insertBefore(src, anchor, text) {
  if (!src.includes(anchor)) throw new Error(`BirefringentMaterial: this three.js has no '${anchor}' in its physical shader`);
  return src.replace(anchor, `${text}\n${anchor}`);
}
