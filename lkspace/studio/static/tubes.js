// Tube around one polyline: positions, normals and triangle indices as typed arrays (no three.js,
// so a worker can build it).  Rotation-minimizing frames by double reflection (Wang et al. 2008),
// `sides` vertices around each point; plain arithmetic on typed arrays, no per-point objects.
// A closed curve's frame comes back around turned by its total twist; that angle is spread
// evenly along the curve, so the tube has no seam (a pinch where the last ring meets the first).
export function tubeArrays(points, closed, radius, sides) {
  const n = points.length / 3, rings = closed ? n : n - 1;
  const position = new Float32Array(n * sides * 3), normal = new Float32Array(n * sides * 3);
  const index = n * sides > 65535 ? new Uint32Array(Math.max(rings, 0) * sides * 6) : new Uint16Array(Math.max(rings, 0) * sides * 6);
  const cosv = new Float64Array(sides), sinv = new Float64Array(sides);
  for (let s = 0; s < sides; s++) { cosv[s] = Math.cos(2 * Math.PI * s / sides); sinv[s] = Math.sin(2 * Math.PI * s / sides); }
  const T = new Float64Array(3 * n), R = new Float64Array(3 * n); // unit tangent and frame vector at each point
  for (let i = 0; i < n; i++) {
    const a = closed ? (i - 1 + n) % n : Math.max(i - 1, 0), b = closed ? (i + 1) % n : Math.min(i + 1, n - 1);
    const ux = points[3 * b] - points[3 * a], uy = points[3 * b + 1] - points[3 * a + 1], uz = points[3 * b + 2] - points[3 * a + 2];
    const ul = Math.hypot(ux, uy, uz) || 1;
    T[3 * i] = ux / ul; T[3 * i + 1] = uy / ul; T[3 * i + 2] = uz / ul;
  }
  if (n > 0) { // any unit vector perpendicular to the first tangent
    const rx = Math.abs(T[0]) < 0.9 ? 1 : 0, ry = rx ? 0 : 1, d = rx * T[0] + ry * T[1];
    R[0] = rx - d * T[0]; R[1] = ry - d * T[1]; R[2] = -d * T[2];
    normalize(R, 0);
  }
  for (let i = 1; i < n; i++) transport(points, T, R, i - 1, i, R, 3 * i);
  let twist = 0;
  if (closed && n > 2) { // the last frame carried on to the first point, against the first frame
    const back = new Float64Array(3);
    transport(points, T, R, n - 1, 0, back, 0);
    const cx = R[1] * back[2] - R[2] * back[1], cy = R[2] * back[0] - R[0] * back[2], cz = R[0] * back[1] - R[1] * back[0];
    twist = Math.atan2(cx * T[0] + cy * T[1] + cz * T[2], R[0] * back[0] + R[1] * back[1] + R[2] * back[2]);
  }
  for (let i = 0; i < n; i++) {
    const tx = T[3 * i], ty = T[3 * i + 1], tz = T[3 * i + 2];
    let rx = R[3 * i], ry = R[3 * i + 1], rz = R[3 * i + 2];
    let bx = ty * rz - tz * ry, by = tz * rx - tx * rz, bz = tx * ry - ty * rx;
    if (twist) { // turn this ring back by its share of the twist
      const c = Math.cos(-twist * i / n), sn = Math.sin(-twist * i / n);
      [rx, ry, rz, bx, by, bz] = [c * rx + sn * bx, c * ry + sn * by, c * rz + sn * bz, c * bx - sn * rx, c * by - sn * ry, c * bz - sn * rz];
    }
    const px = points[3 * i], py = points[3 * i + 1], pz = points[3 * i + 2];
    for (let s = 0; s < sides; s++) {
      const nx = cosv[s] * rx + sinv[s] * bx, ny = cosv[s] * ry + sinv[s] * by, nz = cosv[s] * rz + sinv[s] * bz;
      const o = 3 * (i * sides + s);
      position[o] = px + radius * nx; position[o + 1] = py + radius * ny; position[o + 2] = pz + radius * nz;
      normal[o] = nx; normal[o + 1] = ny; normal[o + 2] = nz;
    }
  }
  let ii = 0;
  for (let i = 0; i < rings; i++) {
    const j = (i + 1) % n;
    for (let s = 0; s < sides; s++) {
      const s2 = (s + 1) % sides, a = i * sides + s, b = i * sides + s2, c = j * sides + s, d = j * sides + s2;
      index[ii++] = a; index[ii++] = c; index[ii++] = b; index[ii++] = b; index[ii++] = c; index[ii++] = d;
    }
  }
  return { position, normal, index };
}

// The frame vector at point i carried to point j by double reflection, written to out[o..o+2] (unit).
function transport(points, T, R, i, j, out, o) {
  const vx = points[3 * j] - points[3 * i], vy = points[3 * j + 1] - points[3 * i + 1], vz = points[3 * j + 2] - points[3 * i + 2];
  let rx = R[3 * i], ry = R[3 * i + 1], rz = R[3 * i + 2];
  const c1 = vx * vx + vy * vy + vz * vz;
  if (c1 > 1e-20) {
    let k = 2 * (vx * rx + vy * ry + vz * rz) / c1;
    const lx = rx - k * vx, ly = ry - k * vy, lz = rz - k * vz;
    k = 2 * (vx * T[3 * i] + vy * T[3 * i + 1] + vz * T[3 * i + 2]) / c1;
    const wx = T[3 * j] - (T[3 * i] - k * vx), wy = T[3 * j + 1] - (T[3 * i + 1] - k * vy), wz = T[3 * j + 2] - (T[3 * i + 2] - k * vz);
    const c2 = wx * wx + wy * wy + wz * wz;
    k = c2 > 1e-20 ? 2 * (wx * lx + wy * ly + wz * lz) / c2 : 0;
    rx = lx - k * wx; ry = ly - k * wy; rz = lz - k * wz;
  }
  const d = rx * T[3 * j] + ry * T[3 * j + 1] + rz * T[3 * j + 2]; // kept perpendicular to the tangent
  out[o] = rx - d * T[3 * j]; out[o + 1] = ry - d * T[3 * j + 1]; out[o + 2] = rz - d * T[3 * j + 2];
  normalize(out, o);
}

function normalize(v, o) {
  const l = Math.hypot(v[o], v[o + 1], v[o + 2]) || 1;
  v[o] /= l; v[o + 1] /= l; v[o + 2] /= l;
}

// The points of the curves an answer sent (base64 little-endian float32), one Float32Array per curve.
export function decodeCurves(b64, counts) {
  const bin = atob(b64), bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  const all = new Float32Array(bytes.buffer), out = [];
  let start = 0;
  for (const n of counts) { out.push(all.subarray(3 * start, 3 * (start + n))); start += n; }
  return out;
}
