// Strand picking: a click on a strand lights its component (every copy, in a lattice block) and the
// scaffold edges it passes, and dims the rest.  A hit is found on the curves the page draws (the
// design answer's centre lines, read by `centerlines`): the ray against each tube's axis within its
// radius, so the answer does not depend on how the tube meshes are laid out.  An edit clears it.
import * as THREE from 'three';
import { raySegment } from '/static/handles.js';

const DIM = 0.12; // opacity of the other strands
const SLACK_PX = 3; // a click this many pixels off a thin (far) tube still hits it

// The drawn curves as {points (Float32Array xyz), counts, strand (strand index of each curve), radius}:
// each curve's centre line as the tubes hold it (`pointsOf(key)`, strands.js), since an answer
// carries the points of its new curves only.
const decoded = new WeakMap();
export function centerlines(curves, pointsOf) {
  if (!curves) return null;
  if (!decoded.has(curves)) {
    const lines = curves.keys.map((key) => pointsOf(key));
    if (lines.some((line) => !line)) return null; // not drawn (yet)
    const points = new Float32Array(lines.reduce((n, line) => n + line.length, 0)), spheres = [];
    let start = 0;
    lines.forEach((line, j) => { points.set(line, 3 * start); spheres.push(bound(points, start, curves.counts[j])); start += curves.counts[j]; });
    decoded.set(curves, { points, counts: curves.counts, closed: curves.closed, strand: curves.strand, radius: curves.radius, spheres });
  }
  return decoded.get(curves);
}
function bound(p, start, n) { // a bounding sphere of points start..start+n: [x, y, z, r]
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = start; i < start + n; i++) for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], p[3 * i + k]); hi[k] = Math.max(hi[k], p[3 * i + k]); }
  const c = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
  return [...c, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2];
}

export class StrandPicker {
  constructor(view, handles, state) {
    this.view = view; this.handles = handles; this.S = state;
    this.group = new THREE.Group(); view.scene.add(this.group);
    this.strand = null; this.design = null; this.meshes = [];
    handles.occluder = (x, y, before) => this.hit(x, y, 0, before) !== null; // a tube really covering the pixel, nearer than `before`
    view.afterRender.push(() => this.sync());
  }

  // The strand under a pixel: {strand, curve, t} of the nearest tube the ray passes within `slack` pixels of
  // (nearer than `before` along the ray), or null.
  hit(clientX, clientY, slack = SLACK_PX, before = Infinity) {
    const c = centerlines(this.S.shown, (key) => this.view.strands.pointsOf(key));
    if (!c) return null;
    const { o, d, perPx } = this.handles.ray(clientX, clientY), p = c.points, r = c.radius;
    let best = null, start = 0;
    c.counts.forEach((n, k) => {
      const [sx, sy, sz, sr] = c.spheres[k], t0 = (sx - o.x) * d.x + (sy - o.y) * d.y + (sz - o.z) * d.z;
      const miss = Math.hypot(o.x + t0 * d.x - sx, o.y + t0 * d.y - sy, o.z + t0 * d.z - sz) > sr + r + slack * perPx * Math.max(t0 + sr, 0);
      if (!miss && t0 - sr < before) {
        const segments = c.closed[k] ? n : n - 1;
        for (let i = 0; i < segments; i++) {
          const h = raySegment(o, d, p, 3 * (start + i), p, 3 * (start + ((i + 1) % n)));
          if (h && h.t < before && h.dist <= r + slack * perPx * h.t && (!best || h.t < best.t)) best = { strand: c.strand[k], curve: k, t: h.t };
        }
      }
      start += n;
    });
    return best;
  }

  // A click off every edge: light the strand under it (true) or clear the highlight (false).
  click(clientX, clientY) {
    const h = this.hit(clientX, clientY);
    if (h) this.show(h.strand); else this.clear();
    return h !== null;
  }

  show(k) {
    this.clear(false);
    const c = centerlines(this.S.shown, (key) => this.view.strands.pointsOf(key));
    if (!c || !this.S.design) return;
    this.strand = k; this.design = this.S.design;
    this.build(c, k);
    this.handles.light(this.S.design.strands[k]?.edges || []);
    this.view.render();
  }
  build(c, k) { // the component's tubes again, opaque over the dimmed ones (a rod a segment)
    for (const m of this.meshes) restore(m);
    this.meshes = [...this.view.groups.strands.children];
    for (const m of this.meshes) dim(m);
    const segs = [];
    let start = 0;
    c.counts.forEach((n, j) => {
      if (c.strand[j] === k) for (let i = 0; i < (c.closed[j] ? n : n - 1); i++) segs.push(start + i, start + ((i + 1) % n));
      start += n;
    });
    const mesh = new THREE.InstancedMesh(new THREE.CylinderGeometry(1, 1, 1, 10, 1, false),
      new THREE.MeshStandardMaterial({ color: this.view.strands.colorOf(k), roughness: 0.45, metalness: 0.05 }), segs.length / 2);
    const m = new THREE.Matrix4(), q = new THREE.Quaternion(), up = new THREE.Vector3(0, 1, 0), a = new THREE.Vector3(), b = new THREE.Vector3(), r = c.radius * 1.06;
    for (let s = 0; s < segs.length; s += 2) {
      a.fromArray(c.points, 3 * segs[s]); b.fromArray(c.points, 3 * segs[s + 1]);
      const len = a.distanceTo(b), dir = b.clone().sub(a).normalize();
      m.compose(a.add(b).multiplyScalar(0.5), q.setFromUnitVectors(up, dir), new THREE.Vector3(r, len + r, r));
      mesh.setMatrixAt(s / 2, m);
    }
    mesh.frustumCulled = false;
    this.group.add(mesh);
  }

  clear(redraw = true) {
    for (const m of this.meshes) restore(m);
    this.meshes = [];
    for (const o of [...this.group.children]) { this.group.remove(o); o.geometry.dispose(); o.material.dispose(); }
    const was = this.strand !== null;
    this.strand = null; this.design = null;
    if (was) { this.handles.light(null); if (redraw) this.view.render(); }
  }

  // After each render: an edit (a new design) clears the highlight; new tubes of the same design
  // (the relaxed curves) are dimmed and the component rebuilt on them.
  sync() {
    if (this.strand === null) return;
    if (this.S.design !== this.design) { this.clear(); return; }
    const now = this.view.groups.strands.children;
    if (now.length !== this.meshes.length || now.some((m, i) => m !== this.meshes[i])) {
      requestAnimationFrame(() => { if (this.strand !== null && this.S.design === this.design) this.show(this.strand); });
    }
  }
}

function dim(mesh) { // a material of its own (strands of one colour share one)
  mesh.userData.undim = mesh.material;
  mesh.material = Object.assign(mesh.material.clone(), { transparent: true, opacity: DIM, depthWrite: false });
}
function restore(mesh) {
  if (!mesh.userData.undim) return;
  mesh.material.dispose(); mesh.material = mesh.userData.undim; delete mesh.userData.undim;
}
