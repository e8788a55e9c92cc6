// The viewer page: decodes the embedded views, draws them in a grid with one linked camera,
// and follows the toolbar, the mouse and the URL hash. `THREE` is the vendored bundle's global.
// Status for tests and people alike: #status reads `ready:<mode>` after each draw, or
// `error:<message>` (the inline handler before this script writes errors).

const FOV_DEG = 35; // vertical field of view of every view's camera
const FIT_MARGIN = 1.15; // the bounding sphere fills 1/1.15 of the narrower half-angle
const DEFAULT_YAW = -60, DEFAULT_PITCH = 25; // degrees: a three-quarter view from above
const TURN_PER_PX = 0.5, TILT_PER_PX = 0.5; // degrees a dragged pixel turns
const ZOOM_PER_WHEEL = 0.0015; // zoom factor exp(-deltaY * this) per wheel step
const STRIPES = 16; // reflection lines (dark+bright pairs) around the axis
const BANDS = 10; // isophote bands over n·L in [-1, 1]
// Colour maps, the same stops for the shader and the colour bar. Diverging: Moreland's
// cool-warm (blue < 0 < red); sequential for distances: viridis.
const DIVERGING = [[59, 76, 192], [141, 176, 254], [221, 221, 221], [244, 154, 123], [180, 4, 38]];
const SEQUENTIAL = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
const LINE_COLOURS = { boundaries: 0x202020, nets: 0xd06000, data_mesh: 0x2050c0 };

const data = JSON.parse(document.getElementById('viewer-data').textContent);
const status = document.getElementById('status');
const setStatus = (s) => { status.textContent = s; };

function decode(b64, Type) {
  if (b64 == null) return null;
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Type(bytes.buffer); // little-endian, as every browser platform is
}

// The modes: shaded, every scalar (in order of first appearance), zebra, isophotes, distance.
const scalarNames = [];
for (const v of data.views) for (const s of v.scalars) if (!scalarNames.includes(s.name)) scalarNames.push(s.name);
const hasDistance = data.views.some((v) => v.distance != null);
const modes = ['shaded', ...scalarNames, 'zebra', 'isophotes', ...(hasDistance ? ['distance'] : [])];
const toggles = ['boundaries', 'nets', 'data_mesh'].filter((t) => data.views.some((v) => v[t] != null));
const toggleLabels = { boundaries: 'patch boundaries', nets: 'control nets', data_mesh: 'data mesh' };
const hashToggle = { boundaries: 'boundaries', nets: 'nets', data_mesh: 'mesh' };

