"""``lkspace construct``: a scaffold with twist labels whose strands are a given knot or link type.

The type's diagram (KnotInfo/LinkInfo's PD code, SnapPy's for ``K14n10910``-style names,
spherogram's connected sum of the factors' for ``3_1#4_1``, or a PD code given) becomes
its checkerboard mesh (:mod:`lkspace.scaffolds.diagram_mesh`), placed by one of
:func:`~lkspace.scaffolds.constructed.layouts` (the one the shipped table checked first).
The result is checked before it is returned: the diagram of the labels
(:func:`~lkspace.knots.assembly.assemble_pd`) is named and must be the type asked for, in
the chirality asked for, and its default geometry (:func:`~lkspace.geometry.realization.realize`,
default parameters) must pass the embedding check, so ``export`` takes it as it is; a
placement that fails either check is replaced by the next one.  When no placement passes
the embedding check, the first one whose strands are right is returned (``clear`` false:
``export`` needs a smaller ``--radius`` for it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from ..errors import LkspaceError, ScaffoldError
from ..knots.assembly import assemble_pd
from ..knots.identification import Naming
from ..knots.naming import name_pd, one_based
from ..knots.tables import knot_modules
from ..model.scaffold import Scaffold
from ..scaffolds.constructed import design_scaffold, layouts, table
from .names import LinkType, parse_type, table_entries


@dataclass(frozen=True)
class Construction:
    """A constructed design: ``scaffold`` carries the labels; ``name``/``mirror`` as identify names it.

    ``layout``: the placement kept; ``crossings``: crossings of the diagram it was made from;
    ``builtin``: the built-in name of the same design (``knot:8_17``) or ``None``;
    ``clear``: its default geometry passes the embedding check.
    """

    scaffold: Scaffold
    name: str | None
    mirror: bool | None
    layout: str
    crossings: int
    builtin: str | None
    clear: bool = True


def _diagram(target: LinkType, typed: str) -> tuple[list[list[int]], bool]:
    """Return the PD code to build for a parsed type, and whether the mirror image is wanted."""
    mirror = target.chirality == "mirror"
    if target.factors or "#" in target.name:
        spherogram = knot_modules()[0]
        factors = target.factors or tuple(target.name.split("#"))
        link = None
        for factor in factors:
            base = factor[1:] if factor.startswith("m") and factor[1:] in table_entries() else factor
            piece = spherogram.Link(_table_pd(base, typed))
            if base != factor:
                piece = piece.mirror()
            link = piece if link is None else link.connected_sum(piece)
        assert link is not None
        return one_based(link.PD_code()), False
    return _table_pd(target.name, typed), mirror


def _table_pd(name: str, typed: str) -> list[list[int]]:
    shipped = table().get(name)
    if shipped is not None:
        return [list(x) for x in shipped.pd]
    entries = table_entries().get(name)
    if entries:
        return entries[0].pd_code()
    from ..knots.hoste import ht_manifold

    manifold = ht_manifold(name)
    if manifold is None:
        raise ScaffoldError(f"{typed!r}: no diagram of this type is known here")
    return one_based(manifold.link().PD_code())


def _named(scaffold: Scaffold) -> tuple[Naming, list[list[int]]]:
    """Return the naming of the design's strands and the PD code of their diagram."""
    assert scaffold.labels is not None
    diagram = assemble_pd(scaffold, scaffold.labels)
    pd = [[int(v) for v in x] for x in diagram.pd]
    return name_pd(pd, diagram.n_components, floer=False), pd


def reversals(pd: Sequence[Sequence[int]]) -> set[tuple[str, str]]:
    """``(Jones, HOMFLY-PT)`` of the link of ``pd`` (simplified) under every reversal of components but the first.

    The two polynomials of a link depend on its components' orientations, which a
    design's trace and a table's PD code choose independently; two diagrams of one
    oriented-up-to-reversal link share a pair.
    """
    spherogram, regina, _ = knot_modules()
    link = spherogram.Link([list(map(int, x)) for x in pd])
    link.simplify("global")
    simple = one_based(link.PD_code())
    k = len(link.link_components)
    out = set()
    for flips in range(2 ** (k - 1)):
        turned = regina.Link.fromPD(simple)
        for i in range(1, k):
            if flips >> (i - 1) & 1:
                turned.reverse(turned.component(i))
        out.add((str(turned.jones()), str(turned.homfly())))
    return out


