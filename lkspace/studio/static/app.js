// The studio page: state, edits, panels.  Every answer (strands, components, names, solutions,
// catalog rows, files) comes from the server's Python API; the page only draws and edits labels.
import { View } from '/static/view.js';
import { Handles } from '/static/handles.js';
import { StrandPicker } from '/static/strandpick.js';
import { bindKeys } from '/static/keys.js';
import { installFiles, openDesign, openLink, showDesign, writeLink } from '/static/files.js';
import { installAnimate } from '/static/animate.js';
import { installLayout } from '/static/layout.js';

const $ = (id) => document.getElementById(id);
const S = {
  key: null, sc: null, labels: [], nulls: new Set(), block: null, selected: null, pins: new Map(),
  undo: [], redo: [], seq: 0, design: null, latencies: [], ready: false, identifyTimer: null, identifyKey: null,
  solveJob: null, catalog: { filters: [], sort: null, desc: false, offset: 0, limit: 25, total: 0 },
};
const view = new View($('canvas'), $('labels-layer'));
const handles = new Handles(view, S), strands = new StrandPicker(view, handles, S);
window.studio = { state: S, view, edgeScreen: (e) => view.screenOf(view.edgeMid(e)), colors: () => view.colors };
Object.assign(window.studio, { handles, strands });

// this page's id: its jobs (identify, clearance, relax, solve) replace only its own, never another tab's
const PAGE = Math.random().toString(36).slice(2, 12) + Date.now().toString(36);
async function api(path, body) {
  const headers = { 'X-Lkspace-Page': PAGE, ...(body === undefined ? {} : { 'Content-Type': 'application/json' }) };
  const res = await fetch('/api/' + path, body === undefined ? { headers } : { method: 'POST', headers, body: JSON.stringify(body) });
  const data = await res.json().catch(() => ({ error: { message: `HTTP ${res.status}` } }));
  if (data && data.error && typeof data.error === 'object') throw Object.assign(new Error(data.error.message), { status: res.status }); // a job's own `error` is text
  return data;
}
const transient = (err) => err.status === 409 || err.status === 429; // superseded or busy: worth asking again
function message(text) { $('message').hidden = !text; $('message').textContent = text || ''; }
function esc(s) { return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]); }

// ---- labels as exact integers (numbers, or decimal strings past 2**53)
function norm(v) { const b = BigInt(v); return (b > 9007199254740991n || b < -9007199254740991n) ? b.toString() : Number(b); }
function add(v, d) { return norm(BigInt(v) + BigInt(d)); }
function parseSet(text) {
  const m = text.trim().match(/^(-?\d+)\s*\.\.\s*(-?\d+)$/);
  let out;
  if (m) { const lo = +m[1], hi = +m[2]; if (hi < lo || hi - lo > 1000) throw new Error(`label set ${text}: a range of at most 1001 labels`); out = []; for (let t = lo; t <= hi; t++) out.push(t); }
  else out = text.split(',').map((x) => { if (!/^\s*-?\d+\s*$/.test(x)) throw new Error(`label set ${text}: integers like -2..2 or -1,1`); return +x; });
  return out;
}

// ---- history
function snapshot() { return { key: S.key, labels: S.labels.slice(), nulls: [...S.nulls], block: S.block && S.block.join('x') }; }
function edit(fn, t0 = performance.now()) {
  S.undo.push(snapshot()); S.redo = [];
  fn(); update(t0);
}
function restore(from, to) {
  if (!from.length) return; to.push(snapshot()); const s = from.pop();
  if (s.key !== S.key) { // a scaffold switch: back to that scaffold with its labels (put back if it cannot open)
    loadScaffold(s.key, s.labels, s.nulls, s.block, true).then((ok) => { if (!ok) { from.push(s); to.pop(); } });
    return;
  }
  S.labels = s.labels; S.nulls = new Set(s.nulls); update(performance.now());
}

