// The WebGL2 viewer: the library's GLSL source (shaders/biref_analytic.glsl), its look-up
// table and the example scenes' uniforms, all from biref_data.js (made by `biref gl-data`).
// ?scene=NAME&width=W&height=H&view=canvas shows only the canvas at W x H with that example's
// camera and sets document.title to "biref ready" once the frame is drawn. The first slab's
// controls may be set from the query too: eta_o, eta_e, thickness_um, axis_tilt, axis_az (deg);
// method=analytic (default, the paper's eq. 26) or analytic-pairs (eq. 26 plus transmission's
// sibling and entry pairs: the shader's u_pairs), as `biref render --backend gl --method`.
// Every query value is checked before anything is drawn: a bad one is an error shown in the page
// (and in document.title as "biref error: ..."), never a silent default or clamp.
import { shaderSource, table, plans, presets } from './biref_data.js';

const MAX_SLABS = 8, MAX_PANELS = 4;
// The largest canvas side: 4096 x 4096 is 16.7 megapixels in one pass, which software WebGL
// (no GPU) draws in tens of seconds; the command line's 8192 x 8192 took minutes there.
const MAX_SIDE = 4096;
const $ = (id) => document.getElementById(id);
const canvas = $('view');

function fail(text) {
  $('fatal').textContent = text;
  document.title = 'biref error: ' + text.replace(/\s+/g, ' ').slice(0, 400);
  throw new Error(text);
}
// Anything that still goes wrong is shown in the page too, not only in the console.
window.addEventListener('error', (e) => {
  if (!document.title.startsWith('biref error')) {
    $('fatal').textContent = String(e.message || e.error);
    document.title = 'biref error: ' + String(e.message || e.error).slice(0, 400);
  }
});

// ---------------------------------------------------------------------------- the query
// Each key once, known keys only, numbers in decimal within the controls' ranges.
const QUERY_NUMBERS = {
  width: [1, MAX_SIDE, true], height: [1, MAX_SIDE, true], eta_o: [1.2, 2.5], eta_e: [1.2, 2.5],
  thickness_um: [1, 10000], axis_tilt: [0, 180], axis_az: [-180, 180],
};
// The shader's methods (the command line's other methods are CPU-only, as with --backend gl).
const METHODS = ['analytic', 'analytic-pairs'];
const QUERY_WORDS = ['scene', 'view', 'method'];
const params = new Map();
for (const [key, value] of new URLSearchParams(location.search)) {
  if (!QUERY_WORDS.includes(key) && !Object.hasOwn(QUERY_NUMBERS, key))
    fail(`unknown query key '${key}' (known: ${QUERY_WORDS.join(', ')}, ${Object.keys(QUERY_NUMBERS).join(', ')})`);
  if (params.has(key)) fail(`query key '${key}' given twice`);
  if (Object.hasOwn(QUERY_NUMBERS, key)) {
    const [lo, hi, integer] = QUERY_NUMBERS[key];
    const re = integer ? /^[0-9]+$/ : /^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?$/;
    const v = Number(value);
    if (!re.test(value) || !(v >= lo && v <= hi))
      fail(`${key}: expected ${integer ? 'an integer' : 'a number'} from ${lo} to ${hi}, got '${value}'`);
  }
  params.set(key, value);
}
if (params.has('view') && params.get('view') !== 'canvas') fail(`view: expected canvas, got '${params.get('view')}'`);
if (params.has('method') && !METHODS.includes(params.get('method')))
  fail(`method: expected ${METHODS.join(' or ')} (the shader's methods), got '${params.get('method')}'`);
if (params.has('scene') && !Object.hasOwn(presets, params.get('scene')))
  fail(`unknown scene '${params.get('scene')}' (presets: ${Object.keys(presets).join(', ')})`);
const canvasOnly = params.get('view') === 'canvas';
if (canvasOnly) document.body.classList.add('canvas-only');

// ---------------------------------------------------------------------------- WebGL set-up
const gl = canvas.getContext('webgl2', { preserveDrawingBuffer: true, antialias: false, alpha: false });
if (!gl) fail('WebGL2 is not available in this browser.');

function compile(type, defines) {
  const sh = gl.createShader(type);
  gl.shaderSource(sh, '#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n' +
    defines + shaderSource);
  gl.compileShader(sh);
  if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) fail('shader does not compile:\n' + gl.getShaderInfoLog(sh));
  return sh;
}
const prog = gl.createProgram();
gl.attachShader(prog, compile(gl.VERTEX_SHADER, '#define BIREF_VERTEX\n'));
gl.attachShader(prog, compile(gl.FRAGMENT_SHADER, '#define BIREF_FRAGMENT\n#define BIREF_SCENE\n#define BIREF_OUTPUT_SRGB\n' +
  `#define BIREF_MAX_SLABS ${MAX_SLABS}\n#define BIREF_MAX_PANELS ${MAX_PANELS}\n`));
