// The live view's page: draws the frames the run sends over its WebSocket
// (message layouts in doc/live_view.md) with three.js r111, and sends the
// driving page's commands back.
'use strict';

const units = {
  'displacement': 'length units',
  'J': 'det F (volume ratio)',
  'von Mises': 'stress units',
  'contact pressure': 'stress units',
};

const view = {
  scene: null,      // the run's greeting
  drives: false,
  topology: null,   // {n, reference: Float32Array}
  pending: null,    // the newest frame not yet drawn
  lastStep: -1,
  fresh: 0,         // frames with a new step drawn in the current second
  freshPerSecond: 0,
  framesReceived: 0,
  bytesPerFrame: 0,
  ended: false,
  history: [],      // per frame: [step ms, budget ms, rate, stored, kinetic]
};
// For tests and benchmarks (headless browser): what the page has drawn.
window.tissuefem = view;

const $ = (id) => document.getElementById(id);
const container = $('view');
// No multisampling: with software WebGL (headless, or no GPU) it costs more
// than the frame rate can spare.
const renderer = new THREE.WebGLRenderer({antialias: false});
renderer.setPixelRatio(window.devicePixelRatio);
container.appendChild(renderer.domElement);
const scene3 = new THREE.Scene();
scene3.background = new THREE.Color(0x1d2026);
const camera = new THREE.PerspectiveCamera(40, 1, 1e-3, 1e3);
const controls = new THREE.OrbitControls(camera, renderer.domElement);
scene3.add(new THREE.HemisphereLight(0xffffff, 0x303040, 0.7));
const sun = new THREE.DirectionalLight(0xffffff, 0.6);
camera.add(sun);
sun.position.set(1, 1, 2);
scene3.add(camera);

let mesh = null, outline = null;