// ---- loading
// a switch is an edit (undo brings the previous scaffold back) unless it is the undo itself (keepHistory)
async function loadScaffold(key, labels, nulls, block, keepHistory = false) {
  const mine = S.loadSeq = (S.loadSeq || 0) + 1;
  try {
    const sc = await api('scaffold', { key });
    if (mine !== S.loadSeq) return true; // a newer switch is on its way
    if (S.sc && !keepHistory) { S.undo.push(snapshot()); S.redo = []; }
    if (sc.key !== S.key) dropSolve();
    S.key = sc.key; S.sc = sc; S.selected = null; S.orbits = null; $('orbit').checked = false; S.pins = new Map();
    S.labels = labels && labels.length === sc.n_edges ? labels.map(norm) : sc.labels ? sc.labels.map(norm) : new Array(sc.n_edges).fill(1);
    S.nulls = new Set(nulls || sc.nulls || []);
    $('block-row').hidden = !sc.dim;
    if (sc.dim) $('block').value = block || sc.block.join('x'); // the server's block fits its bound on faces
    S.block = sc.dim ? $('block').value.split('x').map(Number) : null;
    nameInMenu(sc);
    $('scaffold-info').textContent = `${sc.name}: ${sc.n_vertices} vertices, ${sc.n_edges} edges, ${sc.n_faces} faces${sc.dim ? ` (periodic, ${sc.dim}D)` : ''} — ${sc.origin}`;
    view.setScaffold(sc, S.block);
    await update(performance.now());
    if (mine !== S.loadSeq) return true; // a newer switch (an opened design) came meanwhile: its camera stays
    view.fit(); panelEdge();
    return true;
  } catch (err) { message(err.message); if (S.key) $('builtin').value = S.key; return false; } // the menu keeps naming what is shown
}
function nameInMenu(sc) { // an option for a file, an upload or a supercell the menu does not list
  const menu = $('builtin');
  if (![...menu.options].some((o) => o.value === sc.key)) menu.add(new Option(sc.key.startsWith('id:') ? `${sc.name} (${sc.origin})` : sc.key, sc.key));
  menu.value = sc.key;
}

// ---- the redraw: trace + realize on the server, tubes here
async function update(t0) {
  const seq = ++S.seq; $('busy').hidden = false;
  clearTimeout(S.measureTimer); // an edit is on its way: the last design's clearance would only compete with it
  const body = { key: S.key, labels: S.labels, nulls: [...S.nulls], block: S.block };
  if (identifyKey(body) !== S.identifyKey) pending(); // the read-out names the last design: say so at once
  let d;
  try { d = await api('design', { ...body, have: view.strands.have() }); } catch (err) { if (seq === S.seq) { message(err.message); $('busy').hidden = true; } return; }
  if (seq !== S.seq) return; // a newer edit is on its way: this answer is stale
  const t1 = performance.now();
  if (!(await view.setStrands(d.curves || null, d.strands))) { // a curve it sent as held was dropped meanwhile: ask for all
    try { d = await api('design', body); } catch (err) { if (seq === S.seq) { message(err.message); $('busy').hidden = true; } return; }
    await view.setStrands(d.curves || null, d.strands);
  }
  if (seq !== S.seq) return;
  S.design = d; S.labels = d.labels.map(norm); $('right').classList.remove('pending');
  const t2 = performance.now();
  view.markError(null);
  message(d.failure ? d.failure.message : '');
  view.setEdgeColors(S.labels, S.selected, S.pins, d.failure ? d.failure.edge : null);
  view.render();
  const ms = performance.now() - t0; S.latencies.push(ms);
  S.breakdown = { answer: t1 - t0, tubes: t2 - t1, render: performance.now() - t2 };
  $('busy').hidden = true;
  $('timing').textContent = `redraw ${ms.toFixed(0)} ms: answer ${S.breakdown.answer.toFixed(0)} (trace ${(d.timing.trace * 1000).toFixed(0)}, realize ${(d.timing.realize * 1000).toFixed(0)} on the server), tubes ${S.breakdown.tubes.toFixed(0)}, draw ${S.breakdown.render.toFixed(0)} ms`;
  panelRead(d); panelEdge(); writeLink(S, view);
  $('clearance').textContent = d.failure ? 'clearance: not measured (no embedding)' : 'clearance: measuring…'; // never the last design's
  document.dispatchEvent(new CustomEvent('studio:design', { detail: { seq, body, design: d } })); // diagram.js, compare.js
  S.ready = true;
  if (!d.failure) S.measureTimer = setTimeout(() => measure(seq, body), 200);
  scheduleIdentify(body);
  $('relax-status').textContent = '';
  S.shown = d.curves || null;
  if ($('relaxed').checked && !d.failure) relaxDraw(seq, body);
}

