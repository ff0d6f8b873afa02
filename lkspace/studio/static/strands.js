// The strand tubes: one mesh per curve, kept by the curve's content key (lkspace/studio/curves.py),
// so an edit rebuilds the tubes of the new curves only, in a worker (tube-worker.js); the others
// stay on the GPU as they are.  Colours are lkspace's palette (sent by /api/info) and follow strands
// across edits: a strand is named by the smallest port it passes, and keeps the colour that port had
// in the design drawn before; a new strand takes its export colour where it is free.  A ring copied over the block's cells takes a colour per tone of its
// cell (the curves' `tone`, lkspace/formats/colors.py: neighbouring copies differ), kept the same way.
import * as THREE from 'three';
import { tubeArrays, decodeCurves } from '/static/tubes.js';

const KEEP = 3; // a mesh is kept this many designs after it was last drawn (an answer in flight may name it)
const MAX_HAVE = 50000; // lkspace/studio/curves.py MAX_HAVE

export class Strands {
  constructor(group) {
    this.group = group; this.meshes = new Map(); this.generation = 0; this.radius = null; this.sides = null;
    this.palette = ['#808080']; this.materials = [];
    this.colorOfUnit = new Map(); this.strandColors = []; this.colors = [];
    this.worker = null; this.pending = new Map(); this.nextId = 0; this.queue = Promise.resolve();
  }
  have() { // the curve keys an answer may send without points (those drawn now, if the server would take too many)
    const all = [...this.meshes.keys()];
    return all.length <= MAX_HAVE ? all : this.group.children.slice(0, MAX_HAVE).map((m) => m.userData.key);
  }
  pointsOf(key) { return this.meshes.get(key)?.points; } // a held curve's centre line, Float32Array xyz
  setPalette(palette) { // the colours (hex), lkspace's (lkspace/formats/colors.py PALETTE)
    this.palette = palette;
    this.materials = palette.map((color) => new THREE.MeshStandardMaterial({ color, roughness: 0.45, metalness: 0.05 }));
  }
  colorOf(k) { return this.palette[this.strandColors[k] ?? k % this.palette.length]; }
  reset() { this.dropMeshes(); this.colorOfUnit = new Map(); this.strandColors = []; this.colors = []; } // a new scaffold
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
    const units = this.assignColors(strands, curves);
    const shown = new Set();
    (curves ? curves.keys : []).forEach((key, i) => {
      const held = this.meshes.get(key); held.used = gen; held.mesh.material = this.materials[units[i]];
      shown.add(held.mesh);
    });
    for (const m of [...this.group.children]) if (!shown.has(m)) this.group.remove(m);
    for (const m of shown) if (m.parent !== this.group) this.group.add(m);
    for (const [key, held] of this.meshes) if (held.used <= gen - KEEP) { held.mesh.removeFromParent(); held.mesh.geometry.dispose(); this.meshes.delete(key); }
    this.colors = [...new Set(units)].map((c) => this.palette[c]);
    return true;
  }
  // Colour the units, each strand and each further tone of a ring's cells: a unit drawn before (named by its
  // strand's smallest port) keeps its colour; a new one takes the colour `export` gives it (its curves' `slot`)
  // while no unit holds that colour, else the colour used least among those its strand's other tones leave
  // (so a ring's tones differ while the palette lasts).  A page drawn afresh is coloured as `export` colours
  // the design.  Returns each curve's colour.
  assignColors(strands, curves) {
    const unit = (k, tone) => `${strands[k].port}/${tone}`;
    const names = strands.map((_, k) => unit(k, 0)), ofCurve = [], slotOf = new Map();
    (curves ? curves.strand : []).forEach((k, i) => {
      ofCurve.push(unit(k, curves.tone[i]));
      if (curves.slot) slotOf.set(ofCurve[i], curves.slot[i] % this.palette.length);
    });
    const listed = new Set(names);
    for (const name of ofCurve) if (!listed.has(name)) { listed.add(name); names.push(name); }
    const out = names.map((name) => this.colorOfUnit.get(name)), used = new Array(this.palette.length).fill(0);
    const port = (name) => name.slice(0, name.indexOf('/')), taken = new Map(); // port -> colours of its tones
    names.forEach((name, k) => { if (!taken.has(port(name))) taken.set(port(name), new Set()); if (out[k] !== undefined) taken.get(port(name)).add(out[k]); });
    for (const c of out) if (c !== undefined) used[c]++;
    for (let k = 0; k < out.length; k++) {
      if (out[k] !== undefined) continue;
      const mine = taken.get(port(names[k])), free = mine.size < used.length, own = slotOf.get(names[k]);
      let best = own !== undefined && !used[own] ? own : -1; // export's colour while no unit holds it
      if (best < 0) for (let c = 0; c < used.length; c++) if (!(free && mine.has(c)) && (best < 0 || used[c] < used[best])) best = c;
      out[k] = best; used[best]++; mine.add(best);
    }
    this.colorOfUnit = new Map(names.map((name, k) => [name, out[k]])); this.strandColors = out.slice(0, strands.length);
    return ofCurve.map((name) => this.colorOfUnit.get(name));
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
