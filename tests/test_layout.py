"""The package's architecture: no import cycles, layers that import only downward, no private names
across modules, small files; docs/architecture.md shows the same layers."""

import ast
import pathlib

import networkx as nx

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "lkspace"


def module_name(path: pathlib.Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(path: pathlib.Path):
    """``(module imported, names imported)`` for every import of lkspace modules in ``path``."""
    here = module_name(path).split(".")
    package = here if path.name == "__init__.py" else here[:-1]
    tree = ast.parse(path.read_text())
    type_only = {  # imports under ``if TYPE_CHECKING:`` never run
        id(inner) for node in ast.walk(tree) if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
        for stmt in node.body for inner in ast.walk(stmt)
    }  # fmt: skip
    for node in ast.walk(tree):
        if id(node) in type_only:
            continue
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] == "lkspace":
                yield target, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "lkspace":
                    yield alias.name, []


def import_graph() -> nx.DiGraph:
    modules = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph = nx.DiGraph()
    graph.add_nodes_from(modules)
    for name, path in modules.items():
        for target, names in imports(path):
            for imported in names or [""]:
                sub = f"{target}.{imported}"
                graph.add_edge(name, sub if sub in modules else target)
    return graph


def test_no_import_cycles():
    graph = import_graph()
    graph.remove_node("lkspace")  # the package root only re-exports, lazily
    cycles = [c for c in nx.strongly_connected_components(graph) if len(c) > 1]
    assert cycles == []


def test_data_flows_one_way():
    graph = import_graph()
    stages = ["model", "strands", "design", "catalog"]
    for i, low in enumerate(stages):
        for high in stages[i + 1 :]:
            bad = [(a, b) for a, b in graph.edges if a.startswith(f"lkspace.{low}") and b.startswith(f"lkspace.{high}")]
            assert bad == [], f"{low} must not import {high}"


LAYERS = (
    ("errors", "words", "compiled"),
    ("runtime",),
    ("model",),
    ("scaffolds",),
    ("io",),
    ("strands", "symmetry"),
    ("design", "inverse", "geometry", "dna"),
    ("knots",),
    ("formats",),
    ("catalog",),
    ("linktypes",),
    ("api",),
    ("lkspace",),
    ("studio", "dask_worker"),
    ("cli",),
    ("blender", "__main__"),
)
"""The packages of lkspace from the bottom up (a top-level module such as ``api`` counts as a package;
``lkspace`` is the package root, ``__init__.py``): a package imports only from layers below its own."""

ALLOWED = {
    "errors": set(),
    "words": set(),
    "compiled": set(),
    "runtime": {"errors"},
    "model": {"errors", "words"},
    "scaffolds": {"errors", "model"},
    "io": {"errors", "model", "runtime", "scaffolds", "words"},
    "strands": {"compiled", "model", "runtime", "words"},
    "symmetry": {"compiled", "errors", "model", "runtime", "words"},
    "design": {"compiled", "errors", "model", "runtime", "strands", "symmetry", "words"},
    "inverse": {"compiled", "errors", "model", "runtime", "strands", "symmetry", "words"},
    "geometry": {"compiled", "errors", "model", "runtime", "strands", "words"},
    "dna": {"errors", "io", "model", "strands"},
    "knots": {"compiled", "errors", "geometry", "io", "model", "runtime", "strands", "words"},
    "formats": {"errors", "geometry", "io", "knots", "model", "runtime", "words"},
    "catalog": {"compiled", "design", "dna", "errors", "io", "knots", "model", "runtime", "strands", "symmetry", "words"},
    "linktypes": {"catalog", "design", "errors", "formats", "geometry", "io", "knots", "model", "runtime", "scaffolds", "strands", "symmetry", "words"},
    "api": {"io"},
    "lkspace": {"api", "errors"},
    "studio": {"catalog", "dna", "errors", "formats", "geometry", "io", "knots", "linktypes", "lkspace", "model", "runtime", "scaffolds", "symmetry"},
    "blender": {"cli", "dna", "errors", "formats", "geometry", "inverse", "io", "knots", "model", "strands", "symmetry", "words"},
    "dask_worker": {"runtime"},
    "cli": {"catalog", "design", "dna", "errors", "formats", "geometry", "inverse", "io", "knots", "linktypes", "lkspace", "model", "runtime", "scaffolds", "strands", "studio", "symmetry", "words"},
    "__main__": {"cli"},
}  # fmt: skip
"""Package -> the packages it imports (at run time, anywhere in its modules): the code as it is.

A new import between packages must be added here and to docs/architecture.md; an upward one
(into a layer above, or within one layer) is refused by :func:`test_allowed_imports_point_down`.
"""