const vertexShader = `
attribute float scalar;
varying vec3 vN;
varying vec3 vP;
varying float vS;
void main() {
  vec4 p = modelViewMatrix * vec4(position, 1.0);
  vP = p.xyz;
  vN = normalMatrix * normal;
  vS = scalar;
  gl_Position = projectionMatrix * p;
}`;
const fragmentShader = `
uniform int mode;        // 0 shaded, 1 diverging scalar, 2 sequential scalar, 3 zebra, 4 isophotes
uniform float range;     // colour range: |value| = range is full colour
uniform vec3 diverging[5];
uniform vec3 sequential[5];
uniform mat3 viewToWorld;
uniform vec3 across1;    // with across2 and the up axis, a right-handed world basis
uniform vec3 across2;
uniform float stripes;
uniform float bands;
varying vec3 vN;
varying vec3 vP;
varying float vS;
const float PI = 3.141592653589793;
vec3 ramp(vec3 c[5], float t) {
  float x = clamp(t, 0.0, 1.0) * 4.0;
  int i = int(min(floor(x), 3.0));
  float f = x - float(i);
  vec3 a = c[0], b = c[1];
  if (i == 1) { a = c[1]; b = c[2]; } else if (i == 2) { a = c[2]; b = c[3]; } else if (i == 3) { a = c[3]; b = c[4]; }
  return mix(a, b, f);
}
// An anti-aliased square wave: 0 or 1 by the sign of sin(2πs), blurred over one pixel.
float wave(float s) {
  float w = sin(2.0 * PI * s);
  float aa = max(fwidth(w), 1e-4);
  return smoothstep(-aa, aa, w);
}
void main() {
  vec3 n = normalize(vN);
  vec3 v = normalize(-vP);
  if (dot(n, v) < 0.0) n = -n; // two-sided: the side facing the eye
  vec3 key = normalize(vec3(-0.4, 0.6, 0.7));
  vec3 fill = normalize(vec3(0.6, -0.4, 0.5));
  float d1 = max(dot(n, key), 0.0), d2 = max(dot(n, fill), 0.0);
  float spec = pow(max(dot(n, normalize(key + v)), 0.0), 40.0);
  float light = 0.28 + 0.62 * d1 + 0.22 * d2;
  vec3 c;
  if (mode == 1) {
    c = ramp(diverging, 0.5 + 0.5 * vS / range) * (0.55 + 0.45 * light) + 0.12 * spec;
  } else if (mode == 2) {
    c = ramp(sequential, vS / range) * (0.55 + 0.45 * light) + 0.12 * spec;
  } else if (mode == 3) {
    // Reflection lines: the reflected view ray's angle about the world's up axis.
    vec3 r = viewToWorld * reflect(-v, n);
    float s = atan(dot(r, across2), dot(r, across1)) / (2.0 * PI) * stripes;
    c = vec3(mix(0.06, 0.97, wave(s)));
  } else if (mode == 4) {
    // Isophotes: bands of constant n·L for the key light.
    float s = dot(n, key) * bands * 0.5;
    c = mix(vec3(0.15, 0.18, 0.3), vec3(0.95, 0.93, 0.85), wave(s)) * (0.75 + 0.25 * d1);
  } else {
    c = vec3(0.62, 0.68, 0.80) * light + 0.25 * spec;
  }
  gl_FragColor = vec4(c, 1.0);
}`;

const toVec3 = (rgb) => new THREE.Vector3(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255);
const stage = document.getElementById('stage');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
renderer.setClearColor(0xffffff, 1);
stage.appendChild(renderer.domElement);

// One scene, camera and material a view.
const views = data.views.map((v) => {
  const positions = decode(v.positions, Float32Array);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('normal', new THREE.BufferAttribute(decode(v.normals, Float32Array), 3));
  geometry.setIndex(new THREE.BufferAttribute(decode(v.indices, Uint32Array), 1));
  const scalars = {};
  for (const s of v.scalars) scalars[s.name] = new THREE.BufferAttribute(decode(s.values, Float32Array), 1);
  if (v.distance != null) scalars.distance = new THREE.BufferAttribute(decode(v.distance, Float32Array), 1);
  const zeros = new THREE.BufferAttribute(new Float32Array(v.vertices), 1);
  geometry.setAttribute('scalar', zeros);
  const material = new THREE.ShaderMaterial({
    vertexShader, fragmentShader, side: THREE.DoubleSide,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1, // lines drawn on top
    uniforms: {
      mode: { value: 0 }, range: { value: 1 }, stripes: { value: STRIPES }, bands: { value: BANDS },
      diverging: { value: DIVERGING.map(toVec3) }, sequential: { value: SEQUENTIAL.map(toVec3) },
      viewToWorld: { value: new THREE.Matrix3() },
      across1: { value: new THREE.Vector3() }, across2: { value: new THREE.Vector3() },
    },
  });
  const scene = new THREE.Scene();
  scene.add(new THREE.Mesh(geometry, material));
  const lines = {};
  for (const t of toggles) {
    if (v[t] == null) continue;
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(decode(v[t], Float32Array), 3));
    // Nets are dense (a quartic's is 30 segments a patch): drawn see-through.
    const see = t === 'nets' ? { transparent: true, opacity: 0.55 } : {};
    lines[t] = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: LINE_COLOURS[t], ...see }));
    scene.add(lines[t]);
  }
  // The bounding sphere: centre of the box, radius the farthest vertex from it.
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i++) { const k = i % 3; lo[k] = Math.min(lo[k], positions[i]); hi[k] = Math.max(hi[k], positions[i]); }
  const center = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  let r2 = 0;
  for (let i = 0; i < positions.length; i += 3) {
    const dx = positions[i] - center.x, dy = positions[i + 1] - center.y, dz = positions[i + 2] - center.z;
    r2 = Math.max(r2, dx * dx + dy * dy + dz * dz);
  }
  const camera = new THREE.PerspectiveCamera(FOV_DEG, 1, 0.01, 100);
  const title = document.createElement('div');
  title.className = 'title';
  stage.appendChild(title);
  return { spec: v, geometry, material, scalars, zeros, lines, scene, camera, center, radius: Math.sqrt(r2) || 1, title, cell: null };
});

