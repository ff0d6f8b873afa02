// The 3D view: scaffold faces (translucent), pickable edges, strand tubes coloured by strand (strands.js).
// It only draws what the server computed; it knows nothing of twists or tracing.
import * as THREE from 'three';
import { OrbitControls } from '/static/vendor/OrbitControls.js';
import { Strands } from '/static/strands.js';

export class View {
  constructor(canvas, layer) {
    this.canvas = canvas; this.layer = layer;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.scene = new THREE.Scene(); this.scene.background = new THREE.Color('#ffffff');
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', () => this.render());
    this.scene.add(new THREE.HemisphereLight('#ffffff', '#777788', 2.2));
    const sun = new THREE.DirectionalLight('#ffffff', 1.4); sun.position.set(3, 5, 4); this.camera.add(sun);
    this.scene.add(this.camera);
    this.groups = { faces: new THREE.Group(), edges: new THREE.Group(), strands: new THREE.Group(), marks: new THREE.Group() };
    for (const g of Object.values(this.groups)) this.scene.add(g);
    this.raycaster = new THREE.Raycaster();
    this.edgeColors = null; this.sc = null; this.showNumbers = false; this.strands = new Strands(this.groups.strands);
    this.handles = null; this.afterRender = []; // edge handles (handles.js) and overlays drawn after each frame
    new ResizeObserver(() => this.resize()).observe(canvas.parentElement);
    this.resize();
  }
  resize() {
    const el = this.canvas.parentElement, w = el.clientWidth, h = el.clientHeight;
    this.renderer.setSize(w, h, false); this.camera.aspect = w / Math.max(h, 1); this.camera.updateProjectionMatrix(); this.render();
  }
  clear(group) { for (const o of [...group.children]) { group.remove(o); o.geometry?.dispose(); o.material?.dispose(); } }
  setScaffold(sc, block) {
    this.sc = sc; this.block = block; this.strands.reset();
    for (const g of Object.values(this.groups)) this.clear(g);
    const cp = sc.corner_positions, fs = sc.face_starts, cen = sc.face_centroids;
    const tri = [];
    for (let f = 0; f + 1 < fs.length; f++) for (let c = fs[f]; c < fs[f + 1]; c++) {
      const d = c + 1 < fs[f + 1] ? c + 1 : fs[f];
      tri.push(cen[3 * f], cen[3 * f + 1], cen[3 * f + 2], cp[3 * c], cp[3 * c + 1], cp[3 * c + 2], cp[3 * d], cp[3 * d + 1], cp[3 * d + 2]);
    }
    const fg = new THREE.BufferGeometry(); fg.setAttribute('position', new THREE.Float32BufferAttribute(tri, 3));
    const fm = new THREE.MeshBasicMaterial({ color: '#8aa4c8', transparent: true, opacity: 0.13, side: THREE.DoubleSide, depthWrite: false });
    this.groups.faces.add(new THREE.Mesh(fg, fm));
    const eg = new THREE.BufferGeometry(); eg.setAttribute('position', new THREE.Float32BufferAttribute(sc.edge_points, 3));
    this.edgeColors = new Float32Array(sc.n_edges * 6).fill(0.45);
    eg.setAttribute('color', new THREE.BufferAttribute(this.edgeColors, 3));
    this.edgeLines = new THREE.LineSegments(eg, new THREE.LineBasicMaterial({ vertexColors: true }));
    this.groups.edges.add(this.edgeLines);
    if (sc.lattice) { this.outlineCell(sc.lattice); this.blockCopies(sc, block); }
    const box = new THREE.Box3().setFromBufferAttribute(eg.getAttribute('position'));
    this.scale = box.getSize(new THREE.Vector3()).length() || 1;
    this.handles?.build(sc);
  }
  blockCopies(sc, block) { // the other cells of the block: their edges, faint and not pickable
    if (!block) return;
    const sizes = [...block, 1, 1].slice(0, 3), basis = sc.lattice, pts = [];
    for (let i = 0; i < sizes[0]; i++) for (let j = 0; j < sizes[1]; j++) for (let k = 0; k < sizes[2]; k++) {
      if (!i && !j && !k) continue;
      const t = [0, 1, 2].map((a) => i * basis[0][a] + j * (basis[1] ? basis[1][a] : 0) + k * (basis[2] ? basis[2][a] : 0));
      for (let x = 0; x < sc.edge_points.length; x++) pts.push(sc.edge_points[x] + t[x % 3]);
      if (pts.length > 3e6) break;
    }
    if (!pts.length) return;
    const g = new THREE.BufferGeometry(); g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
    this.groups.faces.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: '#b8c4d8', transparent: true, opacity: 0.5 })));
  }
  outlineCell(basis) {
    const v = basis.map((b) => new THREE.Vector3(b[0], b[1], b[2]));
    while (v.length < 3) v.push(new THREE.Vector3());
    const corners = [];
    for (let i = 0; i < 8; i++) corners.push(new THREE.Vector3().addScaledVector(v[0], i & 1).addScaledVector(v[1], (i >> 1) & 1).addScaledVector(v[2], (i >> 2) & 1));
    const pts = [];
    for (let i = 0; i < 8; i++) for (const bit of [1, 2, 4]) if (!(i & bit)) pts.push(corners[i], corners[i | bit]);
    const g = new THREE.BufferGeometry().setFromPoints(pts);
    this.groups.edges.add(new THREE.LineSegments(g, new THREE.LineDashedMaterial({ color: '#c07000', dashSize: 0.05, gapSize: 0.04 })).computeLineDistances());
  }
  setEdgeColors(labels, selected, pinned, errorEdge) {
    if (!this.edgeColors) return;
    const c = new THREE.Color();
    for (let e = 0; e < labels.length; e++) {
      const t = Number(labels[e]);
      c.set(e === errorEdge ? '#ff0000' : e === selected ? '#f0b000' : pinned.has(e) ? '#00a060' : t > 0 ? '#2050c0' : t < 0 ? '#c03030' : '#888888');
      for (const k of [0, 3]) { this.edgeColors[6 * e + k] = c.r; this.edgeColors[6 * e + k + 1] = c.g; this.edgeColors[6 * e + k + 2] = c.b; }
    }
    this.edgeLines.geometry.getAttribute('color').needsUpdate = true;
    this.handles?.paint(labels, selected, pinned, errorEdge);
  }
  get colors() { return this.strands.colors; }
  setStrands(curves, strands) { return this.strands.set(curves, strands); } // resolves false: ask again without `have`
  markError(point) {
    this.clear(this.groups.marks);
    if (!point) return;
    const m = new THREE.Mesh(new THREE.SphereGeometry(this.scale * 0.02, 16, 8), new THREE.MeshBasicMaterial({ color: '#ff0000', transparent: true, opacity: 0.6 }));
    m.position.set(point[0], point[1], point[2]); this.groups.marks.add(m);
  }
  fit() {
    const shown = this.groups.strands.children.length ? this.groups.strands : this.groups.edges;
    const box = new THREE.Box3().setFromObject(shown);
    if (box.isEmpty()) box.setFromObject(this.groups.edges);
    const center = box.getCenter(new THREE.Vector3()), dir = new THREE.Vector3(0.55, 0.45, 0.7).normalize();
    const dist = this.fitDistance(box.isEmpty() ? this.groups.edges : shown, center, dir) || 1;
    this.camera.position.copy(center).addScaledVector(dir, dist); this.camera.near = dist / 100; this.camera.far = dist * 10;
    this.camera.updateProjectionMatrix(); this.controls.target.copy(center); this.controls.update(); this.render();
  }
  fitDistance(group, center, dir) { // nearest camera distance along dir that shows every drawn point (up to 20,000 sampled), for the canvas aspect
    const right = new THREE.Vector3().crossVectors(this.camera.up, dir).normalize(), up = new THREE.Vector3().crossVectors(dir, right);
    const tanV = 0.94 * Math.tan((this.camera.fov * Math.PI) / 360), tanH = tanV * this.camera.aspect, d = new THREE.Vector3();
    let dist = 0;
    for (const object of group.children) {
      const pos = object.geometry?.getAttribute('position');
      if (!pos) continue;
      for (let i = 0, step = Math.ceil(pos.count / 20000); i < pos.count; i += step) {
        d.fromBufferAttribute(pos, i).sub(center);
        const z = d.dot(dir);
        dist = Math.max(dist, z + Math.abs(d.dot(right)) / tanH, z + Math.abs(d.dot(up)) / tanV);
      }
    }
    return dist;
  }
  pick(clientX, clientY) { return this.handles ? this.handles.pick(clientX, clientY) : null; } // the edge handle under a pixel
  screenOf(p) { // page coordinates of a 3D point
    const rect = this.canvas.getBoundingClientRect(); const v = new THREE.Vector3(p[0], p[1], p[2]).project(this.camera);
    return { x: rect.left + (v.x + 1) / 2 * rect.width, y: rect.top + (1 - v.y) / 2 * rect.height, z: v.z };
  }
  edgeMid(e) { const p = this.sc.edge_points; return [0, 1, 2].map((k) => (p[6 * e + k] + p[6 * e + 3 + k]) / 2); }
  render() {
    this.renderer.render(this.scene, this.camera);
    if (this.showNumbers && this.sc) this.drawNumbers(); else if (this.layer.childElementCount) this.layer.replaceChildren();
    for (const f of this.afterRender) f();
  }
  drawNumbers() {
    const sc = this.sc, rect = this.canvas.getBoundingClientRect(), out = [];
    const add = (p, text, cls) => { const s = this.screenOf(p); if (s.z < 1) out.push(`<span class="${cls}" style="left:${s.x - rect.left}px;top:${s.y - rect.top}px">${text}</span>`); };
    if (sc.n_edges <= 400) for (let e = 0; e < sc.n_edges; e++) add(this.edgeMid(e), e, 'e');
    if (sc.n_vertices <= 300) sc.vertices.forEach((v, i) => add(v, i, 'v'));
    if (sc.n_faces <= 300) for (let f = 0; f < sc.n_faces; f++) add(sc.face_centroids.slice(3 * f, 3 * f + 3), 'f' + f, 'f');
    this.layer.innerHTML = out.join('');
  }
}
