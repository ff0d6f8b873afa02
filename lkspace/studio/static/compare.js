// Two designs side by side: "pin" keeps the current design (scaffold, labels, name, components
// and its diagram) in the Compare panel while editing goes on; "load" brings a pinned one back.
import { colourStrands } from '/static/diagram.js';

const $ = (id) => document.getElementById(id);
const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
const studio = window.studio, S = studio.state;
const MAX_PINNED = 4;
const pinned = [];

function draw() {
  $('pinned').innerHTML = pinned.map((p, i) => `<div class="pinned" data-i="${i}">
    <div class="pinned-diagram">${p.svg}</div>
    <div><b class="pinned-name">${esc(p.name || 'identifying…')}</b>${p.common ? ` (${esc(p.common)})` : ''}</div>
    <div class="dim">${esc(p.scaffold)}, ${p.components} component${p.components === 1 ? '' : 's'}${p.crossings !== null ? `, ${p.crossings} crossings drawn` : ''}</div>
    <div class="dim labels">${p.labels.join(' ')}</div>
    <button data-act="load">load</button> <button data-act="drop">✕</button></div>`).join('');
  colourStrands($('pinned'));
}

$('compare-pin').onclick = () => {
  if (!S.design || !S.sc) return;
  const name = $('knot-name')?.textContent, common = $('common-name')?.textContent.replace(/^\(|\)$/g, '');
  const d = studio.diagram.answer;
  pinned.unshift({
    sig: S.identifyKey, key: S.key, scaffold: S.sc.name, labels: S.labels.slice(), nulls: [...S.nulls],
    name: name || null, common: common || null, components: S.design.components,
    svg: studio.diagram.svg, crossings: d && d.svg ? d.crossings : null,
  });
  pinned.length = Math.min(pinned.length, MAX_PINNED);
  draw();
};
// a design pinned before its name came: the name fills in when identify answers for it
document.addEventListener('studio:identified', (ev) => {
  let changed = false;
  for (const p of pinned) if (p.sig === ev.detail.key && !p.name) { p.name = ev.detail.result.name || 'unknown'; p.common = ev.detail.result.common_name; changed = true; }
  if (changed) draw();
});
$('pinned').onclick = (ev) => {
  const button = ev.target.closest('button'), card = ev.target.closest('.pinned');
  if (!button || !card) return;
  const p = pinned[+card.dataset.i];
  if (button.dataset.act === 'drop') { pinned.splice(+card.dataset.i, 1); draw(); } else studio.open(p.key, p.labels, p.nulls);
};
