"""The diagrams behind a batch's names by key: each design's own, and regina's simplification of it, made once.

Sharing a name by key checks designs against the name
(:meth:`DesignDiagrams.reaches_crossing_number`); designs the first level leaves go on
with the HOMFLY-PT polynomial of the same simplified diagram (:meth:`DesignDiagrams.homfly`).
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ..runtime.workers import interruptible
from .assembled import assemble_many
from .assembly import work_array
from .identification import NameFields
from .keyed import DesignKeys
from .naming import name_key
from .tables import HOMFLY_MAX_CROSSINGS

Diagram = tuple[list[list[int]], int, np.ndarray]
"""A design's PD code (1-based), its components and its crossing signs ``(n,) int64``."""


def simplified(pd: list[list[int]], regina: Any = None) -> Any:
    """Return regina's link of a PD code after regina's greedy simplification (``regina``: the module, if at hand).

    Regina's random moves start from its default seed each time, so a design's
    simplified diagram, and so its second-level key, is the same in every run.
    """
    if regina is None:
        from .tables import regina_module

        regina = regina_module()
    regina.RandomEngine.reseedWithDefault()
    link = regina.Link.fromPD(pd)
    link.simplify()
    return link


def homfly_of_link(link: Any) -> tuple[str, int] | None:
    """Return the HOMFLY-PT polynomial of a simplified regina link and its crossings.

    ``None`` when more than :data:`~lkspace.knots.tables.HOMFLY_MAX_CROSSINGS` are left.
    """
    if link.size() > HOMFLY_MAX_CROSSINGS:
        return None
    return str(interruptible(link.homfly, 2 ** int(link.size()))), int(link.size())  # work exponential in crossings


class DesignDiagrams:
    """Diagrams of the designs of one :class:`~lkspace.knots.keyed.DesignKeys`, each assembled and simplified at most once.

    :meth:`prepare` assembles many in one compiled call; :meth:`diagram` assembles any
    design not prepared on its own.
    """

    def __init__(self, found: DesignKeys) -> None:
        self.found = found
        self._arrays = found.template.arrays()
        self._work = work_array(found.template)
        self._rows: dict[int, tuple[np.ndarray, np.ndarray, int]] = {}  # d -> PD rows, signs, components
        self._pieces: dict[int, int] = {}
        self._simplified: dict[int, Any] = {}
        self._regina: Any = None

    def prepare(self, designs: list[int]) -> None:
        """Assemble the diagrams of ``designs`` (indices into the batch) not assembled yet."""
        todo = [d for d in dict.fromkeys(designs) if d not in self._rows]
        if not todo:
            return
        vidx = np.ascontiguousarray(self.found.vidx[todo])
        work = len(todo) * len(self._work.local)  # steps, about: a few designs run as Python (no numba to load)
        pd, signs, offsets, components, pieces = assemble_many.run(work, self._arrays, vidx, self._work)
        for i, d in enumerate(todo):
            start, end = offsets[i], offsets[i + 1]
            self._rows[d] = (pd[start:end], signs[start:end], int(components[i]))
            self._pieces[d] = int(pieces[i])

    def diagram(self, d: int) -> Diagram:
        """Return design ``d``'s PD code, components and crossing signs (:meth:`DesignKeys.diagram`'s)."""
        if d not in self._rows:
            self.prepare([d])
        pd, signs, n_comp = self._rows[d]
        return pd.tolist(), n_comp, signs

    def simplified(self, d: int) -> Any:
        """Return regina's simplification of design ``d``'s diagram (:func:`simplified`)."""
        if d not in self._simplified:
            if self._regina is None:
                from .tables import regina_module

                self._regina = regina_module()
            self._simplified[d] = simplified(self.diagram(d)[0], self._regina)
        return self._simplified[d]

    def homfly(self, d: int) -> tuple[str, int] | None:
        """Return the HOMFLY-PT polynomial of design ``d`` and the crossings of its simplified diagram (:func:`homfly_of_link`)."""
        if not self.diagram(d)[0]:
            return "1", 0
        return homfly_of_link(self.simplified(d))

    def reaches_crossing_number(self, d: int, named: NameFields) -> bool:
        """Whether design ``d`` has a diagram of exactly the crossing number of ``named``'s name.

        Its own diagram, or regina's simplification of it; for a sum (``L2a1#4_1``) the
        factors' crossing numbers added.  Such a diagram bounds the design's crossing number
        by the name's (11 or fewer for a LinkInfo link, 13 for a KnotInfo knot), and the
        tables hold every prime link that small, so the key leaves the name alone (the key is
        shared by no table type but the name's).  A link past the tables with the key
        (L12n1741 beside L11n383, L2a1#11n_19 beside L2a1#4_1, a satellite, a link whose
        volume is not the name's) never has so few crossings, and a diagram with fewer proves
        another link (the composite L2a1#L4a1 beside the prime L11n420): both go on to the
        second level.  Names no other link can undercut are not checked: a knot of at most 5
        crossings (a sum of knots has at least 6) or a link of at most 3 (a sum or split link
        of that many components has at least as many crossings; the tables hold every prime
        one).  A split name holds only for a diagram in pieces: a free component, or
        components no crossing joins in its own diagram or regina's simplification.
        """
        told = self.told(d, named)
        if told is not None:
            return told
        if named.split:
            return self._in_pieces(d)
        return int(self.simplified(d).size()) == self._crossing_number(named)

    def told(self, d: int, named: NameFields) -> bool | None:
        """Return :meth:`reaches_crossing_number` where design ``d``'s own crossings and free components tell it, else ``None``."""
        found = self.found
        if named.split:
            return True if found.free[d] > 0 else None  # a component crossing nothing
        if not named.knot_name:
            return True
        need = self._crossing_number(named)
        small = "#" not in named.knot_name and named.table in ("knotinfo", "linkinfo")
        if (small and need <= (5 if found.components[d] == 1 else 3)) or found.crossings[d] == need:
            return True
        return False if found.crossings[d] < need else None

    @staticmethod
    def _crossing_number(named: NameFields) -> int:
        """Return the crossing number of ``named``'s name (a sum's factors' added)."""
        return _crossing_number(str(named.knot_name))

    def _in_pieces(self, d: int) -> bool:
        """Whether design ``d``'s diagram, or regina's simplification of it, falls into pieces no crossing joins."""
        if d not in self._pieces:
            self.prepare([d])
        return self._pieces[d] > 1 or not self.simplified(d).isConnected()


@functools.cache
def _crossing_number(name: str) -> int:
    """Return the crossing number of a table name or a sum of them (``L2a1#4_1``: 6)."""
    return sum(name_key(part)[0] for part in name.split("#"))
