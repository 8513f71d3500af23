// biref-three: birefringence-induced iridescence for three.js (WebGLRenderer), from the biref
// library's GLSL source and look-up table (docs/THREE.md).
export { BirefringentMaterial } from './BirefringentMaterial.js';
