// A plate of a quartz-like crystal between crossed polarizers over a light table, drawn with the
// packed biref-three (docs/THREE.md's usage snippet). Sets document.title to "biref ready" once
// drawn without a WebGL error, "biref error: ..." otherwise.
import * as THREE from 'three';
import { BirefringentMaterial } from 'biref-three';

const fail = (text) => { document.title = 'biref error: ' + String(text).replace(/\s+/g, ' ').slice(0, 400); };
window.addEventListener('error', (e) => fail(e.message));
try {
  const renderer = new THREE.WebGLRenderer({ preserveDrawingBuffer: true });
  renderer.debug.onShaderError = (gl, program) => fail('shader: ' + gl.getProgramInfoLog(program));
  renderer.setSize(innerWidth, innerHeight);
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(40, innerWidth / innerHeight, 0.1, 10);
  camera.position.set(0, 1.2, 1.2);
  camera.lookAt(0, 0, 0);
  const table = new THREE.Mesh(new THREE.PlaneGeometry(4, 4).rotateX(-Math.PI / 2), new THREE.MeshBasicMaterial());
  table.position.y = -0.05;
  scene.add(table);
  const plate = new THREE.Mesh(new THREE.PlaneGeometry(1, 1).rotateX(-Math.PI / 2), new BirefringentMaterial({
    ordinaryIOR: 1.544, extraordinaryIOR: 1.553, slabThickness: 50e3, // nanometres
    opticAxis: new THREE.Vector3(1, 0.5, 0.3),                        // tangent, bitangent, normal
    polarization: 'linear', polarizerDirection: new THREE.Vector3(1, 0, 0),
    analyzer: 'linear', analyzerDirection: new THREE.Vector3(0, 0, 1),
  }));
  scene.add(plate);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  const err = gl.getError();
  if (err !== gl.NO_ERROR) fail(`WebGL error 0x${err.toString(16)}`);
  else if (!document.title.startsWith('biref error')) requestAnimationFrame(() => { document.title = 'biref ready'; });
} catch (e) {
  fail(e.message);
}
