// BirefringentMaterial examples. ?example=NAME (fig9c, polariscope, gem, sheet; all: the three
// mesh scenes in turn on one renderer) &width=W
// &height=H &view=canvas (only the canvas, for tests) &frames=N (time N more frames after the
// first) &material=iridescence (three.js's own MeshPhysicalMaterial with iridescence in place of
// every birefringent one, to compare costs) &method=analytic-pairs (every birefringent material's
// method; default analytic, the paper's eq. 26). fig9c also takes thickness_um and eta_o for its slab.
// document.title becomes "biref ready" once the first frame (or the timed frames) is drawn, or
// "biref error: ..." on any error, a shader that does not compile or a WebGL error.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import { BirefringentMaterial } from 'biref-three';
import { presets } from '../../biref_data.js'; // the example scenes as `biref gl-data` exported them

const params = new URLSearchParams(location.search);
const canvasOnly = params.get('view') === 'canvas';
if (canvasOnly) document.body.classList.add('canvas-only');
const $ = (id) => document.getElementById(id);

function fail(text) {
  $('error').textContent = text;
  document.title = 'biref error: ' + String(text).replace(/\s+/g, ' ').slice(0, 400);
  throw new Error(text);
}
window.addEventListener('error', (e) => { if (!document.title.startsWith('biref error')) fail(e.message + (e.error && e.error.stack ? ' at ' + e.error.stack.split('\n').slice(1, 3).join(' ') : '')); });
window.addEventListener('unhandledrejection', (e) => fail(String(e.reason)));

const W = parseInt(params.get('width') || '960', 10), H = parseInt(params.get('height') || '540', 10);
if (!(W > 0 && H > 0 && W <= 8192 && H <= 8192)) fail(`width and height must be 1..8192 (got ${W} x ${H})`);
const useIridescence = params.get('material') === 'iridescence';

const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.setSize(W, H);
renderer.debug.onShaderError = (gl, program, vs, fs) => {
  const log = [gl.getProgramInfoLog(program), gl.getShaderInfoLog(vs), gl.getShaderInfoLog(fs)].join('\n');
  fail('shader does not compile or link:\n' + log.trim().slice(0, 2000));
};
$('view').appendChild(renderer.domElement);
const pmrem = new THREE.PMREMGenerator(renderer);

// A birefringent material, or for cost comparisons three.js's thin-film iridescence in its place.
// A bad method is the material's RangeError, shown by the error handler above.
const method = params.has('method') ? { method: params.get('method') } : {};
function slabMaterial(options) {
  if (!useIridescence) return new BirefringentMaterial({ ...options, ...method });
  return new THREE.MeshPhysicalMaterial({
    side: options.side, roughness: 0, metalness: 0, transmission: 1, thickness: 0,
    iridescence: 1, iridescenceIOR: 1.3, iridescenceThicknessRange: [100, 400],
  });
}

// The mesh scenes' light: three.js's room environment and one directional light (the same in
// every scene, so that their materials share programs).
function roomEnvironment(scene) {
  scene.environment = pmrem.fromScene(new RoomEnvironment(), 0.04).texture;
  scene.background = new THREE.Color(0x202226);
  const light = new THREE.DirectionalLight(0xffffff, 2.5);
  light.position.set(1, 2, 1.5);
  scene.add(light);
}

