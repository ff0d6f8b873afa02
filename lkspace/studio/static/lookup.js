// "Find designs of type …": GET /api/lookup (the atlas lkspace ships) lists the simplest designs
// of a knot or link type, by table name or common name; clicking one opens it (switching scaffold).
const $ = (id) => document.getElementById(id);
const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
let found = [];

async function find() {
  const name = $('find-name').value.trim();
  if (!name) return;
  $('find-status').textContent = 'looking…'; $('find-results').innerHTML = ''; found = [];
  const q = new URLSearchParams({ name, limit: '12' });
  if ($('find-here').checked) q.set('scaffold', window.studio.state.key);
  try {
    const res = await fetch('/api/lookup?' + q);
    const r = await res.json();
    if (r.error) throw new Error(r.error.message);
    found = r.designs;
    const common = r.common_name ? ` (${esc(r.common_name)})` : '';
    $('find-status').innerHTML = `<b>${esc(r.name)}</b>${common}: ${r.designs_total.toLocaleString()} design${r.designs_total === 1 ? '' : 's'} in ${r.found_in.length} space${r.found_in.length === 1 ? '' : 's'}, simplest ${found.length} shown`;
    $('find-results').innerHTML = found.map((d, i) => `<li data-i="${i}" title="${esc(d.command)}"><b>${esc(d.chiral_name || d.type)}</b>${d.common_name ? ` ${esc(d.common_name)}` : ''} <span class="dim">on ${esc(d.scaffold)}: ${d.labels.join(' ')}</span></li>`).join('');
  } catch (err) { $('find-status').textContent = err.message; }
}

$('find-go').onclick = find;
$('find-name').addEventListener('keydown', (ev) => { if (ev.key === 'Enter') find(); });
$('find-results').onclick = (ev) => {
  const li = ev.target.closest('li[data-i]'); if (!li) return;
  const d = found[+li.dataset.i];
  window.studio.open(d.scaffold, d.labels, []);
};