// The linked camera: one state for all views, each relative to its own bounding sphere.
const defaults = () => ({ yaw: DEFAULT_YAW, pitch: DEFAULT_PITCH, zoom: 1, panX: 0, panY: 0 });
let cam = defaults();
let mode = 'shaded';
// The up axis and two across it, right-handed (e1 × e2 = up): z up (the workbench's data) or y.
const BASES = {
  z: [new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 1, 0), new THREE.Vector3(0, 0, 1)],
  y: [new THREE.Vector3(0, 0, 1), new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 1, 0)],
};
let basis = BASES[data.up] || BASES.z;
const shown = { boundaries: true, nets: false, data_mesh: false };

function layout() {
  const w = stage.clientWidth, h = stage.clientHeight;
  renderer.setSize(w, h, false);
  const n = views.length, cols = Math.ceil(Math.sqrt(n)), rows = Math.ceil(n / cols);
  views.forEach((v, i) => {
    const c = i % cols, r = Math.floor(i / cols);
    const x = Math.round((c * w) / cols), y = Math.round((r * h) / rows);
    v.cell = { x, y, w: Math.round(((c + 1) * w) / cols) - x, h: Math.round(((r + 1) * h) / rows) - y };
    v.title.style.left = x + 'px';
    v.title.style.top = y + 'px';
  });
}

function placeCamera(v) {
  const { camera, center, radius, cell } = v;
  camera.aspect = cell.w / Math.max(cell.h, 1);
  const halfY = (FOV_DEG * Math.PI) / 360;
  const halfX = Math.atan(Math.tan(halfY) * camera.aspect);
  const dist = (radius * FIT_MARGIN) / Math.sin(Math.min(halfX, halfY)) / cam.zoom;
  const yaw = (cam.yaw * Math.PI) / 180, pitch = (cam.pitch * Math.PI) / 180;
  const [e1, e2, e3] = basis;
  const dir = new THREE.Vector3()
    .addScaledVector(e1, Math.cos(pitch) * Math.cos(yaw))
    .addScaledVector(e2, Math.cos(pitch) * Math.sin(yaw))
    .addScaledVector(e3, Math.sin(pitch));
  const right = new THREE.Vector3().addScaledVector(e1, -Math.sin(yaw)).addScaledVector(e2, Math.cos(yaw));
  const up = new THREE.Vector3().crossVectors(dir, right).negate();
  camera.up.copy(e3);
  v.material.uniforms.across1.value.copy(e1);
  v.material.uniforms.across2.value.copy(e2);
  const target = center.clone().addScaledVector(right, cam.panX * radius).addScaledVector(up, cam.panY * radius);
  camera.position.copy(target).addScaledVector(dir, dist);
  camera.lookAt(target);
  camera.near = Math.max(dist - 2 * radius, radius * 1e-3);
  camera.far = dist + 2 * radius;
  camera.updateProjectionMatrix();
  camera.updateMatrixWorld();
  v.material.uniforms.viewToWorld.value.setFromMatrix4(camera.matrixWorld);
}

function applyMode(v) {
  const u = v.material.uniforms;
  const attr = v.scalars[mode];
  const scalarMode = scalarNames.includes(mode) || mode === 'distance';
  v.geometry.setAttribute('scalar', scalarMode && attr ? attr : v.zeros);
  if (scalarMode) {
    u.mode.value = attr ? (mode === 'distance' ? 2 : 1) : 0;
    u.range.value = data.ranges[mode] ? data.ranges[mode].range : 1;
  } else {
    u.mode.value = { shaded: 0, zebra: 3, isophotes: 4 }[mode];
  }
  v.title.textContent = v.spec.title + (scalarMode && !attr ? ` (no ${mode})` : '');
  for (const t in v.lines) v.lines[t].visible = shown[t];
}

