// Keyboard-first editing, drag-to-scrub on an edge handle, and the help overlay (`?`) listing
// every key and mouse action.  `+`, `-`, `F`, Escape and Ctrl-Z / Ctrl-Y stay in app.js.
const $ = (id) => document.getElementById(id);
const SCRUB_PX = 12; // a drag of this many pixels changes the label by one

export const KEYS = [
  ['click an edge or its label', 'select it (its label shows at its midpoint)'],
  ['drag an edge or its label', 'scrub its label: up +1, down −1 every 12 px'],
  ['click a strand', 'light its component and the edges it passes'],
  ['click empty space', 'clear the selection and the strand'],
  ['drag / right-drag / wheel', 'orbit / pan / zoom'],
  ['N / P', 'next / previous edge (along the lit strand, if any)'],
  ['0 … 9', 'set the label to that digit'],
  ['Shift + 1 … 9', 'set the label to minus that digit'],
  ['+ / −', 'label + 1 / − 1'],
  ['Enter', 'type any label in the field (Enter sets it, Escape returns)'],
  ['O', 'orbit editing on / off: edits set the whole edge orbit'],
  ['F', 'fit the design to the view'],
  ['Ctrl-Z / Ctrl-Y', 'undo / redo'],
  ['?', 'this help'],
  ['Escape', 'close the help, or clear the selection and the strand'],
];

export function bindKeys({ S, view, handles, strands, select, setLabel, add }) {
  const help = document.createElement('div');
  help.id = 'help'; help.hidden = true;
  help.innerHTML = '<b>Keys and mouse</b> <span class="dim">(? toggles)</span><table>' +
    KEYS.map(([k, what]) => `<tr><td><kbd>${k}</kbd></td><td>${what}</td></tr>`).join('') + '</table>';
  const button = document.createElement('button');
  button.id = 'help-button'; button.textContent = '?'; button.title = 'keys and mouse (?)';
  button.onclick = () => { help.hidden = !help.hidden; };
  view.canvas.parentElement.append(help, button);

  const step = (dir) => { // the next edge in index order, or along the lit strand
    const n = S.sc ? S.sc.n_edges : 0;
    if (!n) return;
    const list = strands.strand !== null ? S.design.strands[strands.strand].edges : null;
    if (list && list.length) {
      const i = list.indexOf(S.selected);
      select(list[i < 0 ? (dir > 0 ? 0 : list.length - 1) : (i + dir + list.length) % list.length]);
    } else select(S.selected === null ? (dir > 0 ? 0 : n - 1) : (S.selected + dir + n) % n);
  };

  // capture: runs before app.js's handler, so Escape with the help open only closes the help
  document.addEventListener('keydown', (ev) => {
    const el = document.activeElement;
    if (el === $('label') && ev.key === 'Escape') { el.blur(); ev.stopPropagation(); return; }
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    if (['INPUT', 'SELECT', 'TEXTAREA'].includes(el?.tagName) && el.type !== 'checkbox') return;
    const t0 = performance.now(), digit = /^Digit(\d)$/.exec(ev.code)?.[1] ?? (/^\d$/.test(ev.key) ? ev.key : null);
    if (ev.key === '?') { help.hidden = !help.hidden; }
    else if (ev.key === 'Escape') {
      if (!help.hidden) { help.hidden = true; ev.stopPropagation(); return; }
      strands.clear();
      return; // app.js clears the selection
    } else if (ev.key === 'n' || ev.key === 'N') step(1);
    else if (ev.key === 'p' || ev.key === 'P') step(-1);
    else if (ev.key === 'o' || ev.key === 'O') $('orbit').click();
    else if (digit !== null && S.selected !== null && !(ev.shiftKey && digit === '0')) setLabel(ev.shiftKey ? -Number(digit) : Number(digit), t0);
    else if (ev.key === 'Enter' && S.selected !== null && el?.tagName !== 'BUTTON') { $('label').focus(); $('label').select(); }
    else return;
    ev.preventDefault();
  }, true);
  $('label').addEventListener('keydown', (ev) => { if (ev.key === 'Enter') setTimeout(() => $('label').blur()); });

  // scrub: a drag that starts on a handle changes its label (one undo step for the whole drag)
  let scrub = null;
  const labelOf = (el) => (el?.parentElement === handles.layer ? Number(el.dataset.edge) : null); // a label drawn at a midpoint
  view.canvas.parentElement.addEventListener('pointerdown', (ev) => {
    if (ev.button !== 0) return;
    const e = ev.target === view.canvas ? handles.pick(ev.clientX, ev.clientY) : labelOf(ev.target);
    if (e === null) return;
    view.controls.enabled = false; // captured before OrbitControls sees the press
    scrub = { e, y: ev.clientY, base: S.labels[e], steps: 0, undo: S.undo.length };
    if (S.selected !== e) select(e);
  }, true);
  window.addEventListener('pointermove', (ev) => {
    if (!scrub) {
      if (!ev.buttons && labelOf(ev.target) !== null) handles.hover(labelOf(ev.target));
      else if (ev.target === view.canvas && !ev.buttons) hoverAt(ev.clientX, ev.clientY);
      return;
    }
    const steps = Math.round((scrub.y - ev.clientY) / SCRUB_PX);
    if (steps === scrub.steps) return;
    scrub.steps = steps;
    setLabel(add(scrub.base, steps), performance.now());
    S.undo.splice(scrub.undo + 1); // keep one undo step: the labels before the drag
  });
  window.addEventListener('pointerup', () => { if (scrub) { scrub = null; view.controls.enabled = true; } });

  let pending = null; // hover: at most one pick a frame
  function hoverAt(x, y) {
    if (pending) { pending = [x, y]; return; }
    pending = [x, y];
    requestAnimationFrame(() => {
      const [px, py] = pending; pending = null;
      const e = handles.pick(px, py);
      view.canvas.style.cursor = e === null ? '' : 'ns-resize';
      handles.hover(e);
    });
  }
  view.canvas.addEventListener('pointerleave', () => { handles.hover(null); });
}
