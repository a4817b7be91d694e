// The page strata view and strata-view serve: one three.js scene fed by the server's WebSocket.
// Wire format (apps/view/scene.h states it for the server): each binary message is a little-endian
// u32 header length L, L bytes of JSON, zero padding to a multiple of 4, then the payload; the
// header's "arrays" name each typed array of the payload: {name, type: f32|u32|u8, count, offset}
// (offset from the payload's start). The page answers with text JSON: a distance query at a clicked
// point and the ESDF slice height. window.strata holds what the tests read (counts, the last pose,
// errors, latencies).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { CSS2DRenderer, CSS2DObject } from 'three/examples/jsm/renderers/CSS2DRenderer.js';

const state = {
  connected: false,
  hello: null,
  meshes: 0,
  triangles: 0,
  vertices: 0,
  objects: 0,
  stats: {},
  lastPose: null,
  trajectoryPoints: 0,
  pathPoints: 0,
  slice: null,
  lastAnswer: null,
  latenciesMs: [],
  messages: 0,
  meshMessages: 0,  // mesh items put or removed
  errors: [],
  framesDrawn: 0,
  fps: 0,
  firstSceneDrawn: false,
  synced: false,
};
window.strata = state;

const canvas = document.getElementById('scene');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2126);
const camera = new THREE.PerspectiveCamera(55, 1, 0.02, 500);
camera.up.set(0, 0, 1);  // Strata's world frame is z-up
camera.position.set(4, -4, 4);
// Object labels: HTML over the canvas, placed by three's CSS2D renderer.
const labelRenderer = new CSS2DRenderer();
labelRenderer.domElement.className = 'labels';
document.body.appendChild(labelRenderer.domElement);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = false;
scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
sun.position.set(3, -2, 6);
scene.add(sun);

const groups = { map: new THREE.Group(), session: new THREE.Group(), object: new THREE.Group(), overlay: new THREE.Group() };
groups.session.visible = false;
for (const g of Object.values(groups)) scene.add(g);
const items = new Map();  // id -> THREE.Object3D
const sessionPalette = [0x8fb3d9, 0xe3a35f, 0x8fcf8f, 0xd98fb3, 0xc9c27a, 0x9a8fd9, 0x6fc6c6];
let colourMode = 'map';
let framed = false;

function resize() {
  const w = window.innerWidth, h = window.innerHeight;
  renderer.setSize(w, h, false);
  labelRenderer.setSize(w, h);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

window.addEventListener('error', (e) => state.errors.push(String(e.message)));

function parseMessage(buffer) {
  const view = new DataView(buffer);
  const headerLength = view.getUint32(0, true);
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, headerLength)));
  const payload = (4 + headerLength + 3) & ~3;
  const arrays = {};
  for (const a of header.arrays || []) {
    const start = payload + a.offset;
    if (a.type === 'f32') arrays[a.name] = new Float32Array(buffer, start, a.count);
    else if (a.type === 'u32') arrays[a.name] = new Uint32Array(buffer, start, a.count);
    else if (a.type === 'u8') arrays[a.name] = new Uint8Array(buffer, start, a.count);
    else throw new Error(`unknown array type ${a.type}`);
  }
  return { header, arrays };
}

function disposeItem(id) {
  const old = items.get(id);
  if (!old) return;
  old.parent.remove(old);
  old.traverse((o) => {
    if (o.isCSS2DObject && o.element.parentNode) o.element.parentNode.removeChild(o.element);
    if (o.geometry) o.geometry.dispose();
    if (o.material) {
      if (o.material.map) o.material.map.dispose();
      o.material.dispose();
    }
  });
  items.delete(id);
}

function meshMaterial(header, hasColours) {
  if (colourMode === 'session' && header.session !== undefined) {
    return new THREE.MeshLambertMaterial({ color: sessionPalette[header.session % sessionPalette.length], side: THREE.DoubleSide });
  }
  if (hasColours) return new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
  const c = header.color ? new THREE.Color(header.color[0] / 255, header.color[1] / 255, header.color[2] / 255) : new THREE.Color(0xb0b0b0);
  return new THREE.MeshLambertMaterial({ color: c, side: THREE.DoubleSide });
}

function onMesh(header, arrays) {
  disposeItem(header.id);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(arrays.positions, 3));
  const hasColours = !!arrays.colors;
  if (hasColours) geometry.setAttribute('color', new THREE.BufferAttribute(arrays.colors, 3, true));
  geometry.setIndex(new THREE.BufferAttribute(arrays.indices, 1));
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  const mesh = new THREE.Mesh(geometry, meshMaterial(header, hasColours));
  mesh.userData = header;
  const group = groups[header.group] || groups.map;
  group.add(mesh);
  items.set(header.id, mesh);
}

