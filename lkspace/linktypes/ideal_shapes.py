"""The relaxed shape of every knot up to 10 crossings that comes within 5% of its ideal ropelength.

For each of the 249 knots, ``experiments/relax_ropelength.py`` relaxed designs of its
lookup, measured the ropelength (length / tube radius) of the exported curve
independently, and kept the tightest: a design, the relaxation options that made it
(``--relax-fine``, ``--relax-points``, ``--relax-escape``, ``--relax-seed``) and the ratio to
KnotInfo's tight ropelength (``results/ropelength.md``).  ``experiments/ideal_shapes.py``
ships them as ``lkspace/data/ideal-shapes.json.gz``; ``lookup`` answers with the one of its
type (``ideal_shape``), so ``lkspace lookup 8_17`` shows the command that draws 8_17 at
its ideal shape.  Mirror images have the same ropelength; the shape kept is of the
chirality ``chiral_name`` says.
"""

from __future__ import annotations

import gzip
import json
import shlex
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from .fields import JsonObject, as_object, read_float, read_ints, read_str, read_strs

SHIPPED = Path(__file__).resolve().parent.parent / "data" / "ideal-shapes.json.gz"
"""``{"rows": [IdealShape.to_json(), ...]}``: one per knot up to 10 crossings."""


@dataclass(frozen=True)
class IdealShape:
    """A design whose relaxed curve comes close to its type's ideal ropelength.

    ``ropelength`` is measured on the exported curve (length / radius of the thickest
    tube), ``ideal`` is KnotInfo's, ``ratio`` their quotient; ``relax_flags`` are the
    ``export`` options past ``--relax`` that made it.
    """

    chiral_name: str
    scaffold: str
    labels: tuple[int, ...]
    relax_flags: tuple[str, ...]
    ropelength: float
    ideal: float
    ratio: float

    def command(self, output: str | None = None) -> str:
        """Return the ``lkspace export`` command that draws this shape (into ``output``, default ``NAME.obj``)."""
        twist = ",".join(map(str, self.labels))
        out = shlex.quote(output or f"{self.chiral_name}.obj")
        flags = "".join(f" {shlex.quote(f)}" for f in self.relax_flags)
        return f"lkspace export {shlex.quote(self.scaffold)} --twist {twist} --relax{flags} -o {out}"

    @classmethod
    def from_json(cls, data: object, where: str = "ideal shape") -> IdealShape:
        """Read :meth:`to_json`."""
        d = as_object(data, where)
        return cls(
            read_str(d, "chiral_name", where),
            read_str(d, "scaffold", where),
            read_ints(d, "labels", where),
            read_strs(d, "relax_flags", where),
            read_float(d, "ropelength", where),
            read_float(d, "ideal", where),
            read_float(d, "ratio", where),
        )

    def to_json(self) -> JsonObject:
        """Return ``{chiral_name, scaffold, labels, relax_flags, ropelength, ideal, ratio, command}``."""
        return {
            "chiral_name": self.chiral_name,
            "scaffold": self.scaffold,
            "labels": list(self.labels),
            "relax_flags": list(self.relax_flags),
            "ropelength": self.ropelength,
            "ideal": self.ideal,
            "ratio": self.ratio,
            "command": self.command(),
        }


@lru_cache(maxsize=1)
def shipped_shapes() -> dict[str, IdealShape]:
    """Return the shipped shapes by type name without mirror mark (``"10_130"``)."""
    with gzip.open(SHIPPED, "rt") as f:
        rows = json.load(f)["rows"]
    shapes = [IdealShape.from_json(r, f"{SHIPPED.name}, row {i}") for i, r in enumerate(rows)]
    return {s.chiral_name.removeprefix("m"): s for s in shapes}


def ideal_shape(name: str) -> IdealShape | None:
    """Return the shipped shape of the knot ``name`` (``"8_17"``; a mirror mark is ignored), ``None`` past the table."""
    return shipped_shapes().get(name.removeprefix("m"))
