"""The records identification hands on, each with one ``from_json`` (validating) and one ``to_json``.

* :class:`Naming`: what :func:`~lkspace.knots.naming.name_pd` found for one PD code (a
  name or why none, and the invariants computed on the way).  The invariants computed
  depend on the path (an unlink, a split link, a table entry, a composite), so the record
  keeps the JSON keys it has, in the order they were found (:attr:`Naming.keys`):
  ``to_json`` writes exactly those.
* :class:`NameFields`: the fields one design's row takes from its naming, shared by every
  design of a trusted key and kept on disk by :class:`~lkspace.knots.key_names.KeyCache`
  (one JSON line per key).
* :class:`Identification`: the answer of :func:`lkspace.identify`; its JSON is what
  ``lkspace identify --json`` prints (with ``labels`` and ``common_name`` added there).

This module is checked by ``mypy --strict`` (``pyproject.toml``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from typing import ClassVar, TypeAlias

from ..words import plural

Json: TypeAlias = "str | int | float | bool | None | list[Json] | dict[str, Json]"
"""A JSON value as :func:`json.loads` returns it."""


class RecordError(ValueError):
    """A JSON payload that is not a valid record (a wrong key or type); the message names the key."""


def _check(key: str, value: Json, kinds: tuple[type, ...], optional: bool = True) -> None:
    if value is None and optional:
        return
    ok = isinstance(value, kinds) and not (isinstance(value, bool) and bool not in kinds)
    if not ok:
        raise RecordError(f"{key}: expected {' or '.join(k.__name__ for k in kinds)}, got {value!r}")


def _opt_str(data: Mapping[str, Json], key: str) -> str | None:
    value = data.get(key)
    _check(key, value, (str,))
    return value if isinstance(value, str) else None


def _opt_int(data: Mapping[str, Json], key: str) -> int | None:
    value = data.get(key)
    _check(key, value, (int,))
    return value if isinstance(value, int) else None


def _opt_bool(data: Mapping[str, Json], key: str) -> bool | None:
    value = data.get(key)
    _check(key, value, (bool,))
    return value if isinstance(value, bool) else None


def _opt_float(data: Mapping[str, Json], key: str) -> float | None:
    value = data.get(key)
    _check(key, value, (float, int))
    return float(value) if isinstance(value, (float, int)) else None


def _names(data: Mapping[str, Json], key: str, nullable_items: bool = True) -> tuple[str | None, ...] | None:
    value = data.get(key)
    if value is None:
        return None
    if not isinstance(value, list):
        raise RecordError(f"{key}: expected a list of names, got {value!r}")
    for item in value:
        _check(f"{key}[]", item, (str,), optional=nullable_items)
    return tuple(item if isinstance(item, str) else None for item in value)


def _mapping(data: object, what: str) -> Mapping[str, Json]:
    if not isinstance(data, dict) or not all(isinstance(k, str) for k in data):
        raise RecordError(f"{what}: expected a JSON object, got {type(data).__name__}")
    return data


def _unknown(data: Mapping[str, Json], known: tuple[str, ...], what: str) -> None:
    extra = [k for k in data if k not in known]
    if extra:
        raise RecordError(f"{what}: unknown key {extra[0]!r}")


@dataclass(frozen=True)
class Naming:
    """A PD code's name (or why none) and the invariants found on the way (:func:`~lkspace.knots.naming.name_pd`).

    Attributes
    ----------
    name : str or None
        ``"0_1"``, Rolfsen ``"3_1"``, Thistlethwaite ``"L6a4"``, HTLinkExteriors ``"K14n10910"``,
        a sum ``"3_1#4_1"``; ``None`` when unknown or split.
    table_name, table : str or None
        The entry's name in its table, and the table (``"knotinfo"``, ``"linkinfo"``,
        ``"HTLinkExteriors"``, ``"knotinfo+linkinfo"`` for sums).
    mirror : bool or None
        The link is the table diagram's mirror image (``None``: cannot tell, or amphichiral).
    candidates : tuple of str or None
        Table entries the Jones polynomial and the checks left (``" (mirror)"`` marks mirrors).
    crossings : int or None
        Crossings of the simplified diagram.
    jones, homfly : str or None
        Jones (in ``sqrt t``) and HOMFLY-PT polynomials (regina's text).
    volume : float or None
        Hyperbolic volume (0 when not hyperbolic; ``None`` when SnapPy failed).
    note, chiral_name : str or None
        Why a name was refused; the name with ``m`` for a mirror image (``"m3_1"``).
    split : bool or None
    pieces, factors : tuple of (str or None) or None
        Names of a split link's pieces, of a composite's prime factors.
    prime : bool or None
        ``False`` for a connected sum.
    knot_floer : dict or None
        ``seifert_genus``, ``fibered``, ``tau``, ``total_rank``, ``L_space_knot``.
    keys : tuple of str
        The JSON keys this naming has, in order (:meth:`to_json` writes these).
    """

    name: str | None = None
    table_name: str | None = None
    mirror: bool | None = None
    candidates: tuple[str | None, ...] | None = None
    crossings: int | None = None
    jones: str | None = None
    homfly: str | None = None
    volume: float | None = None
    table: str | None = None
    note: str | None = None
    chiral_name: str | None = None
    split: bool | None = None
    pieces: tuple[str | None, ...] | None = None
    factors: tuple[str | None, ...] | None = None
    prime: bool | None = None
    knot_floer: dict[str, int | bool] | None = None
    keys: tuple[str, ...] = ()

    FIELDS: ClassVar[tuple[str, ...]] = ()
    """Every JSON key a naming may have."""

    @classmethod
    def of(cls, **values: object) -> Naming:
        """Return a naming holding ``values`` (keys in the order given)."""
        return cls().updated(**values)

    def updated(self, **changes: object) -> Naming:
        """Return this naming with ``changes`` (a key not held yet goes last, as in a ``dict.update``)."""
        unknown = [k for k in changes if k not in self.FIELDS]
        if unknown:
            raise RecordError(f"naming: unknown key {unknown[0]!r}")
        keys = self.keys + tuple(k for k in changes if k not in self.keys)
        return replace(self, keys=keys, **changes)  # type: ignore[arg-type]

    def to_json(self) -> dict[str, Json]:
        """Return the JSON object: the keys of :attr:`keys`, in order."""
        out: dict[str, Json] = {}
        for key in self.keys:
            value = getattr(self, key)
            if isinstance(value, tuple):
                out[key] = list(value)
            elif isinstance(value, dict):
                out[key] = dict(value)
            else:
                out[key] = value
        return out

    @classmethod
    def from_json(cls, data: object) -> Naming:
        """Read a naming from its JSON object; :class:`RecordError` names a wrong key or value."""
        obj = _mapping(data, "naming")
        _unknown(obj, cls.FIELDS, "naming")
        floer = obj.get("knot_floer")
        if floer is not None:
            floer_obj = _mapping(floer, "knot_floer")
            for k, v in floer_obj.items():
                _check(f"knot_floer.{k}", v, (int, bool), optional=False)
        candidates = _names(obj, "candidates", nullable_items=False)
        return cls(
            name=_opt_str(obj, "name"),
            table_name=_opt_str(obj, "table_name"),
            mirror=_opt_bool(obj, "mirror"),
            candidates=candidates,
            crossings=_opt_int(obj, "crossings"),
            jones=_opt_str(obj, "jones"),
            homfly=_opt_str(obj, "homfly"),
            volume=_opt_float(obj, "volume"),
            table=_opt_str(obj, "table"),
            note=_opt_str(obj, "note"),
            chiral_name=_opt_str(obj, "chiral_name"),
            split=_opt_bool(obj, "split"),
            pieces=_names(obj, "pieces"),
            factors=_names(obj, "factors"),
            prime=_opt_bool(obj, "prime"),
            knot_floer=None
            if floer is None
            else {k: v for k, v in _mapping(floer, "knot_floer").items() if isinstance(v, int)},
            keys=tuple(obj),
        )


Naming.FIELDS = tuple(f.name for f in fields(Naming) if f.name != "keys")


@dataclass(frozen=True)
class NameFields:
    """The fields a design's catalog row takes from its naming (:func:`lkspace.knots.batch.identify_batch`).

    Shared by every design of a trusted key and kept on disk, one JSON line per key
    (:class:`~lkspace.knots.key_names.KeyCache`).  ``knot_name`` is the naming's
    ``name``; ``status`` as :attr:`Identification.status`; ``error`` is set (as the
    status without ``unknown: ``) only when the design could not be named: diagram too
    large, time limit.
    """

    knot_name: str | None = None
    split: bool | None = None
    mirror: bool | None = None
    crossings: int | None = None
    jones: str | None = None
    status: str = "identified"
    error: str | None = None
    pieces: tuple[str | None, ...] | None = None
    table: str | None = None
    chiral_name: str | None = None
    candidates: tuple[str | None, ...] | None = None

    KEYS: ClassVar[tuple[str, ...]] = ()
    """The JSON keys, in the order written (the attributes')."""

    @classmethod
    def refused(cls, status: str) -> NameFields:
        """Return the fields of a design that could not be named: ``status`` ``"unknown: ..."``, the reason in ``error``."""
        return cls(status=status, error=status.removeprefix("unknown: "))

    @classmethod
    def of(cls, named: Naming, status: str) -> NameFields:
        """Return the fields of a design named ``named`` with ``status``."""
        return cls(
            status=status,
            knot_name=named.name,
            split=named.split,
            mirror=named.mirror,
            crossings=named.crossings,
            jones=named.jones,
            pieces=named.pieces,
            table=named.table,
            chiral_name=named.chiral_name,
            candidates=named.candidates,
        )

    def to_json(self) -> dict[str, Json]:
        """Return the JSON object, every key of :attr:`KEYS` (``null`` where unset)."""
        out: dict[str, Json] = {}
        for key in self.KEYS:
            value = getattr(self, key)
            out[key] = list(value) if isinstance(value, tuple) else value
        return out

    @classmethod
    def from_json(cls, data: object) -> NameFields:
        """Read the fields from their JSON object (every key of :attr:`KEYS`, no other)."""
        obj = _mapping(data, "fields")
        _unknown(obj, cls.KEYS, "fields")
        missing = [k for k in cls.KEYS if k not in obj]
        if missing:
            raise RecordError(f"fields: missing key {missing[0]!r}")
        status = obj["status"]
        if not isinstance(status, str):
            raise RecordError(f"status: expected str, got {status!r}")
        return cls(
            status=status,
            knot_name=_opt_str(obj, "knot_name"),
            split=_opt_bool(obj, "split"),
            mirror=_opt_bool(obj, "mirror"),
            crossings=_opt_int(obj, "crossings"),
            jones=_opt_str(obj, "jones"),
            error=_opt_str(obj, "error"),
            pieces=_names(obj, "pieces"),
            table=_opt_str(obj, "table"),
            chiral_name=_opt_str(obj, "chiral_name"),
            candidates=_names(obj, "candidates", nullable_items=False),
        )


NameFields.KEYS = tuple(f.name for f in fields(NameFields))

MAIN = ("status", "components", "name", "linking_matrix", "mirror", "split", "crossings")
"""The keys of :class:`Identification`'s JSON that are attributes; the others are its ``details``."""

LAST = ("min_distance", "method", "pd_code")
"""Keys of :attr:`Identification.details` written after the naming's, in this order."""

DETAILS = ("projected_crossings", *(k for k in Naming.FIELDS if k not in MAIN), *LAST)
"""The keys :attr:`Identification.details` may hold."""


@dataclass(frozen=True, repr=False)
class Identification:
    """The knot or link type of a closed structure.

    Attributes
    ----------
    components : int
    name : str or None
        ``"0_1"``, Rolfsen (``"3_1"``) or Thistlethwaite (``"L6a4"``) name, a split link's
        ``"split: 0_1 + 3_1"`` (:func:`~lkspace.knots.naming.split_name`); ``None`` if unknown.
    linking_matrix : list of list of int
    mirror : bool or None
        The structure is the table diagram's mirror image (``None``: the tables cannot tell).
    split : bool or None
    crossings : int or None
        Crossings of the simplified diagram.
    details : dict
        Everything else (JSON values): ``projected_crossings``, ``jones``, ``homfly``,
        ``volume``, ``candidates``, ``pieces``, ... (:data:`DETAILS`), then ``min_distance``
        (geometric path), ``method`` and ``pd_code`` (the diagram named, 1-based).
    status : str
        ``"identified"`` (named, or a split link with every piece named) or
        ``"unknown: <why>"``: not in the tables, several entries match, ``diagram too
        large: N crossings > 2000`` or ``time limit 60 s reached (during ...)``.
    """

    components: int
    name: str | None
    linking_matrix: list[list[int]]
    mirror: bool | None = None
    split: bool | None = None
    crossings: int | None = None
    details: dict[str, Json] = field(default_factory=dict)
    status: str = "identified"

    @classmethod
    def of(
        cls,
        naming: Naming,
        status: str,
        components: int,
        linking_matrix: list[list[int]],
        extra: Mapping[str, Json],
    ) -> Identification:
        """Return the identification of a ``naming``; ``extra`` (``projected_crossings``, ``min_distance``, ...) joins the details.

        ``extra``'s ``projected_crossings`` comes first in the details, the keys of
        :data:`LAST` last, as ``identify --json`` has always printed them.
        """
        named = naming.to_json()
        details: dict[str, Json] = {k: v for k, v in extra.items() if k not in LAST}
        details.update((k, v) for k, v in named.items() if k not in MAIN)
        details.update((k, extra[k]) for k in LAST if k in extra)
        return cls(
            components=components,
            name=naming.name,
            linking_matrix=linking_matrix,
            mirror=naming.mirror,
            split=naming.split,
            crossings=naming.crossings,
            details=details,
            status=status,
        )

    @property
    def naming(self) -> Naming:
        """The naming this identification holds (typed), read from its JSON."""
        return Naming.from_json({k: v for k, v in self.to_json().items() if k in Naming.FIELDS})

    def __repr__(self) -> str:
        chirality = {True: ", mirror", False: "", None: ""}[self.mirror]
        crossings = "crossings unknown" if self.crossings is None else plural(self.crossings, "crossing")
        counts = f"{plural(self.components, 'component')}, {crossings}"
        return f"Identification({self.name or 'unknown'}{chirality}: {counts})"

    def to_json(self) -> dict[str, Json]:
        """Return the JSON form (``status``, ``components``, ``name``, ``linking_matrix``, ..., then the details)."""
        matrix: list[Json] = [list[Json](row) for row in self.linking_matrix]
        return {
            "status": self.status,
            "components": self.components,
            "name": self.name,
            "linking_matrix": matrix,
            "mirror": self.mirror,
            "split": self.split,
            "crossings": self.crossings,
            **self.details,
        }

    def to_dict(self) -> dict[str, Json]:
        """Return :meth:`to_json` (the name kept for callers of earlier versions)."""
        return self.to_json()

    @classmethod
    def from_json(cls, data: object) -> Identification:
        """Read an identification from its JSON (``identify --json`` less ``labels``, ``common_name``, ``scaffold``)."""
        obj = _mapping(data, "identification")
        _unknown(obj, (*MAIN, *DETAILS), "identification")
        components, status, matrix = obj.get("components"), obj.get("status"), obj.get("linking_matrix")
        if not isinstance(components, int) or isinstance(components, bool):
            raise RecordError(f"components: expected int, got {components!r}")
        if not isinstance(status, str):
            raise RecordError(f"status: expected str, got {status!r}")
        if not isinstance(matrix, list) or not all(
            isinstance(row, list) and all(isinstance(v, int) and not isinstance(v, bool) for v in row) for row in matrix
        ):
            raise RecordError(f"linking_matrix: expected a list of lists of int, got {matrix!r}")
        details = {k: v for k, v in obj.items() if k not in MAIN}
        Naming.from_json({k: v for k, v in details.items() if k in Naming.FIELDS})  # checks their types
        _opt_int(details, "projected_crossings")
        _opt_float(details, "min_distance")
        return cls(
            components=components,
            name=_opt_str(obj, "name"),
            linking_matrix=[[int(v) for v in row if isinstance(v, int)] for row in matrix if isinstance(row, list)],
            mirror=_opt_bool(obj, "mirror"),
            split=_opt_bool(obj, "split"),
            crossings=_opt_int(obj, "crossings"),
            details=details,
            status=status,
        )
