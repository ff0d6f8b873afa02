// Edge handles: every edge of the scaffold (of the unit cell, for a lattice) drawn as a thick
// rod a designer can hover, click and drag, coloured by its label's sign (blue > 0, red < 0,
// grey 0), with the label drawn at its midpoint.  Picking is a ray against these rods (exact,
// a few microseconds an edge), so it never picks the faint copies of the other lattice cells.
import * as THREE from 'three';

const COLORS = { pos: '#2050c0', neg: '#c03030', zero: '#8a8a8a', selected: '#ffb000', orbit: '#ffd24a', pin: '#00a060', error: '#ff0000' };
const LENGTH = 0.8; // a rod covers this fraction of its edge: the gaps at the vertices keep rods apart
const SLACK_PX = 5; // a click this many pixels off a rod still hits it
const MID_PX = 8; // a click this near an edge's midpoint on screen picks the edge, even through the strand crossing there
const MIN_LABEL_PX = 40; // labels of edges shorter than this on screen are left out (zoom in to see them)
const MAX_LABELS = 200;
const CELL = [34, 20]; // label grid cell in pixels: one label a cell, nearest first

export class Handles {
  constructor(view, state) {
    this.view = view; this.S = state; view.handles = this;
    this.hovered = null; this.strandEdges = null; this.occluder = null;
    this.layer = document.createElement('div'); this.layer.id = 'edge-labels';
    view.canvas.parentElement.append(this.layer);
    this.spans = [];
    view.afterRender.push(() => this.drawLabels());
  }

