// The knot beside the curve: the 2D diagram of the current design, seen along the 3D view.
// The server projects the realized strands and cuts the under strand at every crossing
// (POST /api/diagram); this module asks after each redraw and each turn of the view,
// colours the paths as the 3D view colours the strands and drops answers for older designs.
// With "simplified diagram" ticked it asks for the simplified diagram instead (few crossings,
// laid out as the tables draw a knot, one ink), which turning the view does not change.
const $ = (id) => document.getElementById(id);
const studio = window.studio;
const D = { seq: 0, body: null, timer: null, svg: '', answer: null, pending: false };
studio.diagram = D;

// colour the paths of a server SVG as the 3D view colours strand k
export function colourStrands(root) {
  for (const p of root.querySelectorAll('path[data-strand]')) p.setAttribute('stroke', studio.view.strands.colorOf(+p.dataset.strand));
}

function cameraAxes() { // right, up and back (towards the viewer) of the 3D camera
  const e = studio.view.camera.matrixWorld.elements;
  return [[e[0], e[1], e[2]], [e[4], e[5], e[6]], [e[8], e[9], e[10]]];
}

async function ask(body) {
  const seq = ++D.seq;
  $('diagram-info').textContent = 'diagram: drawing…';
  try {
    const simplified = $('diagram-simple').checked;
    const res = await fetch('/api/diagram', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ ...body, view: cameraAxes(), simplified }) });
    const d = await res.json();
    if (seq !== D.seq) return; // a newer design or view asked meanwhile: this answer is stale
    D.pending = false;
    if (d.error) throw new Error(d.error.message);
    D.answer = d; D.svg = d.svg || '';
    $('diagram').innerHTML = D.svg; colourStrands($('diagram'));
    $('diagram').dataset.crossings = d.svg ? d.crossings : '';
    const seenFrom = d.view === 'simplified' ? 'in the simplified diagram' : 'seen from the view';
    $('diagram-info').innerHTML = d.svg
      ? `diagram: <b id="diagram-crossings">${d.crossings}</b> crossing${d.crossings === 1 ? '' : 's'} ${seenFrom} <span class="dim">(click to enlarge)</span>`
      : d.message;
  } catch (err) { if (seq === D.seq) { D.pending = false; $('diagram').innerHTML = ''; D.svg = ''; $('diagram-info').textContent = 'diagram: ' + err.message; } }
}

function schedule(delay) {
  clearTimeout(D.timer); ++D.seq; // an answer on its way is for an older design or view
  D.pending = !!D.body;
  if (D.body) D.timer = setTimeout(() => ask(D.body), delay);
}

document.addEventListener('studio:design', (ev) => {
  const { body, design } = ev.detail;
  if (design.failure || !design.curves) { ++D.seq; D.body = null; D.pending = false; D.svg = ''; $('diagram').innerHTML = ''; $('diagram-info').textContent = 'diagram: no curves to draw'; return; }
  D.body = { key: body.key, labels: body.labels, nulls: body.nulls };
  schedule(120);
});
studio.view.controls.addEventListener('end', () => { if (!$('diagram-simple').checked) schedule(60); }); // the view turned: see the knot from there
$('diagram-simple').onchange = () => schedule(0);

$('diagram').onclick = () => { if (!D.svg) return; $('diagram-big').innerHTML = D.svg; colourStrands($('diagram-big')); $('diagram-big').hidden = false; };
$('diagram-big').onclick = () => { $('diagram-big').hidden = true; };
document.addEventListener('keydown', (ev) => { if (ev.key === 'Escape') $('diagram-big').hidden = true; });