// ------------------------------------------------------------------------------ fig. 9c
// examples/fig9c.json as the library exported it (camera, slab, light table, environment,
// polarization): the same view as `biref render examples/fig9c.json`.
function fig9c() {
  const p = presets.fig9c, u = p.uniforms;
  const r = u.u_rgb_from_xyz[1];
  const rgb = (v, i = 0) => {
    const x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
    return [r[0] * x + r[1] * y + r[2] * z, r[3] * x + r[4] * y + r[5] * z, r[6] * x + r[7] * y + r[8] * z];
  };
  const vec = (name, i = 0) => new THREE.Vector3().fromArray(u[name][1], 3 * i);
  const scene = new THREE.Scene();
  const c = p.camera;
  const camera = new THREE.PerspectiveCamera(c.fov_deg, W / H, 0.01, 100); // vertical field of view, as biref's
  camera.position.fromArray(c.position);
  camera.up.fromArray(c.up);
  camera.lookAt(new THREE.Vector3().fromArray(c.look_at));

  // A plane oriented like a scene rectangle: u along its tangent, normal as given.
  const rectangle = (i, prefix, material) => {
    const half = u[`u_${prefix}_half`][1];
    const mesh = new THREE.Mesh(new THREE.PlaneGeometry(2 * half[2 * i], 2 * half[2 * i + 1]), material);
    const t = vec(`u_${prefix}_tangent`, i), n = vec(`u_${prefix}_normal`, i);
    mesh.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(t, n.clone().cross(t), n));
    mesh.position.copy(vec(`u_${prefix}_center`, i));
    scene.add(mesh);
    return mesh;
  };
  const pol = u.u_pol[1], mask = u.u_mask[1];
  for (let i = 0; i < u.u_n_slabs[1][0]; i++) {
    const opt = u.u_slab_optics[1].slice(3 * i, 3 * i + 3);
    if (i === 0 && params.has('thickness_um')) opt[2] = 1000 * parseFloat(params.get('thickness_um'));
    if (i === 0 && params.has('eta_o')) opt[0] = parseFloat(params.get('eta_o'));
    const t = vec('u_slab_tangent', i), n = vec('u_slab_normal', i), a = vec('u_slab_axis', i);
    const m = slabMaterial({
      side: THREE.DoubleSide, ordinaryIOR: opt[0], extraordinaryIOR: opt[1], slabThickness: opt[2],
      surroundingIOR: u.u_eta_medium[1][0],
      // The world optic axis in the plane's tangent frame (tangent, normal x tangent, normal).
      opticAxis: new THREE.Vector3(a.dot(t), a.dot(n.clone().cross(t)), a.dot(n)),
      polarization: pol[0] > 0.5 ? 'linear' : 'sp', polarizationS: pol[1],
      analyzer: pol[3] > 0.5 ? 'linear' : mask[0] === 1 && mask[1] === 0 ? 's' : mask[0] === 0 ? 'p' : 'none',
      // Directions only for world-fixed filters (the s/p model exports zero vectors).
      ...(pol[0] > 0.5 ? { polarizerDirection: vec('u_pol_dir') } : {}),
      ...(pol[3] > 0.5 ? { analyzerDirection: vec('u_filter_dir') } : {}),
    });
    rectangle(i, 'slab', m);
  }
  for (let i = 0; i < u.u_n_panels[1][0]; i++)
    rectangle(i, 'panel', new THREE.MeshBasicMaterial({ color: new THREE.Color(...rgb(u.u_panel_radiance[1], i)), side: THREE.DoubleSide }));

  // The gradient environment (docs/SCENES.md) as an equirectangular float texture: it depends
  // on the elevation only.
  if (u.u_env_checker[1][0] > 0.5) fail('fig9c: checker environments are not drawn by this example');
  const up = vec('u_env_up');
  if (up.y < 0.999) fail('fig9c: the environment must be vertical');
  const zen = rgb(u.u_env_zenith[1]), hor = rgb(u.u_env_horizon[1]), gnd = rgb(u.u_env_ground[1]);
  const EW = 1024, EH = 512, env = new Float32Array(EW * EH * 4);
  for (let j = 0; j < EH; j++) {
    const el = Math.sin(((j + 0.5) / EH - 0.5) * Math.PI);
    const f = el >= 0 ? Math.sqrt(Math.min(el, 1)) : Math.min(1, -el * 8), to = el >= 0 ? zen : gnd;
    for (let i = 0; i < EW; i++)
      for (let k = 0; k < 3; k++) env[4 * (j * EW + i) + k] = hor[k] + (to[k] - hor[k]) * f;
    for (let i = 0; i < EW; i++) env[4 * (j * EW + i) + 3] = 1;
  }
  const envTex = new THREE.DataTexture(env, EW, EH, THREE.RGBAFormat, THREE.FloatType);
  envTex.mapping = THREE.EquirectangularReflectionMapping;
  envTex.magFilter = envTex.minFilter = THREE.LinearFilter;
  envTex.needsUpdate = true;
  scene.background = envTex;
  scene.environment = pmrem.fromEquirectangular(envTex).texture;
  if (u.u_exposure[1][0] !== 1) {
    renderer.toneMapping = THREE.LinearToneMapping;
    renderer.toneMappingExposure = u.u_exposure[1][0];
  }
  return { scene, camera, target: new THREE.Vector3().fromArray(c.look_at) };
}