gl.linkProgram(prog);
if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) fail('shader does not link:\n' + gl.getProgramInfoLog(prog));
gl.useProgram(prog);
gl.bindVertexArray(gl.createVertexArray());

const lut = gl.createTexture();
gl.activeTexture(gl.TEXTURE0);
gl.bindTexture(gl.TEXTURE_2D, lut);
gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, table.width, table.height, 0, gl.RGBA, gl.FLOAT, table.texels);
gl.uniform1i(gl.getUniformLocation(prog, 'u_lut'), 0);
// The coherent regime's sample plans (thin slabs, evanescent coupling) on texture unit 1.
const planTex = gl.createTexture();
gl.activeTexture(gl.TEXTURE1);
gl.bindTexture(gl.TEXTURE_2D, planTex);
gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, plans.width, plans.height, 0, gl.RGBA, gl.FLOAT, plans.texels);
gl.uniform1i(gl.getUniformLocation(prog, 'u_plans'), 1);
gl.activeTexture(gl.TEXTURE0);
const timerExt = gl.getExtension('EXT_disjoint_timer_query_webgl2');

// ---------------------------------------------------------------------------- scene state
const v3 = {
  sub: (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]],
  add: (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]],
  scale: (a, s) => [a[0] * s, a[1] * s, a[2] * s],
  dot: (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
  cross: (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]],
  norm: (a) => { const l = Math.hypot(a[0], a[1], a[2]); return l > 0 ? [a[0] / l, a[1] / l, a[2] / l] : a; },
};

let state = null; // {name, u: uniforms {name: [comps, values]}, cam, axes, W, H}
const get3 = (name, i) => state.u[name][1].slice(3 * i, 3 * i + 3);
const set3 = (name, i, v) => { for (let k = 0; k < 3; k++) state.u[name][1][3 * i + k] = v[k]; };

function loadPreset(name) {
  if (!Object.hasOwn(presets, name)) fail(`unknown scene '${name}' (presets: ${Object.keys(presets).join(', ')})`);
  const p = presets[name];
  const u = JSON.parse(JSON.stringify(p.uniforms));
  if (u.u_n_slabs[1][0] > MAX_SLABS || u.u_n_panels[1][0] > MAX_PANELS)
    fail(`scene '${name}' has more than ${MAX_SLABS} slabs or ${MAX_PANELS} panels`);
  // The query was checked above; a preset's own size is capped like it.
  const W = Number(params.get('width') || Math.min(canvasOnly ? p.camera.width : 640, MAX_SIDE));
  const H = Number(params.get('height') || Math.min(canvasOnly ? p.camera.height : 360, MAX_SIDE));
  const c = p.camera;
  const off = v3.sub(c.position, c.look_at);
  u.u_pairs = [1, [$('method').value === 'analytic-pairs' ? 1 : 0]];
  state = { name, u, axes: JSON.parse(JSON.stringify(p.axes)), W, H, cam: {
    look_at: c.look_at, up: c.up, fov: c.fov_deg, dist: Math.hypot(...off),
    az: Math.atan2(off[0], off[2]), el: Math.asin(off[1] / Math.hypot(...off)), base: c.position } };
  setCamera(true);
}

// Camera basis as render_camera_init: forward, right = forward x up, up = right x forward.
function setCamera(exact) {
  const c = state.cam;
  const pos = exact ? c.base : v3.add(c.look_at, [c.dist * Math.cos(c.el) * Math.sin(c.az), c.dist * Math.sin(c.el),
    c.dist * Math.cos(c.el) * Math.cos(c.az)]);
  const f = v3.norm(v3.sub(c.look_at, pos));
  const r = v3.norm(v3.cross(f, c.up));
  const up = v3.cross(r, f);
  const tv = Math.tan(0.5 * c.fov * Math.PI / 180);
  const u = state.u;
  u.u_cam_origin = [3, pos]; u.u_cam_forward = [3, f]; u.u_cam_right = [3, r]; u.u_cam_up = [3, up];
  u.u_cam_tan_half = [2, [tv * state.W / state.H, tv]];
  u.u_resolution = [2, [state.W, state.H]];
  c.right = r; c.upv = up;
}

