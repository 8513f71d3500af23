// The packed biref-three imported by Node from an application's node_modules: the material's
// properties, bad values refused with a RangeError (the method as the shader's two: analytic,
// analytic-pairs), the shader injection into three.js's own
// physical shader (the library's GLSL entry point and table present), program cache keys and
// needsUpdate when a map comes or goes. Prints "ok" or throws.
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { BirefringentMaterial } from 'biref-three';

const m = new BirefringentMaterial({ ordinaryIOR: 1.6, extraordinaryIOR: 1.7, slabThickness: 1000,
  polarization: 'sp', polarizationS: 0.25, analyzer: 's' });
assert.equal(m.isMeshPhysicalMaterial, true);
assert.equal(m.ordinaryIOR, 1.6);
assert.equal(m.extraordinaryIOR, 1.7);
assert.equal(m.slabThickness, 1000);
assert.equal(m.polarization, 'sp');
assert.equal(m.polarizationS, 0.25);
assert.equal(m.analyzer, 's');
assert.equal(m.opticAxisSpace, 'tangent');
assert.equal(m.method, 'analytic', "the default method is the paper's eq. 26");
assert.equal(new BirefringentMaterial({ method: 'analytic-pairs' }).method, 'analytic-pairs');
const axis = new THREE.Vector3(0, 3, 4);
const n = new BirefringentMaterial({ opticAxis: axis, roughness: 0.2 });
assert.ok(Math.abs(n.opticAxis.y - 0.6) < 1e-12 && Math.abs(n.opticAxis.z - 0.8) < 1e-12, 'the axis is stored normalised');
assert.equal(axis.y, 3, "the caller's vector is left as it is");
assert.equal(n.roughness, 0.2, "MeshPhysicalMaterial's own parameters still apply");
assert.throws(() => new BirefringentMaterial({ slabThickness: NaN }), RangeError);
assert.equal(m.transmission, 1, 'the light behind comes through three.js transmission');

for (const [key, bad] of [['ordinaryIOR', NaN], ['extraordinaryIOR', 0.5], ['surroundingIOR', Infinity],
  ['slabThickness', -1], ['polarization', 'circular'], ['polarizationS', 1.5], ['analyzer', 'x'],
  ['opticAxisSpace', 'world'], ['opticAxis', new THREE.Vector3(0, 0, 0)],
  ['polarizerDirection', new THREE.Vector3(NaN, 0, 1)], ['analyzerDirection', [0, 1, 0]],
  ['method', 'numeric'], ['method', 'expansion'], ['method', 'toString'], ['method', 1], ['analyzer', 'constructor']])
  assert.throws(() => { m[key] = bad; }, RangeError, `${key} = ${bad} must be refused`);
assert.equal(m.ordinaryIOR, 1.6, 'a refused value leaves the property as it was');

const c = m.clone();
assert.equal(c.extraordinaryIOR, 1.7);
assert.equal(c.analyzer, 's');
m.method = 'analytic-pairs';
assert.equal(m.clone().method, 'analytic-pairs', 'a clone keeps the method');
c.ordinaryIOR = 1.5;
assert.equal(m.ordinaryIOR, 1.6, 'a clone has its own uniforms');

const lib = THREE.ShaderLib.physical;
const shader = { uniforms: THREE.UniformsUtils.clone(lib.uniforms), vertexShader: lib.vertexShader,
  fragmentShader: lib.fragmentShader };
m.onBeforeCompile(shader);
assert.match(shader.fragmentShader, /bool biref_shade_slab\(/, 'the library GLSL entry point is in the shader');
assert.match(shader.fragmentShader, /biref_shade_slab\(bView,/, 'and called at each fragment');
assert.match(shader.vertexShader, /vBirefUv = uv;/);
assert.equal(shader.uniforms.u_lut.value.image.width, 2001, 'the library table is bound');
assert.equal(shader.uniforms.biref_slab.value, m.birefUniforms.biref_slab.value, 'uniforms are shared, not copied');
assert.equal(shader.uniforms.u_pairs.value, 1, "the method reaches the shader's u_pairs");
assert.match(shader.fragmentShader, /uniform float u_pairs;/);

const key = m.customProgramCacheKey(), v0 = m.version;
m.slabThickness = 2000;
m.method = 'analytic';
assert.equal(m.version, v0, 'a uniform change (the method too) needs no new program');
assert.equal(m.customProgramCacheKey(), key);
m.slabThicknessMap = new THREE.Texture();
assert.ok(m.version > v0, 'a map that appears needs a new program (needsUpdate)');
assert.notEqual(m.customProgramCacheKey(), key);
const withMap = { uniforms: THREE.UniformsUtils.clone(lib.uniforms), vertexShader: lib.vertexShader,
  fragmentShader: lib.fragmentShader };
m.onBeforeCompile(withMap);
assert.match(withMap.fragmentShader, /#define BIREF_THICKNESSMAP/);
console.log('ok');