function resize() {
  const w = container.clientWidth, h = container.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

// A perceptually ordered colour map (viridis, 5 stops, linear between).
const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
function colour(s, out, i) {
  s = Math.min(Math.max(s, 0), 1) * (stops.length - 1);
  const k = Math.min(Math.floor(s), stops.length - 2), f = s - k;
  for (let c = 0; c < 3; ++c)
    out[3 * i + c] = ((1 - f) * stops[k][c] + f * stops[k + 1][c]) / 255;
}
(function drawLegendBar() {
  const bar = $('legend-bar'), g = bar.getContext('2d'), rgb = new Float32Array(3);
  for (let x = 0; x < bar.width; ++x) {
    colour(x / (bar.width - 1), rgb, 0);
    g.fillStyle = `rgb(${255 * rgb[0]},${255 * rgb[1]},${255 * rgb[2]})`;
    g.fillRect(x, 0, 1, bar.height);
  }
})();

function setTopology(buffer) {
  const d = new DataView(buffer);
  const n = d.getUint32(4, true), m = d.getUint32(8, true);
  const reference = new Float32Array(buffer.slice(16, 16 + 12 * n));
  const index = new Uint32Array(buffer.slice(16 + 12 * n, 16 + 12 * n + 12 * m));
  if (mesh) { scene3.remove(mesh); mesh.geometry.dispose(); }
  if (outline) { scene3.remove(outline); outline.geometry.dispose(); }
  const geometry = new THREE.BufferGeometry();
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  geometry.setAttribute('position', new THREE.BufferAttribute(reference.slice(), 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
  geometry.computeVertexNormals();
  mesh = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({
    vertexColors: THREE.VertexColors, side: THREE.DoubleSide, shininess: 20}));
  scene3.add(mesh);
  const still = new THREE.BufferGeometry();
  still.setIndex(new THREE.BufferAttribute(index, 1));
  still.setAttribute('position', new THREE.BufferAttribute(reference, 3));
  outline = new THREE.LineSegments(new THREE.EdgesGeometry(still, 30),
                                   new THREE.LineBasicMaterial({color: 0x8899aa}));
  outline.visible = $('outline').checked;
  scene3.add(outline);
  setInstruments(d, 16 + 12 * n + 12 * m);
  view.topology = {n: n, triangles: m, reference: reference};
  // Frame the body, once (a new mesh or a reset keeps the user's view).
  geometry.computeBoundingSphere();
  if (view.framed) return;
  view.framed = true;
  const s = geometry.boundingSphere;
  controls.target.copy(s.center);
  camera.near = s.radius / 100;
  camera.far = s.radius * 100;
  camera.position.set(s.center.x + 0.3 * s.radius, s.center.y - 1.2 * s.radius,
                      s.center.z + 3 * s.radius);
  if (view.scene && view.scene.dimension === 2)
    camera.position.set(s.center.x, s.center.y, s.center.z + 3 * s.radius);
  camera.up.set(0, 1, 0);
  camera.updateProjectionMatrix();
  controls.update();
}

// The scene's obstacles and instruments (contact::Shape::drawing(), in
// each shape's frame), placed every frame by their poses; the contact tool
// the mouse moves (role 'mouse') is picked like the surface. Each tool
// shows the force of the tissue on it as an arrow from its centre.
const instruments = {meshes: [], arrows: [], centres: []};

function setInstruments(d, at) {
  for (const m of instruments.meshes) {
    scene3.remove(m); m.geometry.dispose(); m.material.dispose();
  }
  for (const a of instruments.arrows)
    if (a) { scene3.remove(a); a.line.material.dispose(); a.cone.material.dispose(); }
  instruments.meshes = []; instruments.arrows = []; instruments.centres = [];
  if (at + 4 > d.byteLength) return;
  const count = d.getUint32(at, true), roles = (view.scene && view.scene.obstacles) || [];
  at += 4;
  for (let k = 0; k < count; ++k) {
    const corners = d.getUint32(at, true), triangles = d.getUint32(at + 4, true);
    at += 8;
    const x = new Float32Array(d.buffer.slice(at, at + 12 * corners));
    at += 12 * corners;
    const index = new Uint32Array(d.buffer.slice(at, at + 12 * triangles));
    at += 12 * triangles;
    const role = roles[k] ? roles[k].role : 'obstacle', tool = role !== 'obstacle';
    const geometry = new THREE.BufferGeometry();
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.setAttribute('position', new THREE.BufferAttribute(x, 3));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    // Obstacles see-through, so that a floor or a wall hides nothing;
    // behind the tissue where they meet it (2D: the same plane).
    const shape = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({
      color: tool ? 0xc9ced6 : 0x6d7f99, side: THREE.DoubleSide, transparent: !tool,
      opacity: tool ? 1 : 0.45, shininess: tool ? 80 : 10, polygonOffset: true,
      polygonOffsetFactor: 1, polygonOffsetUnits: 1}));
    shape.matrixAutoUpdate = false;
    shape.userData = {role: role, name: roles[k] ? roles[k].name : '', offset: [0, 0, 0]};
    scene3.add(shape);
    instruments.meshes.push(shape);
    instruments.centres.push(geometry.boundingSphere.center.clone());
    instruments.arrows.push(tool ? forceArrow(0xffaa33) : null);
  }
}

function showInstruments(f) {
  const texts = [];
  view.toolForce = null;
  instruments.meshes.forEach((shape, k) => {
    const b = f.obstacles.subarray(19 * k, 19 * k + 19);
    if (b.length < 19) return;
    // x = t + R y, R row by row.
    shape.matrix.set(b[3], b[4], b[5], b[0], b[6], b[7], b[8], b[1], b[9], b[10], b[11], b[2],
                     0, 0, 0, 1);
    shape.matrixWorldNeedsUpdate = true;
    const arrow = instruments.arrows[k];
    if (!arrow) return;
    shape.userData.offset = [b[16], b[17], b[18]];
    view.toolOffset = shape.userData.offset;
    const size = Math.hypot(b[12], b[13], b[14]);
    view.toolForce = [b[12], b[13], b[14]];
    texts.push(shape.userData.name + ': ' + size.toPrecision(4) + ' force units' +
               (b[15] ? '' : ' (not touching)'));
    arrow.position.copy(instruments.centres[k]).applyMatrix4(shape.matrix);
    pointArrow(arrow, view.toolForce);
  });
  view.toolText = texts.join('; ') || 'no contact tool';
}

function decodeFrame(buffer) {
  const d = new DataView(buffer);
  const n = d.getUint32(8, true);
  const header = 20, numbers = [];
  for (let k = 0; k < 10; ++k) numbers.push(d.getFloat64(header + 8 * k, true));
  const at = header + 80;
  const field = d.getUint32(12, true);
  const mouseAt = at + 12 * n + (field > 0 ? 4 * n : 0);
  return {
    step: d.getUint32(4, true), n: n, field: field, flags: d.getUint32(16, true),
    time: numbers[0], dt: numbers[1], stepSeconds: numbers[2], stored: numbers[3],
    kinetic: numbers[4], rate: numbers[5], frameMs: numbers[6], budget: numbers[7],
    latencyMedian: numbers[8], latencyP99: numbers[9],
    u: new Float32Array(buffer, at, 3 * n),
    values: field > 0 ? new Float32Array(buffer, at + 12 * n, n) : null,
    mouse: new Float32Array(buffer, mouseAt, 10),
    obstacles: new Float32Array(buffer, mouseAt + 40,
                                Math.max(0, Math.floor((buffer.byteLength - mouseAt - 40) / 4))),
  };
}

function drawFrame(f) {
  if (!mesh || !view.topology || f.n !== view.topology.n) return;
  const position = mesh.geometry.attributes.position.array;
  const reference = view.topology.reference, rgb = mesh.geometry.attributes.color.array;
  let values = f.values;
  if (!values) {
    values = new Float32Array(f.n);
    for (let i = 0; i < f.n; ++i)
      values[i] = Math.hypot(f.u[3 * i], f.u[3 * i + 1], f.u[3 * i + 2]);
  }
  // The colour range: the 1st to 99th percentile, so that one hot spot (a
  // grasped or clamped corner) does not leave the rest in one colour.
  const sorted = Float32Array.from(values).sort();
  const lo = sorted[Math.floor(0.01 * (f.n - 1))], hi = sorted[Math.ceil(0.99 * (f.n - 1))];
  const span = hi > lo ? hi - lo : 1;
  for (let i = 0; i < 3 * f.n; ++i) position[i] = reference[i] + f.u[i];
  for (let i = 0; i < f.n; ++i) colour((values[i] - lo) / span, rgb, i);
  mesh.geometry.attributes.position.needsUpdate = true;
  mesh.geometry.attributes.color.needsUpdate = true;
  mesh.geometry.computeVertexNormals();
  // Picking and culling use it: it follows the body.
  mesh.geometry.computeBoundingSphere();
  if (f.step !== view.lastStep) {
    ++view.fresh;
    view.lastStep = f.step;
    view.history.push([1e3 * f.stepSeconds, 1e3 * f.budget, f.rate, f.stored, f.kinetic,
                       Math.max(f.latencyMedian, 0), Math.max(f.latencyP99, 0)]);
    if (view.history.length > 300) view.history.shift();
  }
  showForce(f);
  showInstruments(f);
  // The numbers at most 5 times a second: text layout costs frames.
  const now = performance.now();
  if (now - (view.lastText || 0) < 200 && !(f.flags & 1)) return;
  view.lastText = now;
  const name = view.scene ? view.scene.fields[f.field] : '';
  $('legend-min').textContent = lo.toPrecision(3);
  $('legend-max').textContent = hi.toPrecision(3);
  $('legend-unit').textContent = name + ' (' + (units[name] || '') + '), 1st-99th percentile';
  $('legend-range').textContent = 'whole range ' + sorted[0].toPrecision(3) + ' to ' +
                                  sorted[f.n - 1].toPrecision(3);
  $('n-step').textContent = f.step;
  $('n-time').textContent = f.time.toPrecision(6) + ' (time units)';
  $('n-wall').textContent = (1e3 * f.stepSeconds).toFixed(2) + ' ms (budget ' +
                            (1e3 * f.budget).toFixed(1) + ' ms)';
  $('n-rate').textContent = f.rate.toPrecision(3);
  $('n-stored').textContent = f.stored.toPrecision(4);
  $('n-kinetic').textContent = f.kinetic.toPrecision(4);
  $('n-latency').textContent = f.latencyMedian < 0 ? 'no device on the live port'
    : f.latencyMedian.toFixed(3) + ' / ' + f.latencyP99.toFixed(3) + ' ms';
  $('play').disabled = !view.drives || !(f.flags & 1);
  $('pause').disabled = !view.drives || (f.flags & 1);
  $('pace').value = (f.flags & 2) ? 'wall' : 'fast';
  $('n-force').textContent = view.forceText;
  $('n-tool').textContent = view.toolText;
}

// The mouse: dragging the surface grasps the tissue at the picked point
// (the run's 'mouse' tool), releasing lets go; dragging the contact tool
// moves it (it stays where it is let go); elsewhere the mouse orbits.
function forceArrow(colour) {
  const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, colour);
  a.visible = false;
  // The force on a tool points into the tissue: drawn over it.
  for (const part of [a.line, a.cone]) {
    part.material.depthTest = false;
    part.renderOrder = 10;
  }
  scene3.add(a);
  return a;
}
const arrow = forceArrow(0xff5533);
const drag = {active: false, start: null, plane: new THREE.Plane(), sent: null, tool: null};
view.force = [0, 0, 0];