function onObjects(header) {
  disposeItem('objects');
  const g = new THREE.Group();
  for (const o of header.items) {
    const min = new THREE.Vector3(...o.min), max = new THREE.Vector3(...o.max);
    const colour = o.session !== undefined ? new THREE.Color(sessionPalette[o.session % sessionPalette.length])
      : new THREE.Color(...(o.color || [255, 220, 0]).map((v) => v / 255));
    const box = new THREE.Box3Helper(new THREE.Box3(min, max), colour);
    box.userData = o;
    g.add(box);
    const div = document.createElement('div');
    div.className = 'label';
    div.textContent = o.label || `object ${o.id}`;
    const label = new CSS2DObject(div);
    label.position.set((min.x + max.x) / 2, (min.y + max.y) / 2, max.z + 0.05);
    g.add(label);
  }
  groups.object.add(g);
  items.set('objects', g);
  state.objects = header.items.length;
}

function lineItem(id, points, colour, group) {
  disposeItem(id);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
  const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: colour }));
  group.add(line);
  items.set(id, line);
}

// A camera frustum from T_W_C (row-major 4x4) and intrinsics, 0.3 m deep.
function onPose(header) {
  const T = header.T_W_C;
  const m = new THREE.Matrix4().set(...T);
  const k = header.intrinsics || { width: 640, height: 480, fx: 525, fy: 525, cx: 319.5, cy: 239.5 };
  const d = 0.3;
  const corners = [[0, 0], [k.width, 0], [k.width, k.height], [0, k.height]].map(([u, v]) =>
    new THREE.Vector3((u - k.cx) / k.fx * d, (v - k.cy) / k.fy * d, d).applyMatrix4(m));
  const o = new THREE.Vector3(0, 0, 0).applyMatrix4(m);
  const p = [];
  for (let i = 0; i < 4; ++i) {
    p.push(o, corners[i], corners[i], corners[(i + 1) % 4]);
  }
  disposeItem(`pose:${header.id}`);
  const geometry = new THREE.BufferGeometry().setFromPoints(p);
  const frustum = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: 0xffd24a }));
  groups.overlay.add(frustum);
  items.set(`pose:${header.id}`, frustum);
  state.lastPose = { id: header.id, T_W_C: T, t: header.t };
}

// Turbo-like colour map for distances: near red, far blue; unknown cells transparent.
function colourOf(x) {
  const t = Math.min(Math.max(x, 0), 1);
  const r = Math.round(255 * Math.min(Math.max(1.5 - Math.abs(4 * t - 1), 0), 1));
  const g = Math.round(255 * Math.min(Math.max(1.5 - Math.abs(4 * t - 2), 0), 1));
  const b = Math.round(255 * Math.min(Math.max(1.5 - Math.abs(4 * t - 3), 0), 1));
  return [r, g, b];
}

function drawColourBar(min, max) {
  const c = document.getElementById('colourbar-canvas');
  const ctx = c.getContext('2d');
  for (let x = 0; x < c.width; ++x) {
    const [r, g, b] = colourOf(x / (c.width - 1));
    ctx.fillStyle = `rgb(${r},${g},${b})`;
    ctx.fillRect(x, 0, 1, c.height);
  }
  document.getElementById('cb-min').textContent = `${min.toFixed(2)} m`;
  document.getElementById('cb-max').textContent = `${max.toFixed(2)} m`;
}

function onSlice(header, arrays) {
  const { width, height, resolution, origin, z } = header;
  const values = arrays.distances;
  const max = header.max > 0 ? header.max : 1;
  const rgba = new Uint8Array(width * height * 4);
  let known = 0;
  for (let i = 0; i < width * height; ++i) {
    const v = values[i];
    if (Number.isNaN(v)) continue;
    const [r, g, b] = colourOf(v / max);
    rgba.set([r, g, b, 200], 4 * i);
    ++known;
  }
  const texture = new THREE.DataTexture(rgba, width, height, THREE.RGBAFormat);
  texture.needsUpdate = true;
  texture.magFilter = THREE.NearestFilter;
  disposeItem('esdf');
  const plane = new THREE.Mesh(new THREE.PlaneGeometry(width * resolution, height * resolution),
    new THREE.MeshBasicMaterial({ map: texture, transparent: true, side: THREE.DoubleSide, depthWrite: false }));
  plane.position.set(origin[0] + width * resolution / 2, origin[1] + height * resolution / 2, z);
  plane.visible = document.getElementById('show-esdf').checked;
  groups.overlay.add(plane);
  items.set('esdf', plane);
  drawColourBar(0, max);
  state.slice = { z, width, height, known };
}

