// Catalog rows with a picture and a name: each row the catalog table shows gets a small
// drawing of its design (POST /api/thumbnails, drawn on the server for visible rows only,
// kept on both sides), and the knot_name column gets the common name (L6a4 -> Borromean rings).
import { colourStrands } from '/static/diagram.js';

const $ = (id) => document.getElementById(id);
const S = window.studio.state;
const kept = new Map(); // labels -> {svg, common}
let waiting = new Set(), timer = null;

function paint(tr, got) {
  const cell = tr.querySelector('td.thumb');
  if (cell && !cell.dataset.done) { cell.innerHTML = got.svg; colourStrands(cell); cell.dataset.done = '1'; }
  const name = tr.querySelector('td.knot-name');
  if (name && got.common && !name.dataset.done) { name.dataset.done = '1'; name.insertAdjacentHTML('beforeend', ` <span class="dim">(${got.common.replace(/[&<>"]/g, '')})</span>`); }
}

async function fetchWaiting() {
  const rows = [...waiting].filter((tr) => tr.isConnected); waiting = new Set();
  const want = rows.filter((tr) => !kept.has(tr.dataset.labels)).slice(0, 50);
  if (want.length) {
    const nameOf = (tr) => tr.querySelector('td.knot-name')?.textContent || null;
    try {
      const res = await fetch('/api/thumbnails', { method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify({ key: S.catalog.key, designs: want.map((tr) => JSON.parse(tr.dataset.labels)), names: want.map(nameOf) }) });
      const r = await res.json();
      if (r.error) throw new Error(r.error.message);
      want.forEach((tr, i) => kept.set(tr.dataset.labels, { svg: r.thumbs[i], common: r.common_names[i] }));
    } catch (err) { for (const tr of want) { const c = tr.querySelector('td.thumb'); if (c) c.title = err.message; } }
  }
  for (const tr of rows) if (kept.has(tr.dataset.labels)) paint(tr, kept.get(tr.dataset.labels));
}

const seen = new IntersectionObserver((entries) => {
  for (const e of entries) if (e.isIntersecting) { waiting.add(e.target); seen.unobserve(e.target); }
  clearTimeout(timer); timer = setTimeout(fetchWaiting, 40);
});

// a new page of rows: add the picture column, mark the name column, watch the rows
new MutationObserver(() => {
  const table = $('cat-table'), head = table.querySelector('tr');
  if (!head || head.querySelector('th.thumb')) return;
  const nameAt = [...head.children].findIndex((th) => th.textContent === 'knot_name');
  head.insertAdjacentHTML('afterbegin', '<th class="thumb"></th>');
  for (const tr of table.querySelectorAll('tr[data-i]')) {
    const labels = S.catalog.rows?.[+tr.dataset.i];
    if (!labels) continue;
    tr.dataset.labels = JSON.stringify(labels);
    if (nameAt >= 0 && tr.children[nameAt]?.textContent) tr.children[nameAt].classList.add('knot-name');
    tr.insertAdjacentHTML('afterbegin', '<td class="thumb"></td>');
    if (kept.has(tr.dataset.labels)) paint(tr, kept.get(tr.dataset.labels)); else seen.observe(tr);
  }
}).observe($('cat-table'), { childList: true });