def clear(scaffold: Scaffold) -> str | None:
    """Return why the default realization of ``scaffold`` is refused (strands too close), or ``None``."""
    from ..geometry.realization import realize

    try:
        realize(scaffold)
    except LkspaceError as exc:
        return str(exc).splitlines()[0]
    return None


def _matches(got: Naming, want: Naming, design: list[list[int]], target: list[list[int]]) -> bool:
    """Whether a design's naming is the target's: its name and chirality, or (unnamed) its invariants.

    ``design``, ``target``: PD codes of the design's diagram and of the type's (mirrored when asked).
    """
    if want.name is None:  # beyond the tables' names: Jones and HOMFLY-PT equal, for some orientation
        return got.name is None and bool(reversals(design) & reversals(target))
    return got.name == want.name and (want.mirror is None or got.mirror == want.mirror)


def construct(type_name: str | None = None, pd: Sequence[Sequence[int]] | None = None) -> Construction:
    """Return a design whose strands are ``type_name`` (a name ``solve --type`` takes) or the diagram ``pd``.

    Raises :class:`~lkspace.errors.LkspaceError` for an unknown name, a code that is no
    connected link diagram, or (a bug) when no placement realizes the type.
    """
    if (type_name is None) == (pd is None):
        raise ScaffoldError("give a type name or a PD code, not both", usage=True)
    builtin, first = None, None
    if pd is not None:
        code, mirror, label = [list(map(int, x)) for x in pd], False, "diagram"
        want = name_pd(code, _components(code), floer=False)
        if want.name == "0_1":
            return _unknot(len(code))
    else:
        target = parse_type(type_name or "")
        if target.name == "0_1":
            return _unknot(0)
        code, mirror = _diagram(target, type_name or "")
        label = target.label
        want = name_pd(code, target.components, floer=False)
        if mirror:
            want = want.updated(mirror=None if want.mirror is None else not want.mirror)
        if target.name in table() and not target.factors:
            kind = "knot" if target.components == 1 else "link"
            builtin = f"{kind}:{'m' if mirror else ''}{target.name}"
            first = table()[target.name].layout
    aim = code
    if mirror and want.name is None:
        aim = one_based(knot_modules()[0].Link(code).mirror().PD_code())
    tried: list[str] = []
    fallback = None
    for layout in dict.fromkeys([first or "sphere", *layouts(code)]):
        try:
            scaffold = design_scaffold(code, label, layout)
            assert scaffold.labels is not None
            if mirror:
                scaffold = scaffold.with_labels(-scaffold.labels)
            got, design = _named(scaffold)
        except LkspaceError as exc:
            tried.append(f"{layout}: {exc}")
            continue
        if not _matches(got, want, design, aim):
            tried.append(f"{layout}: strands named {got.chiral_name or got.name}")
            continue
        made = Construction(scaffold, got.name, got.mirror, layout, len(code), builtin if layout == first else None)
        refused = clear(scaffold)
        if refused is None:
            return made
        fallback = fallback or replace(made, clear=False)
        tried.append(f"{layout}: {refused}")
    if fallback is not None:
        return fallback
    raise ScaffoldError(
        f"{label}: none of {len(tried)} placements of its mesh realizes the diagram "
        f"({'; '.join(tried[:2])}, ...); please report it"
    )


def _unknot(crossings: int) -> Construction:
    """Return the unknot: one triangle, its strand running once around it."""
    scaffold = Scaffold.from_faces([[1.0, 0.0, 0.0], [-0.5, 0.866, 0.0], [-0.5, -0.866, 0.0]], [[0, 1, 2]], name="0_1")
    return Construction(scaffold.with_labels([0, 0, 0]), "0_1", None, "flat", crossings, None)


def _components(pd: list[list[int]]) -> int:
    from ..scaffolds.diagram_mesh import check_pd, link_components

    return link_components(check_pd(pd))