// ---- relaxed curves: asked for after the default ones are drawn; an answer for an older design is dropped
async function relaxDraw(seq, body) {
  $('relax-status').textContent = 'relaxing…';
  let d;
  try { d = await api('design', { ...body, relax: true }); } catch (err) { if (seq === S.seq) $('relax-status').textContent = 'relax: ' + err.message; return; }
  if (seq !== S.seq || !$('relaxed').checked) return; // stale: the design or the toggle changed meanwhile
  await view.setStrands(d.curves, d.strands); view.render(); S.shown = d.curves;
  const c = d.clearance;
  $('relax-status').textContent = `relaxed in ${d.timing.realize.toFixed(1)} s, clearance ${c.min_distance === null ? '—' : c.min_distance.toFixed(3)}${c.ok ? '' : ' (too close)'}`;
}

function pending() { // an edit on its way: the name, matrix and counts shown are the last design's
  clearTimeout(S.identifyTimer); S.identifyKey = null;
  $('identify').textContent = 'identify: waiting for the redraw…'; $('linking').innerHTML = '';
  $('clearance').textContent = 'clearance: waiting for the redraw…'; $('right').classList.add('pending');
}

async function measure(seq, body, tries = 0) {
  $('clearance').textContent = 'clearance: measuring…';
  try {
    const c = await api('clearance', body);
    if (seq !== S.seq) return;
    if (c.ok) { $('clearance').textContent = `clearance ${c.min_distance === null || !isFinite(c.min_distance) ? '—' : c.min_distance.toFixed(3)} ≥ ${c.min_separation.toFixed(3)}: embedded`; return; }
    $('clearance').textContent = 'clearance: too close';
    clearTimeout(S.identifyTimer); S.identifyKey = null; $('identify').textContent = 'identify: no embedding to identify'; $('linking').innerHTML = '';
    message(c.message); view.setEdgeColors(S.labels, S.selected, S.pins, c.edge); view.markError(view.edgeMid(c.edge)); view.render();
  } catch (err) {
    if (seq !== S.seq) return;
    if (transient(err) && tries < 5) { S.measureTimer = setTimeout(() => measure(seq, body, tries + 1), 500 * (tries + 1)); return; } // stopped or busy: ask again
    $('clearance').textContent = 'clearance: ' + err.message;
  }
}

function identifyKey(body) { return JSON.stringify([body.key, body.labels, [...body.nulls].sort((a, b) => a - b)]); }
function scheduleIdentify(body, tries = 0) {
  const key = identifyKey(body);
  if (key === S.identifyKey && !tries) return; // the same design: keep its answer (or the identification under way)
  clearTimeout(S.identifyTimer); S.identifyKey = key;
  $('identify').textContent = S.sc.dim ? 'periodic: an infinite structure (no knot name)' : 'identify: waiting…';
  $('linking').innerHTML = '';
  if (S.design && S.design.failure && !S.sc.dim) $('identify').textContent = 'identify: no embedding to identify';
  if (S.sc.dim || (S.design && S.design.failure)) return;
  S.identifyTimer = setTimeout(async () => {
    try {
      const { job } = await api('identify', body);
      if (S.identifyKey !== key) return; // stale: the design changed (the server stops the job)
      $('identify').textContent = 'identify: running…';
      for (;;) {
        await new Promise((r) => setTimeout(r, 250));
        if (S.identifyKey !== key) return; // stale: the design changed
        const j = await api('job/' + job);
        if (S.identifyKey !== key) return;
        if (j.state === 'running') continue;
        if (j.state === 'cancelled' && tries < 5) { scheduleIdentify(body, tries + 1); return; } // stopped, not by this page's newer design: ask again
        if (j.state !== 'done') { $('identify').textContent = 'identify: ' + (j.error || j.state); if (j.state === 'cancelled') S.identifyKey = null; return; }
        const r = j.result;
        const least = r.least_crossings ?? null, drawn = r.crossings ?? null; // the type's crossing number (tables), or only the diagram found
        const count = least !== null ? `${least} crossings` : drawn !== null ? `a diagram of ${drawn} crossings found` : 'crossings unknown';
        $('identify').innerHTML = `name: <b id="knot-name">${esc(r.name || 'unknown')}</b>${r.common_name ? ` <b id="common-name">(${esc(r.common_name)})</b>` : ''}${r.mirror ? ' (mirror)' : ''} <span class="dim">${esc(r.status)}, <span id="knot-crossings">${count}</span></span>`;
        document.dispatchEvent(new CustomEvent('studio:identified', { detail: { key, result: r } }));
        const lm = r.linking_matrix;
        if (lm && lm.length > 1 && lm.length <= 16) $('linking').innerHTML = '<div class="dim">linking matrix</div><table>' + lm.map((row) => '<tr>' + row.map((x) => `<td>${x}</td>`).join('') + '</tr>').join('') + '</table>';
        return;
      }
    } catch (err) {
      if (S.identifyKey !== key) return;
      if (transient(err) && tries < 5) { setTimeout(() => S.identifyKey === key && scheduleIdentify(body, tries + 1), 500 * (tries + 1)); return; } // busy: ask again
      $('identify').textContent = 'identify: ' + err.message;
    }
  }, 350);
}

