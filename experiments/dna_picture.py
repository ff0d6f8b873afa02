"""Draw a design's DNA (backbones and base pairs) as a PNG: docs/dna-cube.png.

python experiments/dna_picture.py cube 4 docs/dna-cube.png
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import lkspace
from lkspace.dna.build import build


def main(name: str, twist: str, out: str) -> None:
    s = lkspace.load(name)
    labels = np.array([int(x) for x in twist.split(",")] * (s.n_edges if "," not in twist else 1))
    design = build(s, labels)
    n = design.nucleotides
    p = n.position - n.position.mean(axis=0)
    bb = p - 0.4 * n.a1
    fig = plt.figure(figsize=(7, 7), dpi=130)
    ax = fig.add_subplot(projection="3d")
    colors = plt.get_cmap("tab10")
    for k in range(len(n.strand_starts) - 1):
        lo, hi = n.strand_starts[k], n.strand_starts[k + 1]
        loop = np.vstack([bb[lo:hi], bb[lo : lo + 1]])
        ax.plot(*loop.T, color=colors(k % 10), lw=1.6)
    for i in np.flatnonzero(n.pair > i_min(n.pair)):
        j = n.pair[i]
        ax.plot(*np.stack([p[i], p[j]]).T, color="0.6", lw=0.6)
    ax.set_box_aspect(np.ptp(p, axis=0))
    ax.set_proj_type("ortho")
    ax.view_init(elev=18, azim=-62)
    ax.set_axis_off()
    strands = len(n.strand_starts) - 1
    ax.set_title(f"{name}, twist {twist}: {strands} strand{'s' * (strands != 1)}, {len(p)} nucleotides", fontsize=10)
    fig.savefig(out, bbox_inches="tight")


def i_min(pair: np.ndarray) -> np.ndarray:
    """Each pair once: the nucleotide with the lower index draws it."""
    return np.where(pair >= 0, np.arange(len(pair)), len(pair))


if __name__ == "__main__":
    main(*sys.argv[1:4])