function showForce(f) {
  const holding = f.mouse[0] !== 0;
  const force = [f.mouse[7], f.mouse[8], f.mouse[9]];
  view.force = holding ? force : [0, 0, 0];
  const size = Math.hypot(force[0], force[1], force[2]);
  view.forceText = holding ? size.toPrecision(4) + ' force units' : 'not grasping';
  if (!holding || !mesh || size === 0) { arrow.visible = false; return; }
  // From the grasped point as it is now (where the mouse put it).
  const nearest = nearestVertex(f.mouse[1], f.mouse[2], f.mouse[3]);
  const position = mesh.geometry.attributes.position.array;
  arrow.position.set(position[3 * nearest], position[3 * nearest + 1], position[3 * nearest + 2]);
  pointArrow(arrow, force);
}

// Shows @p arrow (placed) along @p force, a quarter of the body's size
// long; hidden for no force.
function pointArrow(arrow, force) {
  const size = Math.hypot(force[0], force[1], force[2]);
  if (size === 0 || !mesh) { arrow.visible = false; return; }
  arrow.setDirection(new THREE.Vector3(force[0], force[1], force[2]).normalize());
  const length = 0.25 * mesh.geometry.boundingSphere.radius;
  arrow.setLength(length, 0.25 * length, 0.12 * length);
  arrow.visible = true;
}