// ---- panels
function panelRead(d) {
  const rows = [['components', `<b id="components">${d.components}</b>`], ['holds together', d.holds_together ? 'yes' : 'no'], ['pieces', d.pieces]];
  if (d.periodic) rows.push(['loops / threads', `${d.closed_loops} / ${d.infinite_threads}`]);
  $('summary').innerHTML = rows.map(([a, b]) => `<tr><td class="dim">${a}</td><td>${b}</td></tr>`).join('');
  const shown = d.strands.slice(0, 200);
  $('strands').innerHTML = '<tr><th></th><th>#</th><th>kind</th><th>length</th><th>period</th></tr>' + shown.map((s, k) =>
    `<tr><td><span class="swatch" style="background:${view.strands.colorOf(k)}"></span></td><td>${k}</td><td>${s.kind}</td><td>${s.length}</td><td>${s.period ? esc(JSON.stringify(s.period)) : '–'}</td></tr>`).join('') +
    (d.strands.length > shown.length ? `<tr><td colspan=5 class="dim">… ${d.strands.length - shown.length} more</td></tr>` : '');
}
function panelEdge() {
  const e = S.selected, sc = S.sc;
  if (e === null || !sc) { $('edge-info').textContent = 'click an edge'; $('sides').innerHTML = ''; return; }
  const orbit = S.orbits ? `, orbit of ${S.orbits.orbits[S.orbits.orbit_of[e]].length}` : '';
  $('edge-info').innerHTML = `edge <b id="edge-index">${e}</b> (${esc(sc.edge_names[e])}), degree ${sc.edge_degrees[e]}${orbit}; label <b id="edge-label">${S.labels[e]}</b>`;
  if (document.activeElement !== $('label')) $('label').value = S.labels[e];
  const sides = []; sc.side_edge.forEach((x, c) => { if (x === e) sides.push(c); });
  $('sides').innerHTML = sides.map((c) => `<label title="null edge-side: cut the strand of face ${sc.corner_face[c]} here"><input type="checkbox" data-side="${c}" ${S.nulls.has(c) ? 'checked' : ''}> null side of face ${sc.corner_face[c]}</label>`).join('<br>');
}
function setLabel(value, t0) {
  const e = S.selected; if (e === null) return;
  const edges = $('orbit').checked && S.orbits ? S.orbits.orbits[S.orbits.orbit_of[e]] : [e];
  edit(() => { for (const x of edges) S.labels[x] = value; }, t0);
}

