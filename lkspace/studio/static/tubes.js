// Tube around one polyline: positions, normals and triangle indices as typed arrays (no three.js,
// so a worker can build it).  Rotation-minimizing frames by double reflection (Wang et al. 2008),
// `sides` vertices around each point; plain arithmetic on typed arrays, no per-point objects.
export function tubeArrays(points, closed, radius, sides) {
  const n = points.length / 3, rings = closed ? n : n - 1;
  const position = new Float32Array(n * sides * 3), normal = new Float32Array(n * sides * 3);
  const index = n * sides > 65535 ? new Uint32Array(Math.max(rings, 0) * sides * 6) : new Uint16Array(Math.max(rings, 0) * sides * 6);
  const cosv = new Float64Array(sides), sinv = new Float64Array(sides);
  for (let s = 0; s < sides; s++) { cosv[s] = Math.cos(2 * Math.PI * s / sides); sinv[s] = Math.sin(2 * Math.PI * s / sides); }
  let tx = 0, ty = 0, tz = 0, rx = 0, ry = 0, rz = 0;
  for (let i = 0; i < n; i++) {
    const a = closed ? (i - 1 + n) % n : Math.max(i - 1, 0), b = closed ? (i + 1) % n : Math.min(i + 1, n - 1);
    let ux = points[3 * b] - points[3 * a], uy = points[3 * b + 1] - points[3 * a + 1], uz = points[3 * b + 2] - points[3 * a + 2];
    const ul = Math.hypot(ux, uy, uz) || 1; ux /= ul; uy /= ul; uz /= ul;
    if (i === 0) { // any unit vector perpendicular to the first tangent
      rx = Math.abs(ux) < 0.9 ? 1 : 0; ry = rx ? 0 : 1; rz = 0;
      const d = rx * ux + ry * uy; rx -= d * ux; ry -= d * uy; rz -= d * uz;
    } else {
      const vx = points[3 * i] - points[3 * i - 3], vy = points[3 * i + 1] - points[3 * i - 2], vz = points[3 * i + 2] - points[3 * i - 1];
      const c1 = vx * vx + vy * vy + vz * vz;
      if (c1 > 1e-20) {
        let k = 2 * (vx * rx + vy * ry + vz * rz) / c1;
        const lx = rx - k * vx, ly = ry - k * vy, lz = rz - k * vz;
        k = 2 * (vx * tx + vy * ty + vz * tz) / c1;
        const wx = ux - (tx - k * vx), wy = uy - (ty - k * vy), wz = uz - (tz - k * vz);
        const c2 = wx * wx + wy * wy + wz * wz;
        k = c2 > 1e-20 ? 2 * (wx * lx + wy * ly + wz * lz) / c2 : 0;
        rx = lx - k * wx; ry = ly - k * wy; rz = lz - k * wz;
      }
    }
    const rl = Math.hypot(rx, ry, rz) || 1; rx /= rl; ry /= rl; rz /= rl;
    tx = ux; ty = uy; tz = uz;
    const bx = ty * rz - tz * ry, by = tz * rx - tx * rz, bz = tx * ry - ty * rx;
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

// The points of the curves an answer sent (base64 little-endian float32), one Float32Array per curve.
export function decodeCurves(b64, counts) {
  const bin = atob(b64), bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  const all = new Float32Array(bytes.buffer), out = [];
  let start = 0;
  for (const n of counts) { out.push(all.subarray(3 * start, 3 * (start + n))); start += n; }
  return out;
}