function colourbar() {
  const bar = document.getElementById('colorbar');
  const r = data.ranges[mode];
  if (!r || mode === 'shaded') { bar.style.display = 'none'; return; }
  const stops = mode === 'distance' ? SEQUENTIAL : DIVERGING;
  const fmt = (x) => (Math.abs(x) < 1e-3 || Math.abs(x) >= 1e4) && x !== 0 ? x.toExponential(2) : +x.toPrecision(3) + '';
  bar.style.display = 'block';
  bar.querySelector('.name').textContent = mode === 'distance' ? 'distance to the true surface' : mode;
  bar.querySelector('.ramp').style.background =
    `linear-gradient(to right, ${stops.map((s, i) => `rgb(${s}) ${i * 25}%`).join(', ')})`;
  const lo = mode === 'distance' ? 0 : -r.range;
  bar.querySelector('.lo').textContent = fmt(lo);
  bar.querySelector('.mid').textContent = fmt((lo + r.range) / 2);
  bar.querySelector('.hi').textContent = fmt(r.range);
  bar.querySelector('.note').textContent = r.max > r.range
    ? `clipped at the views' median ${Math.round(r.quantile * 100)}th percentile of |${mode}|; max ${fmt(r.max)}` : '';
}

function draw() {
  layout();
  renderer.setScissorTest(true);
  const H = stage.clientHeight;
  for (const v of views) {
    applyMode(v);
    placeCamera(v);
    const { x, y, w, h } = v.cell;
    renderer.setViewport(x, H - y - h, w, h);
    renderer.setScissor(x, H - y - h, w, h);
    renderer.render(v.scene, v.camera);
  }
  colourbar();
  for (const b of document.querySelectorAll('#bar button')) b.classList.toggle('on', b.dataset.mode === mode);
  for (const c of document.querySelectorAll('#bar input')) c.checked = shown[c.dataset.toggle];
  setStatus('ready:' + mode);
}

let pending = false;
function redraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); });
}

// Toolbar.
const bar = document.getElementById('bar');
for (const m of modes) {
  const b = document.createElement('button');
  b.textContent = { k1: 'κ1', k2: 'κ2', zebra: 'reflection lines' }[m] || m;
  b.dataset.mode = m;
  b.onclick = () => { mode = m; redraw(); };
  bar.appendChild(b);
}
for (const t of toggles) {
  const l = document.createElement('label');
  const c = document.createElement('input');
  c.type = 'checkbox';
  c.dataset.toggle = t;
  c.onchange = () => { shown[t] = c.checked; redraw(); };
  l.append(c, ' ' + toggleLabels[t]);
  bar.appendChild(l);
}
const reset = document.createElement('button');
reset.textContent = 'reset view';
reset.onclick = () => { cam = defaults(); redraw(); };
bar.appendChild(reset);

// Mouse: drag turns, shift- or right-drag pans, the wheel zooms; the state is shared, so every
// view follows whichever one is dragged.
const canvas = renderer.domElement;
let dragging = null;
canvas.addEventListener('contextmenu', (e) => e.preventDefault());
canvas.addEventListener('pointerdown', (e) => {
  dragging = { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 || e.button === 1 };
});
window.addEventListener('pointermove', (e) => {
  if (!dragging) return;
  const dx = e.clientX - dragging.x, dy = e.clientY - dragging.y;
  dragging.x = e.clientX;
  dragging.y = e.clientY;
  if (dragging.pan) {
    const cell = views[0].cell;
    const scale = (2 * FIT_MARGIN) / cam.zoom / Math.max(cell.h, 1);
    cam.panX -= dx * scale;
    cam.panY += dy * scale;
  } else {
    cam.yaw -= dx * TURN_PER_PX;
    cam.pitch = Math.max(-89, Math.min(89, cam.pitch + dy * TILT_PER_PX));
  }
  redraw();
});
window.addEventListener('pointerup', () => { dragging = null; });
canvas.addEventListener('wheel', (e) => {
  e.preventDefault();
  cam.zoom *= Math.exp(-e.deltaY * ZOOM_PER_WHEEL);
  redraw();
}, { passive: false });

