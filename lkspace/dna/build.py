"""A labelled scaffold -> its DNA: checked, oriented, placed and given bases."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.scaffold import Scaffold
from ..strands.tracing import Trace, trace
from .helix import Nucleotides, place
from .model import BP_PER_TURN, base_pairs, check_buildable, orient
from .sequences import bases, impose


@dataclass(frozen=True)
class DnaDesign:
    """The DNA of one design.

    Attributes
    ----------
    trace : Trace
        lkspace's strands; DNA strand ``k`` is trace strand ``k``.
    bp : (n_edges,) int64
        Base pairs on each edge.
    nucleotides : Nucleotides
    sequence : str
        One base per nucleotide, in the order of ``nucleotides``.
    """

    trace: Trace
    bp: np.ndarray
    nucleotides: Nucleotides
    sequence: str

    def strand_sequences(self) -> list[str]:
        """Each strand's bases, 5' -> 3'."""
        s = self.nucleotides.strand_starts
        return [self.sequence[s[k] : s[k + 1]] for k in range(len(s) - 1)]

    def summary(self) -> dict[str, object]:
        """JSON-ready counts: strands, nucleotides, base pairs per edge, unpaired, scale."""
        n = self.nucleotides
        return {
            "strands": len(n.strand_starts) - 1,
            "nucleotides": len(n.position),
            "strand_lengths": np.diff(n.strand_starts).tolist(),
            "base_pairs": self.bp.tolist(),
            "unpaired": int(np.sum(n.pair < 0)),
            "nm_per_unit": n.scale,
        }


def build(
    scaffold: Scaffold,
    labels: np.ndarray,
    *,
    seed: int = 0,
    bp_per_turn: float = BP_PER_TURN,
    nm_per_unit: float | None = None,
    sequence: str | None = None,
) -> DnaDesign:
    """Return the DNA of ``scaffold`` under ``labels`` (``docs/dna.md``), or refuse naming an edge.

    ``bp_per_turn`` sets the base pairs per edge (``round(bp_per_turn * t / 2)``), ``nm_per_unit``
    the nm per mesh unit (default: the smallest that fits), ``seed`` the bases; ``sequence``
    gives strand 0's bases 5' -> 3' (its partners get the complements, the rest come from ``seed``).
    """
    labels = np.asarray(labels, np.int64)
    check_buildable(scaffold, labels)
    tr = trace(scaffold, labels)
    passes = orient(tr)
    bp = base_pairs(labels, bp_per_turn)
    nuc = place(scaffold, labels, bp, passes, nm_per_unit)
    text = bases(nuc.edge, nuc.index, nuc.slot, bp, seed)
    if sequence is not None:
        text = impose(text, sequence, (int(nuc.strand_starts[0]), int(nuc.strand_starts[1])), nuc.pair)
    return DnaDesign(tr, bp, nuc, text)
