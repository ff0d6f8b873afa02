// The strand tubes: one mesh per curve, kept by the curve's content key (lkspace/studio/curves.py),
// so an edit rebuilds the tubes of the new curves only, in a worker (tube-worker.js); the others
// stay on the GPU as they are.  Colours follow strands across edits: a strand is named by the
// smallest port it passes, and keeps the colour that port had in the design drawn before.
import * as THREE from 'three';
import { tubeArrays, decodeCurves } from '/static/tubes.js';

export const PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2',
  '#17becf', '#bcbd22', '#393b79', '#637939', '#843c39', '#7b4173', '#3182bd', '#e6550d', '#31a354'];
const KEEP = 3; // a mesh is kept this many designs after it was last drawn (an answer in flight may name it)
const MAX_HAVE = 50000; // lkspace/studio/curves.py MAX_HAVE

export class Strands {
  constructor(group) {
    this.group = group; this.meshes = new Map(); this.generation = 0; this.radius = null; this.sides = null;
    this.materials = PALETTE.map((color) => new THREE.MeshStandardMaterial({ color, roughness: 0.45, metalness: 0.05 }));
    this.colorOfPort = new Map(); this.strandColors = []; this.colors = [];
    this.worker = null; this.pending = new Map(); this.nextId = 0; this.queue = Promise.resolve();
  }
  have() { // the curve keys an answer may send without points (those drawn now, if the server would take too many)
    const all = [...this.meshes.keys()];
    return all.length <= MAX_HAVE ? all : this.group.children.slice(0, MAX_HAVE).map((m) => m.userData.key);
  }
  pointsOf(key) { return this.meshes.get(key)?.points; } // a held curve's centre line, Float32Array xyz
  colorOf(k) { return PALETTE[this.strandColors[k] ?? k % PALETTE.length]; }
  reset() { this.dropMeshes(); this.colorOfPort = new Map(); this.strandColors = []; this.colors = []; } // a new scaffold
  dropMeshes() {
    for (const { mesh } of this.meshes.values()) { mesh.removeFromParent(); mesh.geometry.dispose(); }
    this.meshes.clear(); this.radius = null;
  }
  // Draw an answer's curves (null: none) and colour its strands; resolves false when a curve sent
  // without points is no longer held (ask again without `have`).  Answers are drawn in call order.
  set(curves, strands) {
    const run = this.queue.then(() => this.apply(curves, strands || []));
    this.queue = run.catch(() => {});
    return run;
  }
  async apply(curves, strands) {
    const gen = ++this.generation;
    if (curves) {
      const total = curves.counts.reduce((a, b) => a + b, 0), sides = total > 200000 ? 5 : total > 40000 ? 6 : 8;
      if (curves.radius !== this.radius || sides !== this.sides) { this.dropMeshes(); this.radius = curves.radius; this.sides = sides; }
      if (curves.keys.some((key, i) => !curves.sent[i] && !this.meshes.has(key))) return false;
      const todo = [];
      curves.keys.forEach((key, i) => { if (curves.sent[i]) todo.push({ key, count: curves.counts[i], closed: curves.closed[i] }); });
      const lines = todo.length ? decodeCurves(curves.points, todo.map((t) => t.count)) : [];
      const tubes = todo.length ? await this.build(curves.points, todo, curves.radius, sides) : [];
      tubes.forEach((t, i) => { if (!this.meshes.has(t.key)) this.meshes.set(t.key, { mesh: this.mesh(t), used: gen, points: lines[i] }); });
    }
    this.assignColors(strands);
    const shown = new Set();
    (curves ? curves.keys : []).forEach((key, i) => {
      const held = this.meshes.get(key); held.used = gen; held.mesh.material = this.materials[this.strandColors[curves.strand[i]]];
      shown.add(held.mesh);
    });
    for (const m of [...this.group.children]) if (!shown.has(m)) this.group.remove(m);
    for (const m of shown) if (m.parent !== this.group) this.group.add(m);
    for (const [key, held] of this.meshes) if (held.used <= gen - KEEP) { held.mesh.removeFromParent(); held.mesh.geometry.dispose(); this.meshes.delete(key); }
    this.colors = curves ? [...new Set(curves.strand.map((k) => this.strandColors[k]))].map((c) => PALETTE[c]) : [];
    return true;
  }
  // A strand whose smallest port was drawn before keeps its colour; a new one takes the colour used least.
  assignColors(strands) {
    const out = strands.map((s) => this.colorOfPort.get(s.port)), used = new Array(PALETTE.length).fill(0);
    for (const c of out) if (c !== undefined) used[c]++;
    for (let k = 0; k < out.length; k++) {
      if (out[k] !== undefined) continue;
      let best = 0; for (let c = 1; c < used.length; c++) if (used[c] < used[best]) best = c;
      out[k] = best; used[best]++;
    }
    this.colorOfPort = new Map(strands.map((s, k) => [s.port, out[k]])); this.strandColors = out;
  }
  mesh(t) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(t.position, 3));
    g.setAttribute('normal', new THREE.BufferAttribute(t.normal, 3));
    g.setIndex(new THREE.BufferAttribute(t.index, 1));
    const m = new THREE.Mesh(g, this.materials[0]); m.userData.key = t.key;
    return m;
  }
  // Tubes of the curves sent, built in the worker (on this thread if the worker fails).
  async build(points, curves, radius, sides) {
    try {
      if (!this.worker) {
        this.worker = new Worker('/static/tube-worker.js', { type: 'module' });
        this.worker.onmessage = (ev) => { const p = this.pending.get(ev.data.id); this.pending.delete(ev.data.id); p.resolve(ev.data.tubes); };
        this.worker.onerror = (ev) => { for (const p of this.pending.values()) p.reject(new Error(ev.message)); this.pending.clear(); this.worker = null; };
      }
      const id = ++this.nextId;
      return await new Promise((resolve, reject) => { this.pending.set(id, { resolve, reject }); this.worker.postMessage({ id, points, curves, radius, sides }); });
    } catch {
      const pts = decodeCurves(points, curves.map((c) => c.count));
      return curves.map((c, i) => ({ key: c.key, ...tubeArrays(pts[i], c.closed, radius, sides) }));
    }
  }
}