// ------------------------------------------------------------------------------ polariscope
// Procedural maps for moulded plastic: the optic axis in the sheet's plane along a stress
// direction field, the thickness scaled so that the retardation varies (fringes).
function dataMap(size, fn) {
  const d = new Uint8Array(size * size * 4);
  for (let j = 0; j < size; j++)
    for (let i = 0; i < size; i++) {
      const v = fn((i + 0.5) / size, (j + 0.5) / size);
      for (let k = 0; k < 4; k++) d[4 * (j * size + i) + k] = Math.round(255 * Math.min(1, Math.max(0, v[k] ?? 1)));
    }
  const t = new THREE.DataTexture(d, size, size);
  t.magFilter = THREE.LinearFilter;
  t.needsUpdate = true;
  return t;
}
const axisTexel = (phi) => [0.5 + 0.5 * Math.cos(phi), 0.5 + 0.5 * Math.sin(phi), 0.5];

// UVs of a flat shape mapped to [0, 1]^2 over its bounding box (u along x).
function boxUv(geometry) {
  geometry.computeBoundingBox();
  const b = geometry.boundingBox, pos = geometry.attributes.position, uv = new Float32Array(pos.count * 2);
  for (let k = 0; k < pos.count; k++) {
    uv[2 * k] = (pos.getX(k) - b.min.x) / (b.max.x - b.min.x);
    uv[2 * k + 1] = (pos.getY(k) - b.min.y) / (b.max.y - b.min.y);
  }
  geometry.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
  return geometry;
}