function updateCounts() {
  let meshes = 0, triangles = 0, vertices = 0;
  for (const g of [groups.map, groups.session, groups.object]) {
    g.traverse((o) => {
      if (o.isMesh && o.geometry.index) {
        ++meshes;
        triangles += o.geometry.index.count / 3;
        vertices += o.geometry.attributes.position.count;
      }
    });
  }
  Object.assign(state, { meshes, triangles, vertices });
}

function frameScene() {
  const box = new THREE.Box3();
  for (const g of [groups.map, groups.session]) g.traverse((o) => { if (o.isMesh) box.expandByObject(o); });
  if (box.isEmpty()) return;
  const centre = box.getCenter(new THREE.Vector3());
  const size = box.getSize(new THREE.Vector3()).length();
  controls.target.copy(centre);
  camera.position.copy(centre).add(new THREE.Vector3(0.6 * size, -0.7 * size, 0.8 * size));
  camera.near = Math.max(size / 1000, 0.01);
  camera.far = size * 20;
  camera.updateProjectionMatrix();
  const slider = document.getElementById('slice-z');
  slider.min = (box.min.z).toFixed(2);
  slider.max = (box.max.z).toFixed(2);
  // A planner's height: a third of the way up the map (1 m in a 3 m room).
  slider.value = (box.min.z + (box.max.z - box.min.z) / 3).toFixed(2);
  sendSliceHeight();
  framed = true;
}

const statsTable = document.getElementById('stats');
function renderStats() {
  const rows = { fps: state.fps.toFixed(0), ...state.stats };
  if (state.latenciesMs.length) rows['latency ms'] = state.latenciesMs[state.latenciesMs.length - 1].toFixed(0);
  statsTable.innerHTML = '';
  for (const [k, v] of Object.entries(rows)) {
    const tr = statsTable.insertRow();
    tr.insertCell().textContent = k;
    tr.insertCell().textContent = typeof v === 'number' ? (Number.isInteger(v) ? v : v.toFixed(3)) : String(v);
  }
}

let socket = null;
let countsDirty = false;  // meshes changed since the counts were last taken (once per frame)
let pendingLatency = [];
function send(obj) {
  if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(obj));
}

function onMessage(event) {
  const { header, arrays } = parseMessage(event.data);
  ++state.messages;
  switch (header.type) {
    case 'hello':
      state.hello = header;
      sendSliceHeight();  // offline: the slice at the slider's height (live: the mapper's)
      document.getElementById('title').textContent = `Strata · ${header.title}`;
      // Without an ESDF (a run folder with no map) there is no slice to show or distance to read;
      // live, the mapper chooses the slice's height (the page cannot).
      for (const id of ['show-esdf', 'slice-z', 'colourbar', 'query']) {
        const el = document.getElementById(id);
        const hidden = header.esdf === false || (header.mode === 'live' && id === 'slice-z');
        (el.closest('label') || el).style.display = hidden ? 'none' : '';
      }
      break;
    case 'mesh': onMesh(header, arrays); break;
    case 'remove': disposeItem(header.id); break;
    case 'objects': onObjects(header); break;
    case 'pose': onPose(header); break;
    case 'trajectory': {
      // A session's trajectory in its session's colour; the VIO's cyan; the camera's own yellow.
      const session = /session_(\d+)/.exec(header.id);
      const colour = session ? sessionPalette[Number(session[1]) % sessionPalette.length]
        : header.id === 'vio' ? 0x4ad2ff : 0xffd24a;
      lineItem(`trajectory:${header.id}`, arrays.points, colour, groups.overlay);
      state.trajectoryPoints = arrays.points.length / 3;
      break;
    }
    case 'path':
      lineItem(`path:${header.id}`, arrays.points, 0x52ff7a, groups.overlay);
      state.pathPoints = arrays.points.length / 3;
      break;
    case 'esdf_slice': onSlice(header, arrays); break;
    case 'stats': state.stats = header.values; break;
    case 'answer': {
      state.lastAnswer = header;
      const q = document.getElementById('query');
      q.textContent = header.known
        ? `(${header.point.map((v) => v.toFixed(2)).join(', ')}): ${header.distance.toFixed(3)} m to the nearest obstacle`
        : `(${header.point.map((v) => v.toFixed(2)).join(', ')}): not observed`;
      break;
    }
    case 'error': state.errors.push(`server: ${header.message}`); break;
    case 'synced':
      // The scene as it stood at connection is all here: frame it (again, now whole).
      framed = false;
      state.synced = true;
      state.firstSceneDrawn = false;
      break;
    default: state.errors.push(`unknown message type ${header.type}`);
  }
  if (header.t_pub_us !== undefined) pendingLatency.push(header.t_pub_us);
  if (header.type === 'mesh' || header.type === 'remove') {
    countsDirty = true;
    ++state.meshMessages;
  }
}