// ---- events
$('canvas').addEventListener('pointerdown', (ev) => { S.down = [ev.clientX, ev.clientY]; });
$('canvas').addEventListener('click', (ev) => {
  if (S.down && Math.hypot(ev.clientX - S.down[0], ev.clientY - S.down[1]) > 4) return; // a drag, not a click
  const e = view.pick(ev.clientX, ev.clientY);
  if (e === null && strands.click(ev.clientX, ev.clientY)) return; // a strand: its component lit, the selection kept
  if (e !== null && $('sv-pin').checked) {
    if (S.pins.has(e)) S.pins.delete(e); else S.pins.set(e, S.labels[e]);
    $('sv-pins').textContent = [...S.pins].map(([x, t]) => `${x}=${t}`).join(' ');
  }
  select(e);
});
function select(e) { S.selected = e; panelEdge(); view.setEdgeColors(S.labels, S.selected, S.pins, null); view.render(); }
bindKeys({ S, view, handles, strands, select, setLabel, add });
document.addEventListener('keydown', (ev) => {
  const typing = ['INPUT', 'SELECT'].includes(document.activeElement?.tagName) && document.activeElement.type !== 'checkbox';
  if ((ev.ctrlKey || ev.metaKey) && ev.key.toLowerCase() === 'z') { ev.preventDefault(); ev.shiftKey ? restore(S.redo, S.undo) : restore(S.undo, S.redo); return; }
  if ((ev.ctrlKey || ev.metaKey) && ev.key.toLowerCase() === 'y') { ev.preventDefault(); restore(S.redo, S.undo); return; }
  if (typing) return;
  const t0 = performance.now();
  if ((ev.key === '+' || ev.key === '=') && S.selected !== null) setLabel(add(S.labels[S.selected], 1), t0);
  else if ((ev.key === '-' || ev.key === '_') && S.selected !== null) setLabel(add(S.labels[S.selected], -1), t0);
  else if (ev.key === 'f') view.fit();
  else if (ev.key === 'Escape') { S.selected = null; panelEdge(); view.setEdgeColors(S.labels, null, S.pins, null); view.render(); }
});
$('plus').onclick = () => S.selected !== null && setLabel(add(S.labels[S.selected], 1), performance.now());
$('minus').onclick = () => S.selected !== null && setLabel(add(S.labels[S.selected], -1), performance.now());
$('label').addEventListener('keydown', (ev) => {
  if (ev.key !== 'Enter' || S.selected === null) return;
  const text = $('label').value.trim();
  if (!/^[+-]?\d{1,25}$/.test(text)) { message(`label ${text.slice(0, 30)}: type an integer`); return; }
  setLabel(norm(text), performance.now());
});
$('sides').addEventListener('change', (ev) => {
  const c = Number(ev.target.dataset.side);
  edit(() => { if (ev.target.checked) S.nulls.add(c); else S.nulls.delete(c); });
});
$('set-all').onclick = () => {
  const text = $('all-value').value.trim();
  if (!/^[+-]?\d{1,25}$/.test(text)) { message('set all: type an integer'); return; }
  edit(() => { S.labels = S.labels.map(() => norm(text)); });
};
$('randomize').onclick = () => {
  let set; try { set = parseSet($('rand-set').value); } catch (err) { message(err.message); return; }
  edit(() => { S.labels = S.labels.map(() => set[Math.floor(Math.random() * set.length)]); });
};
$('orbit').onchange = async () => { // edge orbits: a symmetry search, asked for on first use
  if (!$('orbit').checked || S.orbits) { select(S.selected); return; } // on or off with the orbits known: relight
  $('edge-info').textContent = 'computing edge orbits…';
  try { const key = S.key; const o = await api('orbits', { key }); if (key === S.key) S.orbits = o; }
  catch (err) { $('orbit').checked = false; message(err.message); }
  select(S.selected); // the orbit of the selected edge lit
};
$('undo').onclick = () => restore(S.undo, S.redo);
$('redo').onclick = () => restore(S.redo, S.undo);
$('fit').onclick = () => view.fit();
$('relaxed').onchange = () => update(performance.now());
$('numbers').onchange = () => { view.showNumbers = $('numbers').checked; view.render(); };
$('builtin').onchange = () => loadScaffold($('builtin').value);
$('block').addEventListener('change', () => {
  const parts = $('block').value.trim().toLowerCase().split('x').map(Number);
  if (parts.length !== S.sc.dim || parts.some((n) => !Number.isInteger(n) || n < 1)) { message(`block: ${S.sc.dim} sizes like ${S.sc.dim === 3 ? '2x2x2' : '3x3'}`); return; }
  S.block = parts; view.setScaffold(S.sc, S.block); update(performance.now()).then(() => view.fit());
});
$('upload').onchange = async () => {
  const file = $('upload').files[0]; if (!file) return;
  try {
    if (await openDesign(ctx, file, false)) { $('upload').value = ''; return; } // a design file, not a scaffold
    const res = await fetch('/api/upload', { method: 'POST', headers: { 'Content-Type': 'application/octet-stream', 'X-Filename': file.name }, body: await file.arrayBuffer() });
    const data = await res.json(); if (data.error) throw new Error(data.error.message);
    await loadScaffold(data.key);
  } catch (err) { message(err.message); }
  $('upload').value = '';
};

