"""Bases: complementary on every base pair, no run of ``MAX_RUN + 1`` equal bases, linkers of T.

Each edge gets one random word (from ``seed``) read 5' -> 3' along its slot-0 strand; the
slot-1 strand carries its reverse complement, so every base pair is Watson-Crick and a run
on one strand is a run of the complement on the other.  A word starts and ends with C or G
(a GC clamp), so the poly-T linkers at the vertices never lengthen a run of the duplexes.
"""

from __future__ import annotations

import numpy as np

from ..errors import UsageError

COMPLEMENT = {"A": "T", "T": "A", "C": "G", "G": "C"}
MAX_RUN = 3
"""Longest run of one base inside a duplex."""
LINKER = "T"
"""Base of the unpaired nucleotides at the vertices."""


def edge_word(rng: np.random.Generator, n: int) -> str:
    """Return a random word of ``n`` bases: GC at both ends, no run longer than :data:`MAX_RUN`."""
    out: list[str] = []
    for i in range(n):
        choices = "CG" if i in (0, n - 1) else "ACGT"
        if len(out) >= MAX_RUN and len(set(out[-MAX_RUN:])) == 1:
            choices = choices.replace(out[-1], "")
        out.append(choices[int(rng.integers(len(choices)))])
    return "".join(out)


def bases(edge: np.ndarray, index: np.ndarray, slot: np.ndarray, bp: np.ndarray, seed: int) -> str:
    """Return the base of every nucleotide (arrays as in :class:`~lkspace.dna.helix.Nucleotides`), one string.

    The slot-0 nucleotide of base pair ``j`` (counted from end ``a``) of edge ``e`` gets letter
    ``j`` of the edge's word, read 5' -> 3' or backwards as its strand runs; the slot-1
    nucleotide its complement.  Reversal keeps the rules of :func:`edge_word`.
    """
    rng = np.random.default_rng(seed)
    words = [edge_word(rng, int(n)) for n in bp]
    out = []
    for e, j, s in zip(edge.tolist(), index.tolist(), slot.tolist(), strict=True):
        if e < 0:
            out.append(LINKER)
        else:
            b = words[e][j]
            out.append(b if s == 0 else COMPLEMENT[b])
    return "".join(out)


def impose(sequence: str, given: str, strand: tuple[int, int], pair: np.ndarray) -> str:
    """Return ``sequence`` with strand ``(start, stop)`` set to ``given`` (5' -> 3') and its partners complemented.

    Refused (naming the position) when ``given`` has the wrong length or letters, or when it
    pairs with itself (a single strand folding back) with two bases that are not complementary.
    """
    lo, hi = strand
    given = given.upper()
    if len(given) != hi - lo:
        raise UsageError(
            f"sequence: {len(given)} bases given, but strand 0 has {hi - lo} nucleotides", parameter="sequence"
        )
    bad = next((i for i, b in enumerate(given) if b not in COMPLEMENT), None)
    if bad is not None:
        raise UsageError(f"sequence: base {bad + 1} is {given[bad]!r}; use A, C, G and T", parameter="sequence")
    out = list(sequence)
    for i, b in enumerate(given):
        out[lo + i] = b
        j = int(pair[lo + i])
        if j < 0:
            continue
        if lo <= j < hi and COMPLEMENT[b] != given[j - lo]:
            raise UsageError(
                f"sequence: bases {i + 1} ({b}) and {j - lo + 1} ({given[j - lo]}) pair but are not complementary",
                parameter="sequence",
            )
        out[j] = COMPLEMENT[b]
    return "".join(out)
