"""Compiled kernels over residue classes and the group: orbit representatives, stabilizers, counts.

* :func:`orbit_minima`: whether each class code is the smallest of its orbit, and how many
  group actions fix it (the representatives of :func:`lkspace.design.space.class_orbits`);
* :func:`stabilizer_ids`: the actions fixing each representative;
* :func:`burnside_classes`: designs per class, Burnside's lemma over its stabilizer.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..compiled.kernels import kernel
from ..compiled.loops import next_digits, set_digits


class ResidueCodes(NamedTuple):
    """The residues of a design space as the orbit kernels read them (:class:`~lkspace.design.space.ResidueTable`).

    Edge ``j`` has ``n_res[j]`` residues ``values[j, :n_res[j]]`` mod ``moduli[j]``;
    ``lookup[j, r]`` is the index of residue ``r`` (-1 if none).
    """

    n_res: np.ndarray
    values: np.ndarray
    lookup: np.ndarray
    moduli: np.ndarray


class SignedPerms(NamedTuple):
    """Group actions as forward maps: action ``g`` puts ``signs[g] * t[j]`` on edge ``perms[g, j]``."""

    perms: np.ndarray
    signs: np.ndarray


class MinimaOut(NamedTuple):
    """What :func:`orbit_minima` writes per class code: ``is_rep (n,) bool`` and ``n_fix (n,) int64``."""

    is_rep: np.ndarray
    n_fix: np.ndarray


@kernel
def burnside_classes(
    indices: np.ndarray,
    n_opts: np.ndarray,
    has_zero: np.ndarray,
    stab_ptr: np.ndarray,
    stab_ids: np.ndarray,
    cyc_ptr: np.ndarray,
    cyc_head: np.ndarray,
    cyc_even: np.ndarray,
) -> np.ndarray:
    """(n_c,) int64: designs in each class ``indices (n_c, n_edges)`` (Burnside over its stabilizer).

    ``fix(h)`` is the product over the cycles of ``h`` of the class's label count on the
    cycle's first edge (signs multiply to +1) or ``has_zero`` there (to -1); the caller
    makes sure the sums fit in int64.
    """
    n_c = indices.shape[0]
    out = np.zeros(n_c, np.int64)
    for c in range(n_c):
        total = 0
        for p in range(stab_ptr[c], stab_ptr[c + 1]):
            h = stab_ids[p]
            f = 1
            for q in range(cyc_ptr[h], cyc_ptr[h + 1]):
                e = cyc_head[q]
                f *= n_opts[e, indices[c, e]] if cyc_even[q] else has_zero[e, indices[c, e]]
                if f == 0:
                    break
            total += f
        out[c] = total // (stab_ptr[c + 1] - stab_ptr[c])
    return out


@kernel
def orbit_minima(first: int, stop: int, residues: ResidueCodes, group: SignedPerms, out: MinimaOut) -> None:
    """For class codes ``first..stop``: whether each is its orbit's smallest code, and how many actions fix it.

    Codes are mixed radix over the edges' residue indices (edge 0 most significant); the
    image of a class under action ``(perm, sign)`` puts residue ``sign * r`` of edge ``j``
    on edge ``perm[j]``.  Writes ``out.is_rep[i]`` and ``out.n_fix[i]`` for code ``first + i``.
    """
    n_res, values, lookup, moduli = residues.n_res, residues.values, residues.lookup, residues.moduli
    perms, signs, is_rep, n_fix = group.perms, group.signs, out.is_rep, out.n_fix
    n_e = len(n_res)
    n_g = len(signs)
    digits = np.zeros(n_e, np.int64)
    img = np.zeros(n_e, np.int64)
    set_digits(digits, n_res, first)
    for i in range(stop - first):
        code = first + i
        rep = True
        fix = 0
        for g in range(n_g):
            s = signs[g]
            for j in range(n_e):
                t = perms[g, j]
                img[t] = lookup[t, (s * values[j, digits[j]]) % moduli[t]]
            other = 0
            for j in range(n_e):
                other = other * n_res[j] + img[j]
            if other < code:
                rep = False
                break
            if other == code:
                fix += 1
        is_rep[i] = rep
        n_fix[i] = fix
        next_digits(digits, n_res)


@kernel
def stabilizer_ids(
    indices: np.ndarray, residues: ResidueCodes, group: SignedPerms, ptr: np.ndarray, out: np.ndarray
) -> None:
    """Write the actions fixing each class ``indices (n_c, n_edges)``, ascending, to ``out[ptr[c]:ptr[c+1]]``."""
    values, lookup, moduli, perms, signs = residues.values, residues.lookup, residues.moduli, group.perms, group.signs
    n_c, n_e = indices.shape
    for c in range(n_c):
        m = ptr[c]
        for g in range(len(signs)):
            s = signs[g]
            fixed = True
            for j in range(n_e):
                t = perms[g, j]
                if lookup[t, (s * values[j, indices[c, j]]) % moduli[t]] != indices[c, t]:
                    fixed = False
                    break
            if fixed:
                out[m] = g
                m += 1