// The hash: #mode=K&turn=30&tilt=10&zoom=1.5&pan=0.1,0&boundaries=1&nets=0&mesh=1&up=y&ui=0&drag=0:120:0[:pan]&wheel=0:-300
function applyHash() {
  const h = new URLSearchParams(location.hash.slice(1));
  cam = defaults();
  // `reflection` and `reflection-lines` name the zebra mode too (the renderer's and the
  // command line's word for it).
  const alias = { reflection: 'zebra', 'reflection-lines': 'zebra' };
  const asked = h.get('mode');
  const want = asked == null ? null : alias[asked.toLowerCase()] || asked;
  if (want != null) {
    const m = modes.find((x) => x === want) || modes.find((x) => x.toLowerCase() === want.toLowerCase());
    if (!m) throw new Error(`unknown mode "${want}" (modes: ${modes.join(', ')})`);
    mode = m;
  }
  const num = (k, d) => (h.has(k) ? Number(h.get(k)) : d);
  cam.yaw += num('turn', 0);
  cam.pitch = Math.max(-89, Math.min(89, cam.pitch + num('tilt', 0)));
  cam.zoom = num('zoom', 1);
  const upName = h.get('up') || data.up;
  if (!BASES[upName]) throw new Error(`unknown up axis "${upName}" (z or y)`);
  basis = BASES[upName];
  if (h.has('pan')) [cam.panX, cam.panY] = h.get('pan').split(',').map(Number);
  for (const t of toggles) if (h.has(hashToggle[t])) shown[t] = h.get(hashToggle[t]) === '1';
  const bare = h.get('ui') === '0';
  bar.style.display = bare ? 'none' : '';
  stage.style.top = bare ? '0' : '';
  for (const v of views) v.title.style.display = bare ? 'none' : '';
  if (bare) document.getElementById('colorbar').style.visibility = 'hidden';
  draw();
  if (h.has('drag')) {
    // A drag replayed through the mouse handlers: view index, pixels right and down, and
    // `pan` as a fourth field for a shift-drag.
    const [si, sdx, sdy, kind] = h.get('drag').split(':');
    const [i, dx, dy] = [si, sdx, sdy].map(Number);
    const v = views[i];
    if (!v) throw new Error(`drag: no view ${i}`);
    if (kind !== undefined && kind !== 'pan') throw new Error(`drag: unknown kind "${kind}" (pan)`);
    const r = canvas.getBoundingClientRect();
    const x0 = r.left + v.cell.x + v.cell.w / 2, y0 = r.top + v.cell.y + v.cell.h / 2;
    const shiftKey = kind === 'pan';
    const ev = (type, x, y) => new PointerEvent(type, { clientX: x, clientY: y, button: 0, buttons: 1, shiftKey, bubbles: true });
    canvas.dispatchEvent(ev('pointerdown', x0, y0));
    const steps = 10;
    for (let s = 1; s <= steps; s++) window.dispatchEvent(ev('pointermove', x0 + (dx * s) / steps, y0 + (dy * s) / steps));
    window.dispatchEvent(ev('pointerup', x0 + dx, y0 + dy));
    draw();
  }
  if (h.has('wheel')) {
    // Wheel steps replayed through the wheel handler: view index, then deltaY (negative
    // zooms in).
    const [i, dy] = h.get('wheel').split(':').map(Number);
    const v = views[i];
    if (!v) throw new Error(`wheel: no view ${i}`);
    const r = canvas.getBoundingClientRect();
    const x0 = r.left + v.cell.x + v.cell.w / 2, y0 = r.top + v.cell.y + v.cell.h / 2;
    canvas.dispatchEvent(new WheelEvent('wheel', { clientX: x0, clientY: y0, deltaY: dy, bubbles: true, cancelable: true }));
    draw();
  }
}
window.addEventListener('hashchange', applyHash);
window.addEventListener('resize', redraw);
applyHash();
