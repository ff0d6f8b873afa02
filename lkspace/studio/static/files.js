// Save, open and share designs: design files (the server writes and reads them), the link in the URL
// hash (scaffold, labels, nulls, block and camera), and the PNG of the view as it is on screen.
// File names come from the server (/api/filename), so page and server downloads agree.

const $ = (id) => document.getElementById(id);

// ---- the camera: position, target, up
export function cameraOf(view) {
  return { position: view.camera.position.toArray(), target: view.controls.target.toArray(), up: view.camera.up.toArray() };
}
export function setCamera(view, cam) {
  const [p, t] = [cam.position, cam.target];
  view.camera.up.fromArray(cam.up || [0, 1, 0]).normalize();
  view.camera.position.fromArray(p); view.controls.target.fromArray(t);
  const dist = Math.hypot(p[0] - t[0], p[1] - t[1], p[2] - t[2]) || 1;
  view.camera.near = dist / 100; view.camera.far = dist * 10; view.camera.updateProjectionMatrix();
  view.camera.lookAt(view.controls.target); view.controls.update(); view.render();
}
function cameraText(view) { // position and target to 1/10,000 of the viewing distance; up only when it is not +y
  const c = cameraOf(view), up = c.up.every((x, i) => Math.abs(x - [0, 1, 0][i]) < 1e-9) ? [] : c.up;
  const dist = view.camera.position.distanceTo(view.controls.target) || 1;
  const digits = Math.min(12, Math.max(0, 4 - Math.floor(Math.log10(dist))));
  return [...c.position, ...c.target].map((x) => String(+x.toFixed(digits))).concat(up.map((x) => String(+x.toFixed(4)))).join(',');
}
function parseCamera(text) {
  const v = text.split(',').map(Number);
  if ((v.length !== 6 && v.length !== 9) || text.split(',').some((x) => x.trim() === '') || !v.every(Number.isFinite)) return null;
  const cam = { position: v.slice(0, 3), target: v.slice(3, 6), up: v.length === 9 ? v.slice(6) : [0, 1, 0] };
  if (cam.position.every((x, i) => x === cam.target[i]) || cam.up.every((x) => x === 0)) return null;
  return cam;
}

// ---- the link: #s=scaffold&t=labels&n=nulls&b=block&v=camera
export function writeLink(S, view) {
  if (!S.key) return;
  const parts = [`s=${encodeURIComponent(S.key)}`, `t=${S.labels.join(',')}`];
  if (S.nulls.size) parts.push(`n=${[...S.nulls].join(',')}`);
  if (S.block) parts.push(`b=${S.block.join('x')}`);
  if (view.sc) parts.push(`v=${cameraText(view)}`);
  history.replaceState(null, '', '#' + parts.join('&'));
}

// Open the design of the link, if there is one (false: no link).  What the link gets wrong is said
// in one message and replaced by the scaffold's defaults; an unknown scaffold opens `initial` instead.
export async function openLink(ctx, initial) {
  const p = new URLSearchParams(location.hash.slice(1));
  if (!p.get('s')) return false;
  const key = p.get('s'), problems = [];
  let sc = null;
  try { sc = await ctx.api('scaffold', { key }); } catch (err) { problems.push(err.message); }
  if (!sc) {
    await ctx.loadScaffold(initial);
    ctx.message(`link: ${problems[0]} — opened ${initial} instead`);
    return true;
  }
  const ints = (name, max) => {
    const text = p.get(name === 'labels' ? 't' : 'n');
    if (!text) return null;
    const items = text.split(',');
    if (!items.every((x) => /^-?\d{1,25}$/.test(x))) { problems.push(`${name}: integers expected`); return null; }
    if (max !== undefined && items.some((x) => +x < 0 || +x > max)) { problems.push(`${name}: side indices in 0..${max} expected`); return null; }
    return items;
  };
  let labels = ints('labels');
  if (labels && labels.length !== sc.n_edges) { problems.push(`${labels.length} labels for the ${sc.n_edges} edges of ${sc.name}`); labels = null; }
  const nulls = ints('nulls', sc.n_corners - 1);
  let block = p.get('b');
  if (block && (!sc.dim || !/^\d{1,2}(x\d{1,2})*$/.test(block) || block.split('x').length !== sc.dim)) { problems.push(`block ${block.slice(0, 20)} does not fit ${sc.name}`); block = null; }
  const cam = p.get('v') ? parseCamera(p.get('v')) : null;
  if (p.get('v') && !cam) problems.push('view: 6 or 9 numbers expected');
  await ctx.loadScaffold(sc.key, labels && labels.map(ctx.norm), nulls && nulls.map(Number), block);
  if (cam) { setCamera(ctx.view, cam); writeLink(ctx.S, ctx.view); }
  if (problems.length) ctx.message(`link: ${problems.join('; ')} — the scaffold's defaults are shown instead`);
  return true;
}

