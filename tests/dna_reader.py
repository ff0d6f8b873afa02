"""An independent reader of oxDNA/oxView files for the DNA export tests (shares no code with lkspace.dna).

It parses ``NAME.top`` (new format), ``NAME.dat`` and ``NAME.oxview`` and measures what a
user of oxDNA would: backbone sites, linking numbers by counting signed crossings of a
projection, base-pair geometry.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

PAIRS = {("A", "T"), ("T", "A"), ("C", "G"), ("G", "C")}


@dataclass
class OxDNA:
    """What the three files say: strands (5' -> 3' sequences), per-nucleotide frame, pairs from oxView."""

    sequences: list[str]
    circular: list[bool]
    box: np.ndarray
    r: np.ndarray
    a1: np.ndarray
    a3: np.ndarray
    pair: np.ndarray
    view_types: str

    @property
    def starts(self) -> np.ndarray:
        return np.concatenate([[0], np.cumsum([len(s) for s in self.sequences])])

    def strand(self, k: int) -> np.ndarray:
        lo, hi = self.starts[k], self.starts[k + 1]
        return self.r[lo:hi]

    def backbone(self) -> np.ndarray:
        """oxDNA (version 1) backbone sites, ``r - 0.4 a1``."""
        return self.r - 0.4 * self.a1


def read(stem: str) -> OxDNA:
    with open(stem + ".top") as fh:
        lines = fh.read().splitlines()
    n, n_strands, direction = lines[0].split()
    assert direction == "5->3"
    sequences, circular = [], []
    for line in lines[1 : 1 + int(n_strands)]:
        seq, *tags = line.split()
        fields = dict(t.split("=") for t in tags)
        assert fields["type"] == "DNA"
        sequences.append(seq)
        circular.append(fields.get("circular") == "true")
    assert sum(map(len, sequences)) == int(n) and len(lines) == 1 + int(n_strands)
    with open(stem + ".dat") as fh:
        dat = fh.read().splitlines()
    assert dat[0] == "t = 0" and dat[1].startswith("b = ") and dat[2].startswith("E = ")
    box = np.array(dat[1].split()[2:], float)
    rows = np.array([line.split() for line in dat[3:]], float)
    assert rows.shape == (int(n), 15)
    with open(stem + ".oxview") as fh:
        view = json.load(fh)
    monomers = [m for s in view["systems"][0]["strands"] for m in s["monomers"]]
    assert [m["id"] for m in monomers] == list(range(int(n)))
    pair = np.array([m.get("bp", -1) for m in monomers])
    p = np.array([m["p"] for m in monomers])
    assert np.allclose(p, rows[:, :3], atol=1e-5)
    types = "".join(m["type"] for m in monomers)
    return OxDNA(sequences, circular, box, rows[:, :3], rows[:, 3:6], rows[:, 6:9], pair, types)


def crossings(a: np.ndarray, b: np.ndarray, direction: np.ndarray) -> int:
    """Linking number of closed polygons ``a`` and ``b``: signed crossings where ``a`` passes over ``b``.

    Both are projected along ``direction`` (generic); a crossing's sign is the right-hand
    rule of (over tangent x under tangent) . direction.
    """
    d = direction / np.linalg.norm(direction)
    u = np.cross(d, [1.0, 0, 0] if abs(d[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    v = np.cross(d, u)

    def segs(p):
        q = np.roll(p, -1, axis=0)
        return p, q

    a0, a1 = segs(a)
    b0, b1 = segs(b)
    P = lambda x: np.stack([x @ u, x @ v], -1)  # noqa: E731
    pa, qa, pb, qb = P(a0), P(a1), P(b0), P(b1)
    ra = qa - pa
    rb = qb - pb
    denom = ra[:, None, 0] * rb[None, :, 1] - ra[:, None, 1] * rb[None, :, 0]
    w = pb[None, :, :] - pa[:, None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[..., 0] * rb[None, :, 1] - w[..., 1] * rb[None, :, 0]) / denom
        t = (w[..., 0] * ra[:, None, 1] - w[..., 1] * ra[:, None, 0]) / denom
    hit = (s >= 0) & (s < 1) & (t >= 0) & (t < 1)
    i, j = np.nonzero(hit)
    za = (a0[i] + s[i, j, None] * (a1[i] - a0[i])) @ d
    zb = (b0[j] + t[i, j, None] * (b1[j] - b0[j])) @ d
    over = za > zb  # a nearer the viewer (larger along d)
    ta, tb = a1[i] - a0[i], b1[j] - b0[j]
    sign = np.sign(np.einsum("ij,j->i", np.cross(ta, tb), d))
    # a over b with (ta x tb).d > 0 is a positive crossing when viewed from +d
    return int(np.sum(sign[over]))
