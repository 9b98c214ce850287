// The browser page vgd-server serves at / (docs/server.md, "In a browser"):
// the job list, and a job's drape drawn live with three.js from its frames'
// WebSocket. three.js is served by the server itself from its own copy
// (--three), never from a CDN.
#include "vgd/net/page.hpp"

namespace vgd::net {

std::string_view browser_page() {
  return R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>vgd-server</title>
<style>
body { font: 14px system-ui, sans-serif; margin: 0; display: flex; height: 100vh; color: #222; }
#side { width: 360px; overflow: auto; padding: 12px; background: #f4f4f4; box-sizing: border-box; }
#view { flex: 1; position: relative; background: #e8ecf0; }
#status { position: absolute; left: 12px; top: 10px; background: #fffc; padding: 4px 8px; border-radius: 4px; }
table { border-collapse: collapse; width: 100%; }
td { padding: 3px 4px; border-bottom: 1px solid #ddd; }
tr.job { cursor: pointer; } tr.job:hover { background: #e2e8f0; }
.passed { color: #2a7d2a; } .failed { color: #b02a2a; } .running { color: #1d5fb0; }
code { font-size: 12px; }
</style>
<script type="importmap">{"imports": {"three": "/web/three/three.module.js"}}</script>
</head>
<body>
<div id="side">
  <h2>vgd-server</h2>
  <label>token <input id="token" type="password" size="24" placeholder="(if the server needs one)"></label>
  <table id="jobs"><tbody></tbody></table>
</div>
<div id="view"><div id="status">choose a job</div></div>
<script type="module">
import * as THREE from 'three';

const viewer = { frames: 0, lastSeq: -1, state: 'idle', particles: 0, errors: [] };
window.vgdViewer = viewer;
const tokenBox = document.getElementById('token');
tokenBox.value = localStorage.getItem('vgd-token') || '';
tokenBox.onchange = () => localStorage.setItem('vgd-token', tokenBox.value);
const headers = () => (tokenBox.value ? { Authorization: 'Bearer ' + tokenBox.value } : {});
const status = (t) => { document.getElementById('status').textContent = t; };

// The 3-D view.
const view = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xe8ecf0);
const camera = new THREE.PerspectiveCamera(30, 1, 0.01, 100);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(1, 2, 3);
scene.add(sun);
const material = new THREE.MeshStandardMaterial({ color: 0x2f5fb8, side: THREE.DoubleSide, roughness: 0.85 });
let mesh = null, fitted = false;
function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();
function draw() { renderer.render(scene, camera); }

function fit(geometry) {
  geometry.computeBoundingSphere();
  const s = geometry.boundingSphere;
  camera.position.set(s.center.x, s.center.y, s.center.z + s.radius * 4.2);
  camera.lookAt(s.center);
  fitted = true;
}

// A job's frames: topology, then binary frames (include/vgd/net/frames.hpp).
let socket = null;
function watch(id) {
  if (socket) socket.close();
  if (mesh) { scene.remove(mesh); mesh.geometry.dispose(); mesh = null; }
  fitted = false;
  Object.assign(viewer, { frames: 0, lastSeq: -1, state: 'connecting', job: id });
  const proto = location.protocol === 'https:' ? 'wss' : 'ws';
  const q = tokenBox.value ? '?token=' + encodeURIComponent(tokenBox.value) : '';
  socket = new WebSocket(`${proto}://${location.host}/v1/jobs/${id}/frames${q}`);
  socket.binaryType = 'arraybuffer';
  let progress = '';
  socket.onmessage = (e) => {
    if (typeof e.data === 'string') {
      const m = JSON.parse(e.data);
      if (m.type === 'topology') {
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(m.particles * 3), 3));
        g.setIndex(m.triangles);
        mesh = new THREE.Mesh(g, material);
        scene.add(mesh);
        viewer.particles = m.particles;
        viewer.state = 'streaming';
      } else if (m.type === 'progress') {
        const p = m.progress;
        progress = `${p.stage || ''}  t ${(p.simulated_s ?? 0).toFixed(2)} s  seams ${p.seams_closed ?? 0}/${p.seam_pairs ?? 0}`;
      } else if (m.type === 'end') {
        viewer.state = 'end';
        viewer.endState = m.state;
        status(`job ${id}: ${m.state}, ${viewer.frames} frames`);
        return;
      }
      status(`job ${id}: ${progress}  frames ${viewer.frames}`);
      return;
    }
    const b = e.data, dv = new DataView(b);
    if (!mesh || dv.getUint32(0, true) !== 0x46444756) return;  // "VGDF"
    const seq = dv.getUint32(4, true), count = dv.getUint32(16, true);
    const pos = mesh.geometry.attributes.position;
    pos.array.set(new Float32Array(b, 24, count));
    pos.needsUpdate = true;
    mesh.geometry.computeVertexNormals();
    if (!fitted) fit(mesh.geometry);
    viewer.frames += 1;
    viewer.lastSeq = seq;
    status(`job ${id}: ${progress}  frames ${viewer.frames}`);
    draw();
  };
  socket.onerror = () => { viewer.errors.push('websocket error'); status(`job ${id}: the stream failed`); };
}

// The job list.
async function refresh() {
  try {
    const r = await fetch('/v1/jobs', { headers: headers() });
    const jobs = r.ok ? await r.json() : [];
    const body = document.querySelector('#jobs tbody');
    body.innerHTML = '';
    for (const j of jobs) {
      const tr = document.createElement('tr');
      tr.className = 'job';
      tr.innerHTML = `<td><code>${j.id}</code></td><td class="${j.state}">${j.state}</td><td></td>`;
      tr.lastChild.textContent = j.name;
      tr.onclick = () => watch(j.id);
      body.appendChild(tr);
    }
  } catch (e) { viewer.errors.push(String(e)); }
}
refresh();
setInterval(refresh, 2000);
const wanted = new URLSearchParams(location.search).get('job');
if (wanted) watch(wanted);
draw();
</script>
</body>
</html>
)HTML";
}

}  // namespace vgd::net
