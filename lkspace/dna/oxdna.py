"""oxDNA topology and configuration, and oxView JSON, of a :class:`~lkspace.dna.build.DnaDesign`.

* ``NAME.top``: oxDNA's newer topology format: a header ``N_nucleotides N_strands 5->3``,
  then one line per strand, its bases 5' -> 3' and ``circular=true type=DNA``.
* ``NAME.dat``: ``t = 0``, ``b = Lx Ly Lz`` (a box with a margin around the structure),
  ``E = 0 0 0``, then one line per nucleotide in topology order: centre of mass ``r``, ``a1``,
  ``a3``, velocity and angular velocity (zero), lengths in oxDNA units.
* ``NAME.oxview``: the same nucleotides as oxView JSON (``box``, ``systems[0].strands[k].monomers``
  with ``id, type, class, p, a1, a3, n3, n5, bp, cluster``), base pairs recorded in ``bp``.

The three files are written to temporary names first and renamed only when all are
complete.
"""

from __future__ import annotations

import contextlib
import json
import os

import numpy as np

from ..io.atomic import atomic_path
from .build import DnaDesign

SUFFIXES = (".top", ".dat", ".oxview")
BOX_MARGIN = 10.0
"""Room around the structure in the box, oxDNA units."""


def targets(output: str) -> list[str]:
    """Return the three files of ``NAME.oxdna``: ``NAME.top``, ``NAME.dat``, ``NAME.oxview``."""
    stem = os.path.splitext(output)[0]
    return [stem + s for s in SUFFIXES]


def centred(design: DnaDesign) -> tuple[np.ndarray, np.ndarray]:
    """Positions moved into the middle of the box, and the box ``(3,)``."""
    p = design.nucleotides.position
    lo, hi = p.min(axis=0), p.max(axis=0)
    box = np.full(3, float(np.max(hi - lo)) + 2 * BOX_MARGIN)
    return p - (lo + hi) / 2 + box / 2, box


def topology(design: DnaDesign) -> str:
    """Return the ``.top`` text."""
    seqs = design.strand_sequences()
    lines = [f"{len(design.sequence)} {len(seqs)} 5->3"]
    lines += [f"{s} circular=true type=DNA" for s in seqs]
    return "\n".join(lines) + "\n"


def configuration(design: DnaDesign) -> str:
    """Return the ``.dat`` text."""
    p, box = centred(design)
    n = design.nucleotides
    lines = ["t = 0", "b = " + " ".join(f"{x:.6f}" for x in box), "E = 0 0 0"]
    rows = np.hstack([p, n.a1, n.a3])
    lines += [" ".join(f"{x:.6f}" for x in row) + " 0 0 0 0 0 0" for row in rows]
    return "\n".join(lines) + "\n"


def oxview(design: DnaDesign) -> str:
    """Return the ``.oxview`` text."""
    p, box = centred(design)
    n = design.nucleotides
    strands = []
    for k in range(len(n.strand_starts) - 1):
        lo, hi = int(n.strand_starts[k]), int(n.strand_starts[k + 1])
        monomers = []
        for i in range(lo, hi):
            m = {
                "id": i,
                "type": design.sequence[i],
                "class": "DNA",
                "p": [round(float(x), 6) for x in p[i]],
                "a1": [round(float(x), 6) for x in n.a1[i]],
                "a3": [round(float(x), 6) for x in n.a3[i]],
                "n3": i + 1 if i + 1 < hi else lo,
                "n5": i - 1 if i > lo else hi - 1,
                "cluster": k + 1,
            }
            if n.pair[i] >= 0:
                m["bp"] = int(n.pair[i])
            monomers.append(m)
        strands.append({"id": k, "class": "NucleicAcidStrand", "end5": lo, "end3": hi - 1, "monomers": monomers})
    doc = {"box": box.tolist(), "systems": [{"id": 0, "strands": strands}], "forces": [], "selections": []}
    return json.dumps(doc, separators=(",", ":")) + "\n"


def zip_bytes(design: DnaDesign, stem: str) -> bytes:
    """Return a zip archive of ``STEM.top``, ``STEM.dat`` and ``STEM.oxview`` (fixed dates: the same design, the same bytes)."""
    import io
    import zipfile

    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for suffix, text in zip(SUFFIXES, (topology(design), configuration(design), oxview(design)), strict=True):
            archive.writestr(zipfile.ZipInfo(stem + suffix, date_time=(1980, 1, 1, 0, 0, 0)), text)
    return buffer.getvalue()


def write(design: DnaDesign, output: str) -> list[str]:
    """Write the three files of ``output`` (``NAME.oxdna``); return their paths.

    Every text is made first, then written to a temporary file beside its target; the
    renames happen only once all three are written.
    """
    paths = targets(output)
    texts = [topology(design), configuration(design), oxview(design)]
    with contextlib.ExitStack() as stack:
        for path, text in zip(paths, texts, strict=True):
            tmp = stack.enter_context(atomic_path(path))
            with open(tmp, "w", encoding="utf-8") as fh:
                fh.write(text)
    return paths