// The surface vertex nearest the reference point (x, y, z): searched once
// per grasp point and topology, not every frame.
const nearestCache = {key: null, topology: null, index: 0};
function nearestVertex(x, y, z) {
  const key = [x, y, z].join(' ');
  if (key === nearestCache.key && nearestCache.topology === view.topology)
    return nearestCache.index;
  const r = view.topology.reference;
  let best = 0, distance = Infinity;
  for (let i = 0; i < view.topology.n; ++i) {
    const d = (r[3 * i] - x) ** 2 + (r[3 * i + 1] - y) ** 2 + (r[3 * i + 2] - z) ** 2;
    if (d < distance) { distance = d; best = i; }
  }
  Object.assign(nearestCache, {key: key, topology: view.topology, index: best});
  return best;
}

function pointer(event) {
  const r = renderer.domElement.getBoundingClientRect();
  return new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1,
                           -((event.clientY - r.top) / r.height) * 2 + 1);
}
const raycaster = new THREE.Raycaster();

// Capture phase on the container: before the orbit controls see it.
container.addEventListener('mousedown', (event) => {
  if (event.button !== 0 || !mesh || !view.drives) return;
  const movable = instruments.meshes.filter((m) => m.userData.role === 'mouse');
  const targets = (view.mouseGrasps ? [mesh] : []).concat(movable);
  if (!targets.length) return;
  raycaster.setFromCamera(pointer(event), camera);
  const hit = raycaster.intersectObjects(targets)[0];
  if (!hit) return;
  event.stopPropagation();
  event.preventDefault();
  drag.active = true;
  drag.start = hit.point.clone();
  drag.plane.setFromNormalAndCoplanarPoint(camera.getWorldDirection(new THREE.Vector3()), hit.point);
  drag.sent = null;
  // The tool: offsets from where it is (its own motion plus the last).
  drag.tool = hit.object === mesh ? null : hit.object.userData.offset.slice();
  if (drag.tool) return;
  // The picked point in reference coordinates: the same barycentric
  // weights in the reference triangle.
  const position = mesh.geometry.attributes.position.array, x = view.topology.reference;
  const corner = (k) => new THREE.Vector3(position[3 * k], position[3 * k + 1], position[3 * k + 2]);
  const w = THREE.Triangle.getBarycoord(hit.point, corner(hit.face.a), corner(hit.face.b),
                                        corner(hit.face.c), new THREE.Vector3());
  const X = [0, 1, 2].map((d) => w.x * x[3 * hit.face.a + d] + w.y * x[3 * hit.face.b + d] +
                                 w.z * x[3 * hit.face.c + d]);
  send('grasp ' + X.join(' '));
}, true);