STUDIO_INTERNALS = {
    "lkspace.catalog.verify": "the catalog browser opens and checks catalogs (open_catalog, damaged)",
    "lkspace.dna.build": "the DNA download builds the design's nucleotides (build)",
    "lkspace.dna.oxdna": "the DNA download is a zip of the oxDNA and oxView files (zip_bytes)",
    "lkspace.formats.colors": "the page colours strands as lkspace export does (PALETTE, a ring copy's tone: curve_tones)",
    "lkspace.formats.diagram": "the simplified diagram drawn as export --diagram draws it (planar_diagram)",
    "lkspace.formats.registry": "the download formats the page offers (FORMATS)",
    "lkspace.geometry.clearance": "a preview realized without measuring is measured when the page asks",
    "lkspace.geometry.realization": "an edit realizes only the strands it changed (realize_reusing)",
    "lkspace.io.design_json": "design files saved from and opened in the page (scaffold, labels, view)",
    "lkspace.io.json_values": "request bodies typed as JSON values, the one type every wire record's from_json reads",
    "lkspace.io.obj": "an uploaded .obj is parsed from bytes (no file)",
    "lkspace.io.scaffold_json": "scaffolds sent to and uploaded from the page as JSON",
    "lkspace.io.sources": "the one scaffold file the studio reads: the MESH of lkspace studio FILE",
    "lkspace.io.text": "uploaded JSON parsed with the input bounds of every lkspace reader",
    "lkspace.knots.diagram": "the diagram beside the 3D view: crossings of the projection identify uses",
    "lkspace.linktypes.common_names": "common names beside identify's answers and catalog names",
    "lkspace.linktypes.lookup": "the page asks the shipped atlas for the simplest designs of a type (/api/lookup)",
    "lkspace.model.specs": "the label set typed in the page's solve form",
    "lkspace.model.validation": "labels and null sides sent by the page",
    "lkspace.runtime.progress": "progress of identify and solve jobs reported to the page",
    "lkspace.scaffolds": "the built-in names the page lists (and the default)",
    "lkspace.symmetry.edge_orbits": "a subgroup name typed in the page checked before a job starts",
    "lkspace.runtime.workers": "identify and solve run in worker processes the studio owns",
}
"""What the studio uses below the public API (``lkspace.errors`` aside), and why; it computes through
the public functions (``trace``, ``realize``, ``export``, ``identify``, ``solve``, ``relax``)."""