// ---- solve
$('sv-go').onclick = async () => {
  const n = Number($('sv-n').value);
  const body = { key: S.key, components: n, label_set: $('sv-set').value.trim(), no_zero: $('sv-nozero').checked, objective: $('sv-objective').value || null,
    fixes: Object.fromEntries([...S.pins].map(([e, t]) => [e, Number(t)])), count: Number($('sv-count').value), time_limit: Number($('sv-limit').value) };
  $('sv-results').innerHTML = ''; $('sv-status').textContent = 'starting…';
  try {
    const { job } = await api('solve', body);
    if (body.key !== S.key) { api(`job/${job}/cancel`, {}).catch(() => {}); return; } // the scaffold changed meanwhile
    S.solveJob = job; $('sv-cancel').disabled = false;
    for (;;) {
      await new Promise((r) => setTimeout(r, 300));
      const j = await api('job/' + job);
      if (S.solveJob !== job) return;
      if (j.state === 'running') { const p = j.progress; $('sv-status').textContent = `solving… ${j.elapsed.toFixed(0)} s ${p.note ? '— ' + p.note : ''}`; continue; }
      $('sv-cancel').disabled = true; S.solveJob = null;
      if (j.state !== 'done') { $('sv-status').textContent = j.state === 'cancelled' ? 'cancelled' : 'error: ' + j.error; return; }
      const r = j.result;
      $('sv-status').innerHTML = `<span id="sv-state">${r.status}</span>: ${r.solutions.length} design${r.solutions.length === 1 ? "" : "s"} by ${r.method} in ${r.wall_time.toFixed(2)} s${r.reason ? ' — ' + esc(r.reason) : ''}`;
      $('sv-results').innerHTML = r.solutions.map((s, i) => `<li data-i="${i}">${s.components} comp.: ${s.labels.slice(0, 16).join(' ')}${s.labels.length > 16 ? ' …' : ''}</li>`).join('');
      S.solutions = r.solutions; return;
    }
  } catch (err) { $('sv-status').textContent = 'error: ' + err.message; $('sv-cancel').disabled = true; }
};
$('sv-cancel').onclick = async () => { if (S.solveJob) { const job = S.solveJob; S.solveJob = null; await api(`job/${job}/cancel`, {}).catch(() => {}); $('sv-status').textContent = 'cancelled'; $('sv-cancel').disabled = true; } };
function dropSolve() { // a solve's designs belong to the scaffold it ran on: a switch cancels it and clears them
  if (S.solveJob) api(`job/${S.solveJob}/cancel`, {}).catch(() => {});
  S.solveJob = null; S.solutions = []; $('sv-results').innerHTML = ''; $('sv-status').textContent = ''; $('sv-cancel').disabled = true;
}
$('sv-results').onclick = (ev) => { const li = ev.target.closest('li'); if (li) { const s = S.solutions[+li.dataset.i]; edit(() => { S.labels = s.labels.map(norm); }); } };

// ---- export
async function download(fmt) {
  try {
    const res = await fetch('/api/export', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ key: S.key, labels: S.labels, nulls: [...S.nulls], format: fmt }) });
    if (!res.ok) { const d = await res.json(); throw new Error(d.error.message); }
    const name = (res.headers.get('Content-Disposition') || '').match(/filename="([^"]+)"/)?.[1] || 'design.' + fmt;
    const a = document.createElement('a'); a.href = URL.createObjectURL(await res.blob()); a.download = name; document.body.append(a); a.click(); a.remove();
  } catch (err) { message(err.message); }
}

