"""The package's architecture: no import cycles, no private names across modules, small files."""

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