def package_of(module: str) -> str:
    """``lkspace.design.space`` -> ``design``; ``lkspace.api`` -> ``api``; the root ``lkspace`` -> ``lkspace``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def package_imports() -> dict[tuple[str, str], list[tuple[str, str]]]:
    """``(package, package imported)`` -> the module-level imports ``(module, module imported)`` behind it."""
    found: dict[tuple[str, str], list[tuple[str, str]]] = {}
    for a, b in import_graph().edges:
        if package_of(a) != package_of(b):
            found.setdefault((package_of(a), package_of(b)), []).append((a, b))
    return found


def test_every_package_has_a_layer_and_a_row():
    layered = [p for layer in LAYERS for p in layer]
    code = {package_of(m) for m in import_graph().nodes}
    assert len(layered) == len(set(layered)), "a package is in two layers"
    assert set(layered) == code == set(ALLOWED), (
        f"packages without a layer: {sorted(code - set(layered))}; layers of no package: {sorted(set(layered) - code)}"
    )


def test_allowed_imports_point_down():
    level = {p: i for i, layer in enumerate(LAYERS) for p in layer}
    upward = [(a, b) for a, targets in ALLOWED.items() for b in targets if level[b] >= level[a]]
    assert upward == [], f"ALLOWED lets a package import from its own layer or above: {upward}"


def test_packages_import_only_what_the_table_allows():
    found = package_imports()
    unlisted = [
        f"{a} imports {b} ({', '.join(f'{x} -> {y}' for x, y in found[a, b][:3])}); {a} may import only "
        f"{sorted(ALLOWED.get(a, ()))}: an import into a higher layer breaks the layering of docs/architecture.md, "
        "a new downward one is added to ALLOWED and to the table in docs/architecture.md"
        for a, b in sorted(found)
        if b not in ALLOWED.get(a, set())
    ]
    assert unlisted == [], "\n".join(unlisted)
    unused = sorted((a, b) for a, targets in ALLOWED.items() for b in targets if (a, b) not in found)
    assert unused == [], f"ALLOWED lists imports the code no longer makes (remove them here and in the docs): {unused}"


def test_no_cycles_between_packages():
    graph = nx.DiGraph(list(package_imports()))
    assert nx.is_directed_acyclic_graph(graph), list(nx.simple_cycles(graph))


def test_studio_uses_the_public_api_and_named_internals():
    used = {
        b
        for a, b in import_graph().edges
        if package_of(a) == "studio" and package_of(b) not in ("studio", "lkspace", "errors")
    }
    assert used == set(STUDIO_INTERNALS), (
        f"the studio imports internals not in STUDIO_INTERNALS: {sorted(used - set(STUDIO_INTERNALS))}; "
        f"listed but unused: {sorted(set(STUDIO_INTERNALS) - used)} (and docs/architecture.md says which and why)"
    )


BOUNDARY = (
    "lkspace.api",
    "lkspace.io",
    "lkspace.cli.",
    "lkspace.studio.",
    "lkspace.blender.",
    "lkspace.catalog.reader",
    "lkspace.catalog.settings",
)
"""The modules that may turn a path or a built-in name into a scaffold (``lkspace.io.sources``): the
public API, io itself, the programs, and the catalog reader and the checks of what a catalog
records (a catalog stores its scaffold's name)."""


def test_only_the_boundary_loads_scaffolds():
    loading = sorted(a for a, b in import_graph().edges if b == "lkspace.io.sources" and not a.startswith(BOUNDARY))
    assert loading == [], f"computing modules take a Scaffold; these load paths or names: {loading}"


def label(package: str) -> str:
    """How docs/architecture.md names a package: ``design/``, ``api.py``, ``__init__.py`` (the root)."""
    if package == "lkspace":
        return "`__init__.py`"
    return f"`{package}/`" if (PACKAGE / package).is_dir() else f"`{package}.py`"


def architecture_table() -> str:
    """The layers and what each package imports, as docs/architecture.md shows them (top layer first)."""
    rows = ["| layer | package | imports |", "|---|---|---|"]
    for i, layer in reversed(list(enumerate(LAYERS, start=1))):
        for package in layer:
            imported = ", ".join(label(p) for p in sorted(ALLOWED[package])) or "nothing of lkspace"
            rows.append(f"| {i} | {label(package)} | {imported} |")
    return "\n".join(rows) + "\n"


def architecture_layers() -> str:
    """The layers as the diagram of docs/architecture.md draws them (top layer first)."""
    lines = [f"{i:>2}  " + "  ".join(label(p).strip("`") for p in layer) for i, layer in enumerate(LAYERS, start=1)]
    return "\n".join(reversed(lines)) + "\n"


def test_architecture_doc_shows_the_layers_and_the_table():
    doc = (PACKAGE.parent / "docs" / "architecture.md").read_text()
    for text in (architecture_layers(), architecture_table()):
        assert text in doc, f"docs/architecture.md must hold this (generated from LAYERS and ALLOWED):\n{text}"
    for module, why in STUDIO_INTERNALS.items():
        assert f"`{module.removeprefix('lkspace.')}`" in doc, (
            f"docs/architecture.md: the studio's use of {module} ({why})"
        )


def test_no_private_names_across_modules():
    crossing = [
        (module_name(path), target, name)
        for path in PACKAGE.rglob("*.py")
        for target, names in imports(path)
        for name in names
        if name.startswith("_") and not name.startswith("__")
    ]
    assert crossing == []


def test_files_stay_small():
    big = {module_name(p): n for p in PACKAGE.rglob("*.py") if (n := len(p.read_text().splitlines())) > 420}
    assert big == {}