// ---- catalog
async function queryCatalog() {
  const c = S.catalog, asked = { filters: c.filters.slice(), sort: c.sort, desc: c.desc, offset: c.offset }, mine = c.seq = (c.seq || 0) + 1;
  try {
    const r = await api('catalog', { filters: c.filters, sort: c.sort, descending: c.desc, offset: c.offset, limit: c.limit });
    if (mine !== c.seq) return; // a newer query is on its way: these rows are not the ones asked for now
    if (!r.ready) { $('cat-page').textContent = 'reading catalog…'; setTimeout(queryCatalog, 500); return; }
    c.total = r.total; c.rows = r.labels; c.shown = JSON.stringify([c.filters, c.sort, c.desc, c.offset]);
    c.good = asked;
    $('cat-page').textContent = ` ${r.total ? c.offset + 1 : 0}–${c.offset + r.rows.length} of ${r.total.toLocaleString()} (${(r.seconds * 1000).toFixed(0)} ms) `;
    $('cat-table').innerHTML = '<tr>' + r.columns.map((x) => `<th>${x}</th>`).join('') + '<th>labels</th></tr>' + r.rows.map((row, i) =>
      `<tr data-i="${i}">` + row.map((v) => `<td>${esc(v)}</td>`).join('') + `<td>${r.labels[i].join(' ')}</td></tr>`).join('');
  } catch (err) { // a refused filter or sort is not kept: back to the last query the server answered
    if (mine !== c.seq) return;
    message(err.message);
    if (c.good) { Object.assign(c, c.good, { filters: c.good.filters.slice() }); drawFilters(); $('cat-sort').value = c.sort || ''; $('cat-desc').checked = c.desc; }
  }
}
function catalogControls(info) {
  $('catalog').hidden = false;
  $('cat-title').textContent = `${info.scaffold} catalog`;
  const opts = (info.columns || []).map((x) => `<option>${x}</option>`).join('');
  $('cat-col').innerHTML = opts; $('cat-sort').innerHTML = '<option value="">(row)</option>' + opts;
  $('cat-add').onclick = () => {
    const col = $('cat-col').value, op = $('cat-op').value, raw = $('cat-val').value.trim();
    const value = raw === 'true' ? true : raw === 'false' ? false : raw !== '' && !isNaN(Number(raw)) ? Number(raw) : raw;
    S.catalog.filters.push([col, op, value]); S.catalog.offset = 0; drawFilters(); queryCatalog();
  };
  $('cat-sort').onchange = () => { S.catalog.sort = $('cat-sort').value || null; S.catalog.offset = 0; queryCatalog(); };
  $('cat-desc').onchange = () => { S.catalog.desc = $('cat-desc').checked; S.catalog.offset = 0; queryCatalog(); };
  $('cat-prev').onclick = () => { S.catalog.offset = Math.max(0, S.catalog.offset - S.catalog.limit); queryCatalog(); };
  $('cat-next').onclick = () => { if (S.catalog.offset + S.catalog.limit < S.catalog.total) { S.catalog.offset += S.catalog.limit; queryCatalog(); } };
  $('cat-table').onclick = (ev) => {
    const tr = ev.target.closest('tr[data-i]'); if (!tr) return;
    const labels = S.catalog.rows[+tr.dataset.i];
    if (S.key !== S.catalog.key) loadScaffold(S.catalog.key, labels); // the catalog's own scaffold
    else edit(() => { S.labels = labels.map(norm); });
  };
  queryCatalog();
}
function drawFilters() {
  $('cat-filters').innerHTML = S.catalog.filters.map((f, i) => `<span class="filter" data-i="${i}" title="remove">${esc(f.join(' '))} ✕</span>`).join('');
}
$('cat-filters').onclick = (ev) => { const x = ev.target.closest('.filter'); if (x) { S.catalog.filters.splice(+x.dataset.i, 1); S.catalog.offset = 0; drawFilters(); queryCatalog(); } };

// ---- open a design from another panel (lookup.js, compare.js): same scaffold -> an undoable edit
window.studio.open = (key, labels, nulls) => (key === S.key
  ? edit(() => { S.labels = labels.map(norm); S.nulls = new Set(nulls || []); })
  : loadScaffold(key, labels, nulls));

// ---- start
const ctx = { S, view, api, message, loadScaffold, norm };
installFiles(ctx); installAnimate(ctx); installLayout();
(async () => {
  const info = await api('info');
  view.strands.setPalette(info.palette);
  $('builtin').innerHTML = info.builtins.map((n) => `<option>${esc(n)}</option>`).join('');
  $('exports').innerHTML = info.exports.map((f) => `<button data-format="${f}">${f.toUpperCase()}</button>`).join('');
  $('exports').onclick = (ev) => { const f = ev.target.dataset.format; if (f) download(f); };
  if (info.catalog) { S.catalog.key = info.initial; catalogControls(info.catalog); }
  if (!(await openLink(ctx, info.initial))) { if (info.design) await showDesign(ctx, info.design); else await loadScaffold(info.initial); }
})();