function connect() {
  const url = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`;
  socket = new WebSocket(url);
  socket.binaryType = 'arraybuffer';
  socket.onopen = () => {
    state.connected = true;
    document.getElementById('status').textContent = `connected to ${location.host}`;
  };
  socket.onclose = () => {
    state.connected = false;
    state.synced = false;
    document.getElementById('status').textContent = 'disconnected; retrying';
    setTimeout(connect, 1000);
  };
  socket.onmessage = onMessage;
}

function sendSliceHeight(exact) {
  if (state.hello && state.hello.mode === 'live') return;  // the mapper's slice, at its height
  // The slider snaps to its step; a height given exactly (from a script) is sent as it is.
  const z = typeof exact === 'number' ? exact : parseFloat(document.getElementById('slice-z').value);
  document.getElementById('slice-z-value').textContent = `${z.toFixed(2)} m`;
  send({ type: 'slice', z });
}

document.getElementById('slice-z').addEventListener('change', () => sendSliceHeight());
document.getElementById('slice-z').addEventListener('input', () => {
  document.getElementById('slice-z-value').textContent = `${parseFloat(document.getElementById('slice-z').value).toFixed(2)} m`;
});
document.getElementById('show-esdf').addEventListener('change', (e) => {
  const s = items.get('esdf');
  if (s) s.visible = e.target.checked;
});
document.getElementById('show-objects').addEventListener('change', (e) => { groups.object.visible = e.target.checked; });
document.getElementById('colour').addEventListener('change', (e) => {
  colourMode = e.target.value;
  // By session: each session's own map in its colour where the run has them, instead of the map.
  const bySession = colourMode === 'session' && groups.session.children.length > 0;
  groups.session.visible = bySession;
  groups.map.visible = !bySession;
  for (const g of [groups.map, groups.session, groups.object]) {
    g.traverse((o) => {
      if (o.isMesh) {
        o.material.dispose();
        o.material = meshMaterial(o.userData, !!o.geometry.attributes.color);
      }
    });
  }
});
document.getElementById('screenshot').addEventListener('click', () => {
  const a = document.createElement('a');
  a.href = canvas.toDataURL('image/png');
  a.download = 'strata-view.png';
  a.click();
});

// Click on a surface: the server answers the distance to the nearest obstacle from its ESDF.
let queryId = 0;
const raycaster = new THREE.Raycaster();
let downAt = null;
canvas.addEventListener('pointerdown', (e) => { downAt = [e.clientX, e.clientY]; });
canvas.addEventListener('pointerup', (e) => {
  if (!downAt || Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) > 4) return;  // a drag
  const ndc = new THREE.Vector2((e.clientX / window.innerWidth) * 2 - 1, -(e.clientY / window.innerHeight) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const visible = [groups.map, groups.session, groups.object].filter((g) => g.visible);
  const hits = raycaster.intersectObjects(visible, true).filter((h) => h.object.isMesh && h.object.visible);
  if (!hits.length) return;
  const p = hits[0].point;
  send({ type: 'query', id: ++queryId, point: [p.x, p.y, p.z] });
});
// Orbit the camera about the view's centre (z axis) by `radians`: benchmarks drive the view with it.
window.strataOrbitStep = (radians) => {
  const offset = camera.position.clone().sub(controls.target);
  offset.applyAxisAngle(new THREE.Vector3(0, 0, 1), radians);
  camera.position.copy(controls.target).add(offset);
  camera.lookAt(controls.target);
};
// The same from a test or the console: a point in the world frame.
window.strataQuery = (point) => send({ type: 'query', id: ++queryId, point });
window.strataSetSlice = (z) => {
  document.getElementById('slice-z').value = String(z);
  sendSliceHeight(z);
};

let fpsFrames = 0, fpsStart = performance.now();
function animate() {
  requestAnimationFrame(animate);
  if (countsDirty) {
    updateCounts();
    countsDirty = false;
  }
  if (!framed && (groups.map.children.length || groups.session.children.length)) frameScene();
  controls.update();
  renderer.render(scene, camera);
  labelRenderer.render(scene, camera);
  ++state.framesDrawn;
  ++fpsFrames;
  if (state.meshes > 0 && state.synced) state.firstSceneDrawn = true;
  if (pendingLatency.length) {
    const now = performance.timeOrigin + performance.now();
    for (const t of pendingLatency) state.latenciesMs.push(now - t / 1000);
    if (state.latenciesMs.length > 10000) state.latenciesMs.splice(0, state.latenciesMs.length - 10000);
    pendingLatency = [];
  }
  const elapsed = performance.now() - fpsStart;
  if (elapsed > 1000) {
    state.fps = (fpsFrames * 1000) / elapsed;
    fpsFrames = 0;
    fpsStart = performance.now();
    renderStats();
  }
}
connect();
animate();