window.addEventListener('mousemove', (event) => {
  if (!drag.active) return;
  raycaster.setFromCamera(pointer(event), camera);
  const p = raycaster.ray.intersectPlane(drag.plane, new THREE.Vector3());
  if (p) drag.sent = p.sub(drag.start);
});

window.addEventListener('mouseup', () => {
  if (!drag.active) return;
  sendDrag();
  drag.active = false;
  if (!drag.tool) send('release');
});

// For scripts (tests, pictures): how much of the canvas is drawn (the share
// of pixels away from the background) and how many colours it has, read
// right after a render (the drawing buffer is not kept).
view.pixelStatistics = () => {
  renderer.render(scene3, camera);
  const source = renderer.domElement, c = document.createElement('canvas');
  c.width = source.width; c.height = source.height;
  const g = c.getContext('2d');
  g.drawImage(source, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let differing = 0;
  const colours = new Set();
  for (let i = 0; i < d.length; i += 4) {
    if (Math.abs(d[i] - 0x1d) + Math.abs(d[i + 1] - 0x20) + Math.abs(d[i + 2] - 0x26) > 30) ++differing;
    colours.add((d[i] >> 3) * 1024 + (d[i + 1] >> 3) * 32 + (d[i + 2] >> 3));
  }
  return {share: differing / (d.length / 4), colours: colours.size};
};

// For scripts (tests, pictures): the page coordinates of a point of the
// drawn surface, the one nearest the canvas's centre on a grid of rays.
view.surfacePoint = () => {
  if (!mesh) return null;
  const r = renderer.domElement.getBoundingClientRect();
  let best = null;
  for (let i = 1; i < 40; ++i)
    for (let j = 1; j < 40; ++j) {
      raycaster.setFromCamera(new THREE.Vector2(i / 20 - 1, j / 20 - 1), camera);
      if (!raycaster.intersectObject(mesh).length) continue;
      const d = (i - 20) ** 2 + (j - 20) ** 2;
      if (!best || d < best.d)
        best = {d: d, x: r.left + (i / 40) * r.width, y: r.top + (1 - j / 40) * r.height};
    }
  return best && {x: best.x, y: best.y};
};

// For scripts (tests, pictures): the page coordinates of the centre of the
// instrument the mouse moves, and the colour drawn at page coordinates.
view.instrumentPoint = () => {
  const k = instruments.meshes.findIndex((m) => m.userData.role === 'mouse');
  if (k < 0) return null;
  const p = instruments.centres[k].clone().applyMatrix4(instruments.meshes[k].matrix).project(camera);
  const r = renderer.domElement.getBoundingClientRect();
  return {x: r.left + (p.x + 1) / 2 * r.width, y: r.top + (1 - p.y) / 2 * r.height};
};
view.colourAt = (x, y) => {
  renderer.render(scene3, camera);
  const source = renderer.domElement, r = source.getBoundingClientRect();
  const c = document.createElement('canvas');
  c.width = source.width; c.height = source.height;
  c.getContext('2d').drawImage(source, 0, 0);
  const d = c.getContext('2d').getImageData(Math.round((x - r.left) * source.width / r.width),
                                            Math.round((y - r.top) * source.height / r.height), 1, 1).data;
  return [d[0], d[1], d[2]];
};

// At most one drag message per animation frame.
function sendDrag() {
  if (drag.active && drag.sent) {
    const t = drag.tool, s = drag.sent;
    send(t ? 'tool ' + (t[0] + s.x) + ' ' + (t[1] + s.y) + ' ' + (t[2] + s.z)
           : 'drag ' + s.x + ' ' + s.y + ' ' + s.z);
    drag.sent = null;
  }
}

// A line chart of columns @p series of view.history, with a dashed level.
function chart(id, series, colours, level) {
  const c = $(id), g = c.getContext('2d'), h = view.history;
  g.clearRect(0, 0, c.width, c.height);
  if (h.length < 2) return;
  let hi = level || 0;
  for (const row of h) for (const s of series) hi = Math.max(hi, row[s]);
  hi = hi > 0 ? 1.1 * hi : 1;
  const x = (k) => k * (c.width - 1) / (h.length - 1), y = (v) => c.height - 1 - v / hi * (c.height - 12);
  series.forEach((s, j) => {
    g.strokeStyle = colours[j];
    g.beginPath();
    h.forEach((row, k) => (k ? g.lineTo(x(k), y(row[s])) : g.moveTo(x(k), y(row[s]))));
    g.stroke();
  });
  if (level) {
    g.setLineDash([4, 3]); g.strokeStyle = '#ccc';
    g.beginPath(); g.moveTo(0, y(level)); g.lineTo(c.width, y(level)); g.stroke();
    g.setLineDash([]);
  }
  g.fillStyle = '#aab';
  g.fillText(hi.toPrecision(3), 2, 10);
}

// Adaptive resolution: where drawing cannot keep 30 frames a second (a
// software WebGL, a slow GPU), the canvas is drawn at fewer pixels (down to
// a third of the screen's) and back up when there is time to spare.
const pace = {frames: 0, since: performance.now(), ratio: window.devicePixelRatio};
function adaptResolution() {
  ++pace.frames;
  const now = performance.now(), elapsed = now - pace.since;
  if (elapsed < 1000) return;
  const rate = 1000 * pace.frames / elapsed;
  const best = window.devicePixelRatio;
  let ratio = pace.ratio;
  if (rate < 40) ratio = Math.max(best / 3, ratio * 0.8);
  else if (rate > 55) ratio = Math.min(best, ratio * 1.1);
  if (ratio !== pace.ratio) {
    pace.ratio = ratio;
    renderer.setPixelRatio(ratio);
    resize();
  }
  view.pixelRatio = ratio;
  pace.frames = 0;
  pace.since = now;
}

function animate() {
  requestAnimationFrame(animate);
  adaptResolution();
  sendDrag();
  if (view.pending) { drawFrame(view.pending); view.pending = null; }
  controls.update();
  renderer.render(scene3, camera);
}

setInterval(() => {
  view.freshPerSecond = view.fresh;
  view.fresh = 0;
  $('n-fps').textContent = view.freshPerSecond;
  $('n-bytes').textContent = view.bytesPerFrame + ' B';
  const last = view.history[view.history.length - 1];
  chart('chart-wall', [0], ['#7c7'], last ? last[1] : 0);
  chart('chart-rate', [2], ['#c7c'], 1);
  chart('chart-energy', [3, 4], ['#f93', '#6af'], 0);
  chart('chart-latency', [5, 6], ['#7c7', '#f66'], last ? 2 : 0);
}, 1000);

let socket = null;
function send(text) { if (socket && socket.readyState === 1) socket.send(text); }
function connect() {
  socket = new WebSocket(`ws://${location.host}/ws`);
  socket.binaryType = 'arraybuffer';
  socket.onmessage = receive;
  socket.onclose = () => {
    // After a reset the run starts again on the same address: try until
    // it answers (a minute at most).
    if (view.resetting && performance.now() - view.resetting < 60000) {
      setTimeout(connect, 250);
      return;
    }
    if (!view.ended) $('connection').textContent = 'disconnected (the run ended or stopped)';
  };
}
function receive(event) {
  if (typeof event.data !== 'string') {
    const magic = String.fromCharCode(...new Uint8Array(event.data, 0, 4));
    if (magic === 'TFT1') setTopology(event.data);
    else if (magic === 'TFF1') {
      ++view.framesReceived;
      view.bytesPerFrame = event.data.byteLength;
      view.pending = decodeFrame(event.data);
    }
    return;
  }
  const message = JSON.parse(event.data);
  if (message.type === 'scene') {
    // A new run (the first, or one that starts again after a reset).
    view.resetting = 0;
    view.history = [];
    view.lastStep = -1;
    $('status').textContent = '';
    view.scene = message;
    document.title = message.file + ' - TissueFEM live view';
    $('description').textContent = message.file + ': ' + message.description + ', integrator \'' +
      message.integrator + '\', material ' + message.materials + ', time step ' +
      message.time_step + ', output in ' + message.directory + '/';
    const movable = (message.obstacles || []).filter((o) => o.role === 'mouse');
    if (message.mouse !== 'grasp')
      document.querySelector('.hint').textContent = (movable.length
        ? 'Drag the instrument (light grey) to move it; elsewhere the mouse turns the view (the tissue cannot be grasped: '
        : 'The mouse turns the view (') + message.mouse +
        '): drag to turn, right-drag to pan, wheel to zoom.';
    else if (movable.length)
      document.querySelector('.hint').textContent = 'Drag the surface to pull the tissue, the ' +
        'instrument (light grey) to move it; drag elsewhere to turn the view, right-drag to pan, ' +
        'wheel to zoom.';
    view.mouseGrasps = message.mouse === 'grasp';
    const select = $('field');
    select.innerHTML = '';
    message.fields.forEach((name) => select.add(new Option(name, name)));
    select.selectedIndex = message.field;
  } else if (message.type === 'role') {
    view.drives = message.drives;
    $('connection').textContent = message.drives ? 'connected: this page drives the run'
                                                 : 'connected: watching (another page drives)';
    $('connection').className = message.drives ? '' : 'watching';
    for (const id of ['play', 'pause', 'step', 'reset', 'pace', 'field']) $(id).disabled = !message.drives;
  } else if (message.type === 'error') {
    $('status').textContent = (message.fatal ? 'the run stopped: ' : '') + message.message;
  } else if (message.type === 'end') {
    view.ended = true;
    $('connection').textContent = 'the run ended at t = ' + message.time;
  } else if (message.type === 'reset') {
    view.resetting = performance.now();
    view.drives = false;
    ++view.resets;
    $('connection').textContent = 'reset: the run starts again from t = 0...';
  }
}
view.resets = 0;
connect();

$('play').onclick = () => send('play');
$('pause').onclick = () => send('pause');
$('step').onclick = () => send('step');
$('reset').onclick = () => send('reset');
$('pace').onchange = (e) => send('pace ' + e.target.value);
$('field').onchange = (e) => send('field ' + e.target.value);
$('outline').onchange = (e) => { if (outline) outline.visible = e.target.checked; };
animate();
