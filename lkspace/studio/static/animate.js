// Animations recorded from the canvas as WebM (canvas.captureStream + MediaRecorder): a turntable
// (the camera orbiting the design) and a twist (the selected edge's label stepping through a range,
// each step a real redraw: traced and realized on the server, tubes built here).  Both are bounded
// and cancellable; the design and the camera are put back afterwards.
import { saveBlob, stemOf } from '/static/files.js';

const $ = (id) => document.getElementById(id);
const FPS = 30;
const TURN_SECONDS = 4;
const STEP_SECONDS = 0.6;
const MAX_STEPS = 41;
const sleep = (ms) => new Promise((done) => setTimeout(done, ms));

function recorder(canvas) {
  const type = window.MediaRecorder && ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm'].find((t) => MediaRecorder.isTypeSupported(t));
  if (!type || !canvas.captureStream) throw new Error('this browser cannot record the canvas as video (no WebM MediaRecorder)');
  const stream = canvas.captureStream(0), track = stream.getVideoTracks()[0];
  const rec = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: 6e6 }), chunks = [];
  rec.ondataavailable = (ev) => { if (ev.data.size) chunks.push(ev.data); };
  const stopped = new Promise((done) => { rec.onstop = done; });
  rec.start();
  return {
    frame: () => track.requestFrame(),
    async finish() { rec.stop(); await stopped; track.stop(); return new Blob(chunks, { type: 'video/webm' }); },
  };
}

function parseRange(text) {
  const m = text.trim().match(/^(-?\d{1,6})\s*\.\.\s*(-?\d{1,6})$/);
  if (!m || +m[2] < +m[1]) throw new Error(`twist range ${text.slice(0, 20)}: two integers like -3..3`);
  if (+m[2] - +m[1] + 1 > MAX_STEPS) throw new Error(`twist range ${text}: at most ${MAX_STEPS} labels`);
  return [+m[1], +m[2]];
}

export function installAnimate(ctx) {
  const { S, view } = ctx;
  $('animate').innerHTML = `<div class="row"><button id="an-turn" title="the camera orbiting the design: ${TURN_SECONDS} s of WebM">turntable</button>` +
    '<button id="an-twist" title="the selected edge\'s label stepping through the range, one redraw a step (WebM)">twist</button>' +
    `<input id="an-range" size="6" value="-3..3" title="labels of the twist animation (at most ${MAX_STEPS})"><button id="an-cancel" disabled>cancel</button></div>` +
    '<div id="an-status" class="dim"></div>';
  let job = null;
  const status = (text) => { $('an-status').textContent = text; };

  async function redrawShown() { // the design's own strands again (asked for whole if the frames pushed its tubes out)
    if (await view.setStrands(S.shown || null, S.design?.strands)) return;
    const d = await ctx.api('design', { key: S.key, labels: S.labels, nulls: [...S.nulls], block: S.block });
    await view.setStrands(d.curves || null, d.strands); S.shown = d.curves || null;
  }

  async function run(name, frames) { // frames(job) draws and records, returning the recorder; saved unless cancelled
    if (job) return;
    job = { cancelled: false }; const mine = job;
    $('an-cancel').disabled = false; $('an-turn').disabled = $('an-twist').disabled = true;
    const camera = { position: view.camera.position.clone(), target: view.controls.target.clone() };
    view.controls.enabled = false;
    try {
      const stem = await stemOf(ctx);
      const rec = await frames(mine);
      const blob = await rec.finish();
      if (mine.cancelled) { status('cancelled'); return; }
      saveBlob(blob, `${stem}_${name}.webm`);
      status(`${name}: ${(blob.size / 1024).toFixed(0)} KB WebM saved`);
    } catch (err) { status(''); ctx.message(err.message); }
    finally {
      view.camera.position.copy(camera.position); view.controls.target.copy(camera.target); view.controls.enabled = true;
      await redrawShown(); view.setEdgeColors(S.labels, S.selected, S.pins, null); view.controls.update(); view.render();
      job = null; $('an-cancel').disabled = true; $('an-turn').disabled = $('an-twist').disabled = false;
    }
  }

  $('an-turn').onclick = () => run('turntable', async (mine) => {
    const rec = recorder(view.canvas), n = TURN_SECONDS * FPS, target = view.controls.target.clone();
    const start = view.camera.position.clone().sub(target), axis = view.camera.up.clone().normalize();
    for (let i = 0; i <= n && !mine.cancelled; i++) {
      view.camera.position.copy(start).applyAxisAngle(axis, (2 * Math.PI * i) / n).add(target);
      view.camera.lookAt(target); view.render(); rec.frame();
      status(`turntable: frame ${i} of ${n}`);
      await sleep(1000 / FPS);
    }
    return rec;
  });

  $('an-twist').onclick = () => {
    const e = S.selected;
    if (e === null) { ctx.message('twist: click an edge first (its label steps through the range)'); return; }
    let lo, hi;
    try { [lo, hi] = parseRange($('an-range').value); } catch (err) { ctx.message(err.message); return; }
    run(`twist-e${e}_${lo}..${hi}`, async (mine) => {
      const steps = [];
      for (let t = lo; t <= hi && !mine.cancelled; t++) { // every step traced and realized first, then played at an even pace
        status(`twist: redrawing label ${t} (${t - lo + 1} of ${hi - lo + 1})`);
        const labels = S.labels.slice(); labels[e] = t;
        steps.push({ labels, d: await ctx.api('design', { key: S.key, labels, nulls: [...S.nulls], block: S.block }) });
      }
      const rec = recorder(view.canvas);
      for (const [k, { labels, d }] of steps.entries()) {
        if (mine.cancelled) break;
        await view.setStrands(d.curves || null, d.strands); view.setEdgeColors(labels, e, S.pins, d.failure ? d.failure.edge : null); view.render(); rec.frame();
        status(`twist: edge ${e} label ${labels[e]} (${k + 1} of ${steps.length})`);
        await sleep(STEP_SECONDS * 1000);
      }
      return rec;
    });
  };

  $('an-cancel').onclick = () => { if (job) { job.cancelled = true; status('cancelling…'); } };
}