function polariscope() {
  const scene = new THREE.Scene();
  roomEnvironment(scene);
  const camera = new THREE.PerspectiveCamera(40, W / H, 0.01, 50);
  camera.position.set(0.35, 0.25, 1.9);
  camera.lookAt(0, 0, 0);
  // Crossed polarizers, world-fixed: light polarized along x reaches the plastic, the analyzer
  // in front passes y. Both apply to everything the birefringent materials see.
  const crossed = { polarization: 'linear', polarizerDirection: new THREE.Vector3(1, 0, 0),
    analyzer: 'linear', analyzerDirection: new THREE.Vector3(0, 1, 0) };
  const box = new THREE.Mesh(new THREE.PlaneGeometry(2.2, 1.5), new THREE.MeshBasicMaterial({ color: 0xffffff }));
  box.position.z = -0.4;
  scene.add(box);
  // The polarizer sheet: an isotropic film (η_o = η_e) seen through the analyzer, dark where the
  // polarizers are crossed.
  const sheet = new THREE.Mesh(new THREE.PlaneGeometry(2.0, 1.3), slabMaterial({
    ordinaryIOR: 1.5, extraordinaryIOR: 1.5, slabThickness: 2e5, opticAxis: new THREE.Vector3(0, 0, 1), ...crossed,
    side: THREE.DoubleSide }));
  sheet.position.z = -0.3;
  scene.add(sheet);

  // A protractor: a half ring on a strip, polycarbonate-like (Δn = 0.001 where stressed).
  const pro = new THREE.Shape();
  pro.moveTo(-0.55, -0.08); pro.lineTo(0.55, -0.08); pro.lineTo(0.55, 0);
  pro.absarc(0, 0, 0.55, 0, Math.PI, false); pro.lineTo(-0.55, -0.08);
  const hole = new THREE.Path();
  hole.moveTo(0.35, 0.02); hole.absarc(0, 0.02, 0.35, 0, Math.PI, false); hole.lineTo(0.35, 0.02);
  pro.holes.push(hole);
  const proGeo = boxUv(new THREE.ShapeGeometry(pro, 48));
  const proMat = slabMaterial({
    ordinaryIOR: 1.585, extraordinaryIOR: 1.586, slabThickness: 2e6, ...crossed, side: THREE.DoubleSide,
    // Stress around the ring: axis along the radius, retardation growing towards the edges.
    opticAxisMap: dataMap(256, (s, t) => axisTexel(Math.atan2(t * 0.63 - 0.51, s - 0.5))),
    slabThicknessMap: dataMap(256, (s, t) => {
      const rr = Math.hypot((s - 0.5) * 1.1, (t * 0.63 - 0.51) * 1.1);
      return [0, 0.25 + 0.75 * Math.min(1, Math.abs(rr - 0.45) * 5 + 0.3 * Math.sin(9 * s) ** 2), 0, 1];
    }),
  });
  const protractor = new THREE.Mesh(proGeo, proMat);
  protractor.position.set(-0.45, -0.05, 0);
  scene.add(protractor);

  // A 45° set square with a triangular cut-out.
  const sq = new THREE.Shape([new THREE.Vector2(0, 0), new THREE.Vector2(0.75, 0), new THREE.Vector2(0, 0.75)]);
  sq.holes.push(new THREE.Path([new THREE.Vector2(0.12, 0.12), new THREE.Vector2(0.12, 0.43), new THREE.Vector2(0.43, 0.12)]));
  const sqMat = slabMaterial({
    ordinaryIOR: 1.585, extraordinaryIOR: 1.586, slabThickness: 1.5e6, ...crossed, side: THREE.DoubleSide,
    opticAxisMap: dataMap(256, (s, t) => axisTexel(Math.atan2(t - 0.3, s - 0.3) + 0.4)),
    slabThicknessMap: dataMap(256, (s, t) => [0, 0.3 + 0.7 * Math.min(1, Math.hypot(s - 0.27, t - 0.27) * 1.6), 0, 1]),
  });
  const square = new THREE.Mesh(boxUv(new THREE.ShapeGeometry(sq)), sqMat);
  square.position.set(0.25, -0.42, 0.02);
  square.rotation.z = 0.2;
  scene.add(square);

  // The analyzer's frame in front (its film is the materials' analyzer).
  const frame = new THREE.Shape([new THREE.Vector2(-1, -0.65), new THREE.Vector2(1, -0.65), new THREE.Vector2(1, 0.65), new THREE.Vector2(-1, 0.65)]);
  frame.holes.push(new THREE.Path([new THREE.Vector2(-0.94, -0.59), new THREE.Vector2(-0.94, 0.59), new THREE.Vector2(0.94, 0.59), new THREE.Vector2(0.94, -0.59)]));
  const frameMesh = new THREE.Mesh(new THREE.ShapeGeometry(frame), new THREE.MeshStandardMaterial({ color: 0x303238, roughness: 0.6 }));
  frameMesh.position.z = 0.3;
  scene.add(frameMesh);
  return { scene, camera, target: new THREE.Vector3(0, -0.05, 0) };
}

// ------------------------------------------------------------------------------ gem
function gem() {
  const scene = new THREE.Scene();
  roomEnvironment(scene);
  const camera = new THREE.PerspectiveCamera(35, W / H, 0.01, 50);
  camera.position.set(0.9, 1.7, 1.3);
  camera.lookAt(0, 0, 0);
  // A brilliant-like cut: pavilion, girdle, crown and table, eight facets around.
  const profile = [[0.001, -0.55], [0.6, 0], [0.6, 0.05], [0.38, 0.25], [0.001, 0.25]].map(([x, y]) => new THREE.Vector2(x, y));
  const geometry = new THREE.LatheGeometry(profile, 8).toNonIndexed();
  geometry.computeVertexNormals();
  // A quartz-like crystal seen between crossed polarizers (light polarized vertically, analyzer
  // horizontal): each facet a 60 µm slab, the optic axis fixed in the crystal.
  const material = slabMaterial({
    ordinaryIOR: 1.544, extraordinaryIOR: 1.553, slabThickness: 6e4, side: THREE.DoubleSide,
    opticAxisSpace: 'object', opticAxis: new THREE.Vector3(1, 0.3, 0.5),
    polarization: 'linear', polarizerDirection: new THREE.Vector3(0, 1, 0),
    analyzer: 'linear', analyzerDirection: new THREE.Vector3(1, 0, -0.6),
  });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.rotation.y = 0.3;
  scene.add(mesh);
  // On a gemmologist's light table: the light the facets transmit comes from below.
  const floor = new THREE.Mesh(new THREE.CircleGeometry(1.6, 64), new THREE.MeshBasicMaterial({ color: 0xf2f2f2 }));
  floor.rotation.x = -Math.PI / 2;
  floor.position.y = -0.6;
  scene.add(floor);
  return { scene, camera, target: new THREE.Vector3(0, -0.1, 0) };
}