// ---------------------------------------------------------------------------- drawing
let pendingQuery = null, lastCpuMs = 0, frames = 0;
function draw() {
  if (canvas.width !== state.W || canvas.height !== state.H) { canvas.width = state.W; canvas.height = state.H; }
  for (const [name, [comps, v]] of Object.entries(state.u)) {
    const loc = gl.getUniformLocation(prog, name);
    if (loc === null) continue;
    const a = new Float32Array(v);
    if (comps === 1) gl.uniform1fv(loc, a); else if (comps === 2) gl.uniform2fv(loc, a);
    else if (comps === 3) gl.uniform3fv(loc, a); else gl.uniform4fv(loc, a);
  }
  gl.viewport(0, 0, state.W, state.H);
  const t0 = performance.now();
  let q = null;
  if (timerExt && !pendingQuery) { q = gl.createQuery(); gl.beginQuery(timerExt.TIME_ELAPSED_EXT, q); }
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  if (q) { gl.endQuery(timerExt.TIME_ELAPSED_EXT); pendingQuery = q; }
  // A one-pixel read waits for the frame: the readout is the time to a finished picture.
  gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  lastCpuMs = performance.now() - t0;
  frames++;
  showTime();
}

function showTime() {
  let gpu = '';
  if (pendingQuery && gl.getQueryParameter(pendingQuery, gl.QUERY_RESULT_AVAILABLE)) {
    if (!gl.getParameter(timerExt.GPU_DISJOINT_EXT))
      gpu = `, GPU ${(gl.getQueryParameter(pendingQuery, gl.QUERY_RESULT) * 1e-6).toFixed(2)} ms`;
    gl.deleteQuery(pendingQuery);
    pendingQuery = null;
  }
  $('frametime').textContent = `${state.W}×${state.H}: ${lastCpuMs.toFixed(1)} ms per frame${gpu}`;
}

let queued = false;
function redraw() {
  if (queued) return;
  queued = true;
  requestAnimationFrame(() => { queued = false; draw(); if ($('animate').checked) { state.cam.az += 0.01; setCamera(false); redraw(); } });
}

// ---------------------------------------------------------------------------- controls
const deg = Math.PI / 180;
function slabIndex() { return parseInt($('slab').value || '0', 10); }

function syncControls() {
  const u = state.u, i = slabIndex();
  const opt = get3('u_slab_optics', i);
  setVal('eta_o', opt[0], 3); setVal('eta_e', opt[1], 3);
  $('thick').value = Math.log10(opt[2] / 1000); $('thick_v').value = fmtThickness(opt[2]);
  const a = state.axes[i];
  setVal('axis_tilt', Math.acos(Math.max(-1, Math.min(1, a[1]))) / deg, 1);
  setVal('axis_az', Math.atan2(a[2], a[0]) / deg, 1);
  const pol = u.u_pol[1];
  $('pol_type').value = pol[0] > 0.5 ? 'linear' : 'sp';
  setVal('pol_s', pol[1], 2);
  const pd = u.u_pol_dir[1];
  setVal('pol_angle', Math.atan2(pd[2], pd[0]) / deg, 1);
  const mask = u.u_mask[1];
  $('filter_type').value = pol[3] > 0.5 ? 'linear' : mask[0] === 0 ? 'p' : mask[1] === 0 ? 's' : 'none';
  const fd = u.u_filter_dir[1];
  setVal('filter_angle', Math.atan2(v3.dot(fd, state.cam.upv), v3.dot(fd, state.cam.right)) / deg, 1);
}
function setVal(id, v, digits) { $(id).value = v; $(id + '_v').value = Number(v).toFixed(digits); }
function fmtThickness(nm) { return nm >= 1e6 ? (nm / 1e6).toFixed(2) + ' mm' : (nm / 1e3).toFixed(1) + ' µm'; }

function onSlab() {
  const i = slabIndex();
  const opt = get3('u_slab_optics', i);
  opt[0] = parseFloat($('eta_o').value); opt[1] = parseFloat($('eta_e').value);
  opt[2] = 1000 * Math.pow(10, parseFloat($('thick').value));
  set3('u_slab_optics', i, opt);
  const t = parseFloat($('axis_tilt').value) * deg, az = parseFloat($('axis_az').value) * deg;
  const a = [Math.sin(t) * Math.cos(az), Math.cos(t), Math.sin(t) * Math.sin(az)];
  state.axes[i] = a;
  // Local (tangent, normal, tangent x normal) to world, as biref_renderer_create.
  const T = get3('u_slab_tangent', i), N = get3('u_slab_normal', i), B = get3('u_slab_bitangent', i);
  set3('u_slab_axis', i, v3.norm(v3.add(v3.add(v3.scale(T, a[0]), v3.scale(N, a[1])), v3.scale(B, a[2]))));
  for (const id of ['eta_o', 'eta_e']) $(id + '_v').value = parseFloat($(id).value).toFixed(3);
  for (const id of ['axis_tilt', 'axis_az']) $(id + '_v').value = parseFloat($(id).value).toFixed(1);
  $('thick_v').value = fmtThickness(opt[2]);
  redraw();
}