  // ---- geometry: one instanced rod an edge; a halo drawn through everything marks the selected edge
  build(sc) {
    const p = sc.edge_points, n = sc.n_edges;
    this.a = new Float64Array(3 * n); this.b = new Float64Array(3 * n);
    const lengths = [];
    for (let e = 0; e < n; e++) {
      for (let k = 0; k < 3; k++) {
        const x = p[6 * e + k], y = p[6 * e + 3 + k], m = (x + y) / 2;
        this.a[3 * e + k] = m + (x - m) * LENGTH; this.b[3 * e + k] = m + (y - m) * LENGTH;
      }
      lengths.push(Math.hypot(p[6 * e + 3] - p[6 * e], p[6 * e + 4] - p[6 * e + 1], p[6 * e + 5] - p[6 * e + 2]));
    }
    lengths.sort((x, y) => x - y);
    this.radius = 0.02 * (lengths[n >> 1] || 1);
    const geometry = new THREE.CylinderGeometry(1, 1, 1, 12, 1, false);
    this.mesh = new THREE.InstancedMesh(geometry, new THREE.MeshLambertMaterial(), n);
    this.mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(3 * n), 3);
    this.mesh.frustumCulled = false;
    this.halo = new THREE.Mesh(new THREE.CylinderGeometry(1, 1, 1, 16, 1, false),
      new THREE.MeshBasicMaterial({ color: COLORS.selected, transparent: true, opacity: 0.45, depthTest: false, depthWrite: false }));
    this.halo.renderOrder = 10; this.halo.visible = false;
    this.view.groups.edges.add(this.mesh, this.halo);
    this.hovered = null; this.strandEdges = null; this.errorEdge = null;
  }

  // The edges an edit of edge e sets: its orbit when orbit editing is on, else e alone.
  orbitOf(e) {
    const S = this.S;
    if (e === null || e === undefined) return [];
    return S.orbits && document.getElementById('orbit').checked ? S.orbits.orbits[S.orbits.orbit_of[e]] : [e];
  }

  paint(labels = this.S.labels, selected = this.S.selected, pinned = this.S.pins, errorEdge = this.errorEdge) {
    if (!this.mesh) return;
    this.errorEdge = errorEdge;
    const lit = new Set(this.orbitOf(selected)), m = new THREE.Matrix4(), q = new THREE.Quaternion(), c = new THREE.Color();
    const up = new THREE.Vector3(0, 1, 0), dir = new THREE.Vector3(), mid = new THREE.Vector3(), size = new THREE.Vector3(), white = new THREE.Color('#ffffff');
    for (let e = 0; e < labels.length; e++) {
      const t = Number(labels[e]), dim = this.strandEdges && !this.strandEdges.has(e);
      let r = this.radius;
      if (e === errorEdge) { c.set(COLORS.error); r *= 1.8; }
      else if (e === selected) { c.set(COLORS.selected); r *= 1.6; }
      else if (lit.has(e)) { c.set(COLORS.orbit); r *= 1.6; }
      else if (pinned.has(e)) c.set(COLORS.pin);
      else c.set(t > 0 ? COLORS.pos : t < 0 ? COLORS.neg : COLORS.zero);
      if (e === this.hovered) { c.lerp(white, 0.2); r *= 1.3; }
      else if (dim && e !== selected) { c.lerp(white, 0.75); r *= 0.6; }
      this.mesh.setColorAt(e, c);
      this.rod(e, mid, dir); m.compose(mid, q.setFromUnitVectors(up, dir.normalize()), size.set(r, this.len, r));
      this.mesh.setMatrixAt(e, m);
    }
    this.mesh.instanceMatrix.needsUpdate = true; this.mesh.instanceColor.needsUpdate = true;
    this.halo.visible = selected !== null && selected < labels.length;
    if (this.halo.visible) {
      const r = this.radius * 2.2;
      this.rod(selected, this.halo.position, dir);
      this.halo.quaternion.setFromUnitVectors(up, dir.normalize()); this.halo.scale.set(r, this.len, r);
    }
  }
  rod(e, mid, dir) { // midpoint, direction and length (this.len) of edge e's rod
    const a = this.a, b = this.b;
    mid.set((a[3 * e] + b[3 * e]) / 2, (a[3 * e + 1] + b[3 * e + 1]) / 2, (a[3 * e + 2] + b[3 * e + 2]) / 2);
    dir.set(b[3 * e] - a[3 * e], b[3 * e + 1] - a[3 * e + 1], b[3 * e + 2] - a[3 * e + 2]);
    this.len = dir.length();
  }

  hover(e) { if (e !== this.hovered) { this.hovered = e; this.paint(); this.view.render(); } }
  light(edges) { this.strandEdges = edges ? new Set(edges) : null; this.paint(); } // a lit strand's edges; the others dimmed

  // ---- picking: the nearest rod the ray through the pixel passes within its radius (plus a few pixels)
  ray(clientX, clientY) {
    const rect = this.view.canvas.getBoundingClientRect(), rc = this.view.raycaster;
    rc.setFromCamera(new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1), this.view.camera);
    return { o: rc.ray.origin, d: rc.ray.direction, perPx: 2 * Math.tan((this.view.camera.fov * Math.PI) / 360) / rect.height };
  }
  pickAt(clientX, clientY) { // {edge, distance along the ray} or null: an edge whose midpoint is at the pixel, else the nearest rod the ray passes through, else the closest in pixels
    if (!this.mesh) return null;
    const { o, d, perPx } = this.ray(clientX, clientY), a = this.a, b = this.b, n = a.length / 3, r = this.radius * 1.5;
    let best = null;
    for (let e = 0; e < n; e++) { // midpoints first: a strand crosses every edge there, and the edge is what a click there means
      const m = [0, 1, 2].map((k) => (a[3 * e + k] + b[3 * e + k]) / 2), t = (m[0] - o.x) * d.x + (m[1] - o.y) * d.y + (m[2] - o.z) * d.z;
      if (t <= 0) continue;
      const px = Math.hypot(o.x + t * d.x - m[0], o.y + t * d.y - m[1], o.z + t * d.z - m[2]) / (perPx * t);
      if (px <= MID_PX && (!best || px < best.px - 0.5 || (px < best.px + 0.5 && t < best.t))) best = { edge: e, t, px };
    }
    if (best) return best;
    for (let e = 0; e < n; e++) {
      const hit = raySegment(o, d, a, 3 * e, b, 3 * e);
      if (!hit) continue;
      const px = Math.max(hit.dist - r, 0) / (perPx * hit.t); // pixels off the rod
      if (px <= SLACK_PX && (!best || px < best.px || (px === best.px && hit.t < best.t))) best = { edge: e, t: hit.t, px };
    }
    if (best && this.occluder && this.occluder(clientX, clientY, best.t - 4 * this.radius)) return null; // a strand in front
    return best;
  }
  pick(clientX, clientY) { const hit = this.pickAt(clientX, clientY); return hit ? hit.edge : null; }

  // ---- labels at the midpoints: always for the selected, hovered and orbit edges; others when
  // their edge is long enough on screen, nearest first, one a grid cell (so ~2,000 edges stay fast)
  drawLabels() {
    const S = this.S, sc = this.view.sc;
    if (!this.mesh || !sc || S.labels.length !== sc.n_edges) { this.show([]); return; }
    const rect = this.view.canvas.getBoundingClientRect(), cam = this.view.camera, v = new THREE.Vector3(), w = new THREE.Vector3();
    const forced = new Set([...this.orbitOf(S.selected), ...(this.hovered === null ? [] : [this.hovered])]);
    const items = [];
    for (let e = 0; e < sc.n_edges; e++) {
      v.set(this.a[3 * e], this.a[3 * e + 1], this.a[3 * e + 2]).project(cam);
      w.set(this.b[3 * e], this.b[3 * e + 1], this.b[3 * e + 2]).project(cam);
      if (v.z > 1 || w.z > 1) continue; // behind the camera
      const x = ((v.x + w.x) / 4 + 0.5) * rect.width, y = (0.5 - (v.y + w.y) / 4) * rect.height;
      if (x < 0 || y < 0 || x > rect.width || y > rect.height) continue;
      const long = Math.hypot((v.x - w.x) * rect.width, (v.y - w.y) * rect.height) / 2 / LENGTH >= MIN_LABEL_PX;
      if (forced.has(e) || (long && !(this.strandEdges && !this.strandEdges.has(e)))) items.push({ e, x, y, z: v.z + w.z, forced: forced.has(e) });
    }
    items.sort((p, q) => (q.forced - p.forced) || (p.z - q.z));
    const taken = new Set(), out = [];
    for (const it of items) {
      const cell = `${Math.floor(it.x / CELL[0])},${Math.floor(it.y / CELL[1])}`;
      if (!it.forced && (taken.has(cell) || out.length >= MAX_LABELS)) continue;
      taken.add(cell); out.push(it);
    }
    this.show(out);
  }
  show(items) { // reuse one span a label
    const S = this.S;
    while (this.spans.length < items.length) { const s = document.createElement('span'); this.layer.append(s); this.spans.push(s); }
    items.forEach((it, i) => {
      const s = this.spans[i], t = S.labels[it.e], text = String(t).length > 8 ? String(t).slice(0, 7) + '…' : String(t);
      const cls = (it.e === S.selected ? 'sel ' : it.forced ? 'lit ' : '') + (Number(t) > 0 ? 'pos' : Number(t) < 0 ? 'neg' : 'zero');
      if (s.textContent !== text) s.textContent = text;
      if (s.className !== cls) s.className = cls;
      s.dataset.edge = it.e; s.style.transform = `translate(${it.x.toFixed(1)}px, ${it.y.toFixed(1)}px) translate(-50%, -50%)`;
      s.hidden = false;
    });
    for (let i = items.length; i < this.spans.length; i++) this.spans[i].hidden = true;
  }
}

// Closest approach of the ray o + t d (|d| = 1, t > 0) and the segment a[i..i+2] -> b[j..j+2]: {t, dist}.
export function raySegment(o, d, a, i, b, j) {
  const ux = b[j] - a[i], uy = b[j + 1] - a[i + 1], uz = b[j + 2] - a[i + 2];
  const wx = o.x - a[i], wy = o.y - a[i + 1], wz = o.z - a[i + 2];
  const uu = ux * ux + uy * uy + uz * uz, ud = ux * d.x + uy * d.y + uz * d.z, uw = ux * wx + uy * wy + uz * wz, dw = d.x * wx + d.y * wy + d.z * wz;
  const den = uu - ud * ud;
  const s = Math.min(Math.max(den > 1e-12 * uu ? (uw - ud * dw) / den : 0, 0), 1); // parameter on the segment
  const px = a[i] + s * ux, py = a[i + 1] + s * uy, pz = a[i + 2] + s * uz;
  const t = (px - o.x) * d.x + (py - o.y) * d.y + (pz - o.z) * d.z;
  if (t <= 0) return null;
  return { t, dist: Math.hypot(o.x + t * d.x - px, o.y + t * d.y - py, o.z + t * d.z - pz) };
}