// ------------------------------------------------------------------------------ curved sheet
function sheet() {
  const scene = new THREE.Scene();
  roomEnvironment(scene);
  const camera = new THREE.PerspectiveCamera(40, W / H, 0.01, 50);
  camera.position.set(0.2, 0.3, 1.8);
  camera.lookAt(0, 0, 0);
  const box = new THREE.Mesh(new THREE.PlaneGeometry(2.6, 1.6), new THREE.MeshBasicMaterial({ color: 0xffffff }));
  box.position.z = -0.7;
  scene.add(box);
  // A stretched film (Δn 0.009, 110 µm) bent into a half cylinder: the retardation changes with
  // the angle of incidence along the bend. Optic axis along the stretch (the tangent).
  const R = 0.45, geometry = new THREE.PlaneGeometry(Math.PI * R, 0.9, 96, 1);
  const pos = geometry.attributes.position;
  for (let k = 0; k < pos.count; k++) {
    const a = pos.getX(k) / R;
    pos.setXYZ(k, R * Math.sin(a), pos.getY(k), R * Math.cos(a) - R * 0.5);
  }
  geometry.computeVertexNormals();
  const material = slabMaterial({
    ordinaryIOR: 1.55, extraordinaryIOR: 1.559, slabThickness: 1.1e5, side: THREE.DoubleSide,
    opticAxis: new THREE.Vector3(1, 0, 0),
    polarization: 'linear', polarizerDirection: new THREE.Vector3(Math.SQRT1_2, Math.SQRT1_2, 0),
    analyzer: 'linear', analyzerDirection: new THREE.Vector3(-Math.SQRT1_2, Math.SQRT1_2, 0),
  });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.rotation.set(0.35, 0.5, 0.15);
  scene.add(mesh);
  return { scene, camera, target: new THREE.Vector3(0, 0, 0) };
}

const EXAMPLES = { fig9c, polariscope, gem, sheet };
const name = params.get('example') || 'fig9c';
// 'all': every mesh example drawn in turn by one renderer (its programs compiled once), for tests.
const ALL = ['polariscope', 'gem', 'sheet'];
if (!(name in EXAMPLES) && name !== 'all')
  fail(`unknown example '${name}' (examples: ${Object.keys(EXAMPLES).join(', ')}, all)`);

const gl = renderer.getContext();
const pixel = new Uint8Array(4);
let current = null;
function render() {
  renderer.render(current.scene, current.camera);
  // A one-pixel read waits for the frame: the time measured is the time to a finished picture.
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
  const err = gl.getError();
  if (err !== gl.NO_ERROR) fail(`WebGL error 0x${err.toString(16)} while drawing '${current.name}'`);
}

let firstMs = 0;
for (const n of name === 'all' ? ALL : [name]) {
  current = { name: n, ...EXAMPLES[n]() };
  const t0 = performance.now();
  render();
  firstMs += performance.now() - t0;
}
const controls = new OrbitControls(current.camera, renderer.domElement);
controls.target.copy(current.target); // the camera already looks there: no update before the first frame
controls.addEventListener('change', () => render());

const frames = parseInt(params.get('frames') || '0', 10);
const times = [];
for (let k = 0; k < frames; k++) {
  const t0 = performance.now();
  render();
  times.push(performance.now() - t0);
}
times.sort((a, b) => a - b);
const median = times.length ? times[times.length >> 1] : NaN;
document.body.dataset.firstFrameMs = firstMs.toFixed(1);
document.body.dataset.frameMs = median.toFixed(1);
$('info').textContent = `${name}, ${W}×${H}${useIridescence ? ', MeshPhysicalMaterial iridescence' : ''}: first frame ` +
  `${firstMs.toFixed(0)} ms (shader compile included)` + (times.length ? `, median of ${times.length}: ${median.toFixed(1)} ms` : '') +
  '. Drag to orbit, wheel to zoom.';
requestAnimationFrame(() => { if (!document.title.startsWith('biref error')) document.title = 'biref ready'; });
