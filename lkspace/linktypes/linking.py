"""Linking matrices as targets: ``--linking-matrix "0,1,0;1,0,1;0,1,0"`` (three rings, each linked with the next).

A design matches when some renumbering of its components turns its linking matrix into
the target.  **Signs.**  A strand's direction is a convention of the tracer (faces are
walked in their vertex order), not something a maker sees, so by default signs are
ignored: ``|lk|`` is compared.  ``signed=True`` (``--signed``) compares the linking
numbers of the strands as traced (``lkspace trace`` shows their direction), still up to
renumbering.
"""

from __future__ import annotations

import json

import numpy as np

from ..errors import UsageError

MAX_COMPONENTS = 64


def parse_linking_matrix(linking_matrix: str) -> np.ndarray:
    """Parse ``"0,1;1,0"`` (rows split by ``;``) or JSON ``"[[0,1],[1,0]]"`` into an ``(n, n) int64`` matrix.

    The matrix must be square, symmetric, with a zero diagonal.

    Examples
    --------
    >>> parse_linking_matrix("0,1;1,0").tolist()
    [[0, 1], [1, 0]]
    """
    where = f"linking_matrix {linking_matrix[:60]!r}"
    try:
        text = linking_matrix.strip()
        rows = json.loads(text) if text.startswith("[") else [r.split(",") for r in text.split(";")]
        matrix = np.array([[int(str(v).strip()) for v in row] for row in rows], dtype=np.int64)
    except (ValueError, TypeError, OverflowError, RecursionError):
        raise UsageError(
            f"{where}: write integers, rows separated by ';' (e.g. 0,1;1,0) or JSON [[0,1],[1,0]]",
            parameter="linking_matrix",
        ) from None
    n = len(matrix)
    if matrix.ndim != 2 or matrix.shape != (n, n) or n == 0:
        raise UsageError(f"{where}: not a square matrix", parameter="linking_matrix")
    if n > MAX_COMPONENTS:
        raise UsageError(f"{where}: {n} components; at most {MAX_COMPONENTS}", parameter="linking_matrix")
    if not np.array_equal(matrix, matrix.T):
        raise UsageError(f"{where}: not symmetric (lk(a, b) = lk(b, a))", parameter="linking_matrix")
    if np.any(np.diag(matrix) != 0):
        raise UsageError(f"{where}: the diagonal must be zero", parameter="linking_matrix")
    return matrix


def matches(got: np.ndarray, want: np.ndarray, signed: bool = False) -> bool:
    """Whether some renumbering ``p`` of ``got``'s components gives ``got[p][:, p] == want``.

    A backtracking search over component assignments, pruned by each component's sorted
    row (its multiset of linking numbers).

    Examples
    --------
    >>> a = np.array([[0, 1, 0], [1, 0, 2], [0, 2, 0]])
    >>> b = np.array([[0, 2, 1], [2, 0, 0], [1, 0, 0]])
    >>> matches(a, b), matches(a, -b), matches(a, -b, signed=True)
    (True, True, False)
    """
    got = np.asarray(got, np.int64)
    want = np.asarray(want, np.int64)
    if got.shape != want.shape:
        return False
    if not signed:
        got, want = np.abs(got), np.abs(want)
    n = len(got)
    got_rows = [tuple(sorted(r)) for r in got.tolist()]
    want_rows = [tuple(sorted(r)) for r in want.tolist()]
    if sorted(got_rows) != sorted(want_rows):
        return False
    image = [-1] * n  # image[i]: the component of ``got`` playing target component i
    used = [False] * n

    def place(i: int) -> bool:
        if i == n:
            return True
        for j in range(n):
            if used[j] or got_rows[j] != want_rows[i]:
                continue
            if all(got[j, image[k]] == want[i, k] for k in range(i)):
                image[i], used[j] = j, True
                if place(i + 1):
                    return True
                used[j] = False
        return False

    return place(0)