function onPolarization(ev) {
  const u = state.u, pol = u.u_pol[1];
  pol[0] = $('pol_type').value === 'linear' ? 1 : 0;
  const s = parseFloat($('pol_s').value);
  pol[1] = s; pol[2] = 1 - s;
  if (ev && ev.target.id === 'pol_angle' || pol[0] && !v3.dot(u.u_pol_dir[1], u.u_pol_dir[1])) {
    const a = parseFloat($('pol_angle').value) * deg;
    u.u_pol_dir = [3, [Math.cos(a), 0, Math.sin(a)]];
  }
  const ft = $('filter_type').value;
  pol[3] = ft === 'linear' ? 1 : 0;
  u.u_mask = [2, [ft === 'p' ? 0 : 1, ft === 's' ? 0 : 1]];
  if (ev && ev.target.id === 'filter_angle' || pol[3] && !v3.dot(u.u_filter_dir[1], u.u_filter_dir[1])) {
    const a = parseFloat($('filter_angle').value) * deg;
    u.u_filter_dir = [3, v3.add(v3.scale(state.cam.right, Math.cos(a)), v3.scale(state.cam.upv, Math.sin(a)))];
  }
  for (const id of ['pol_s']) $(id + '_v').value = parseFloat($(id).value).toFixed(2);
  for (const id of ['pol_angle', 'filter_angle']) $(id + '_v').value = parseFloat($(id).value).toFixed(1);
  redraw();
}

function fillSlabs() {
  const n = state.u.u_n_slabs[1][0];
  $('slab').innerHTML = Array.from({ length: n }, (_, i) => `<option value="${i}">${i + 1} of ${n}</option>`).join('');
}

function start(name, overrides) {
  loadPreset(name);
  $('preset').value = name;
  fillSlabs();
  syncControls();
  if (overrides) {
    // Through the controls themselves, so the query exercises what a user's hand does.
    let any = false;
    for (const id of ['eta_o', 'eta_e', 'axis_tilt', 'axis_az']) {
      if (params.has(id)) { $(id).value = params.get(id); any = true; }
    }
    if (params.has('thickness_um')) { $('thick').value = Math.log10(parseFloat(params.get('thickness_um'))); any = true; }
    if (any) onSlab();
  }
  draw();
  // The frame is finished (draw reads a pixel back): tests take their screenshot now.
  requestAnimationFrame(() => { document.title = 'biref ready'; });
}

$('preset').innerHTML = Object.keys(presets).map((n) => `<option>${n}</option>`).join('');
$('method').innerHTML = METHODS.map((n) => `<option>${n}</option>`).join('');
$('method').value = params.get('method') || 'analytic';
$('method').addEventListener('change', () => {
  state.u.u_pairs = [1, [$('method').value === 'analytic-pairs' ? 1 : 0]];
  redraw();
});
$('preset').addEventListener('change', () => { document.title = 'biref'; start($('preset').value); });
$('slab').addEventListener('change', syncControls);
for (const id of ['eta_o', 'eta_e', 'thick', 'axis_tilt', 'axis_az']) $(id).addEventListener('input', onSlab);
for (const id of ['pol_type', 'pol_s', 'pol_angle', 'filter_type', 'filter_angle'])
  $(id).addEventListener('input', onPolarization);
$('animate').addEventListener('change', redraw);

// Orbit: drag rotates about the look-at point, the wheel zooms.
let drag = null;
canvas.addEventListener('pointerdown', (e) => { if (!canvasOnly) { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); } });
canvas.addEventListener('pointerup', () => { drag = null; });
canvas.addEventListener('pointermove', (e) => {
  if (!drag) return;
  const c = state.cam;
  c.az -= (e.clientX - drag[0]) * 0.01;
  c.el = Math.max(-1.5, Math.min(1.5, c.el + (e.clientY - drag[1]) * 0.01));
  drag = [e.clientX, e.clientY];
  setCamera(false);
  redraw();
});
canvas.addEventListener('wheel', (e) => {
  if (canvasOnly) return;
  e.preventDefault();
  state.cam.dist *= Math.exp(e.deltaY * 0.001);
  setCamera(false);
  redraw();
}, { passive: false });

start(params.get('scene') || 'fig9c', true);
