// Builds strand tubes off the page's main thread: {id, points (base64), curves: [{key, count, closed}],
// radius, sides} in, {id, tubes: [{key, position, normal, index}]} out (buffers transferred, not copied).
import { decodeCurves, tubeArrays } from '/static/tubes.js';

self.onmessage = (ev) => {
  const { id, points, curves, radius, sides } = ev.data;
  const pts = decodeCurves(points, curves.map((c) => c.count)), tubes = [], buffers = [];
  curves.forEach((c, i) => {
    const t = tubeArrays(pts[i], c.closed, radius, sides);
    tubes.push({ key: c.key, ...t }); buffers.push(t.position.buffer, t.normal.buffer, t.index.buffer);
  });
  self.postMessage({ id, tubes }, buffers);
};