// ---- downloads
export function saveBlob(blob, name) {
  const a = document.createElement('a'); a.href = URL.createObjectURL(blob); a.download = name;
  document.body.append(a); a.click(); a.remove(); setTimeout(() => URL.revokeObjectURL(a.href), 60000);
}
export async function stemOf(ctx) {
  const { S } = ctx;
  return (await ctx.api('filename', { key: S.key, labels: S.labels, nulls: [...S.nulls] })).stem;
}
async function saveDesign(ctx) {
  const { S, view } = ctx;
  const body = { key: S.key, labels: S.labels, nulls: [...S.nulls], block: S.block, view: cameraOf(view) };
  const res = await fetch('/api/design-file', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  if (!res.ok) throw new Error((await res.json()).error.message);
  const name = (res.headers.get('Content-Disposition') || '').match(/filename="([^"]+)"/)?.[1] || 'design.design.json';
  saveBlob(await res.blob(), name);
}

// Open a design file; with `onlyDesigns` false, a file that is not a design is left to the scaffold upload (false).
export async function openDesign(ctx, file, onlyDesigns = true) {
  const text = await file.text();
  if (!onlyDesigns) {
    let data = null;
    try { data = JSON.parse(text); } catch { return false; }
    if (!data || data.format !== 'lkspace-design') return false;
  }
  const res = await fetch('/api/open-design', { method: 'POST', headers: { 'Content-Type': 'application/octet-stream', 'X-Filename': file.name }, body: text });
  const d = await res.json();
  if (d.error) throw new Error(d.error.message);
  await showDesign(ctx, d);
  return true;
}
export async function showDesign(ctx, d) {
  await ctx.loadScaffold(d.key, d.labels.map(ctx.norm), d.nulls, d.block ? d.block.join('x') : null);
  if (d.view) setCamera(ctx.view, d.view);
  writeLink(ctx.S, ctx.view);
}

// The canvas as drawn (preserveDrawingBuffer), at `scale` times its resolution (redrawn larger, same camera).
export async function viewPng(view, scale = 1) {
  const r = view.renderer, ratio = r.getPixelRatio(), el = view.canvas.parentElement;
  if (scale !== 1) { r.setPixelRatio(ratio * scale); r.setSize(el.clientWidth, el.clientHeight, false); }
  view.render();
  const blob = await new Promise((done) => view.canvas.toBlob(done, 'image/png'));
  if (scale !== 1) { r.setPixelRatio(ratio); r.setSize(el.clientWidth, el.clientHeight, false); view.render(); }
  if (!blob) throw new Error('PNG (view): the browser gave no image of the canvas');
  return blob;
}

export function installFiles(ctx) {
  const box = $('files');
  box.innerHTML = '<button id="save-design" title="scaffold, labels, nulls, block and camera as a .design.json file">save design</button>' +
    '<label class="file" title="a .design.json file saved here">open design… <input type="file" id="open-design" accept=".json"></label>' +
    '<button id="png-view" title="the view exactly as on screen">PNG (view)</button>' +
    '<label title="redraw at twice the resolution, same camera"><input type="checkbox" id="png-2x"> 2×</label>';
  const guard = (fn) => async () => { try { await fn(); } catch (err) { ctx.message(err.message); } };
  $('save-design').onclick = guard(() => saveDesign(ctx));
  $('open-design').onchange = guard(async () => {
    const file = $('open-design').files[0]; $('open-design').value = '';
    if (file) await openDesign(ctx, file);
  });
  $('png-view').onclick = guard(async () => {
    const scale = $('png-2x').checked ? 2 : 1, stem = await stemOf(ctx);
    saveBlob(await viewPng(ctx.view, scale), `${stem}_view${scale === 2 ? '-2x' : ''}.png`);
  });
  let timer = null; // a moved camera goes into the link once the motion stops
  ctx.view.controls.addEventListener('change', () => { clearTimeout(timer); timer = setTimeout(() => writeLink(ctx.S, ctx.view), 250); });
}
