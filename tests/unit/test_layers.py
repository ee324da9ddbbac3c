"""The layers of the package point one way, and there is no import cycle (DESIGN.md).

The test reads every ``import`` statement of every module with :mod:`ast` —
at module level *and inside functions* — resolves relative imports, adds the
implicit import of every enclosing package (``import a.b.c`` runs
``a/b/__init__.py``) and checks on that graph:

* no cycle (Tarjan's strongly connected components);
* no import that points up the layers below;
* function-level imports of wheelrail modules only where they load an optional,
  heavy leaf (plotting, i.e. matplotlib) or inside the command line, whose
  sub-commands import the library when they run so that ``wheelrail --help``
  starts without loading the solvers; a leaf can neither close a cycle nor
  point up.

Layers, lowest first (a module may import its own layer and those below)::

    0 base      errors, conventions, _validation, materials, plausibility, _toml, ...
    1 kernels   halfspace/*, numba kernel modules (*_kernel, *_kernels)
    2 core      options, results, patch (ContactPatch), hertzian (HertzContact)
    3 methods   profiles, geometry, normal, tangential
    4 drivers   contact, transient, fe, sweeps, dynamics, wear
    5 API       wheelrail (package), api, prescribed, cases
    6 leaves    cli, casefile, plotting, validation, citations, *.plot(s)

Planted violations are detected (the walker is not vacuous).
"""

from __future__ import annotations

import ast
import collections
import pathlib
import re
import sys

import pytest

import wheelrail

ROOT = pathlib.Path(wheelrail.__file__).parent

BASE = {"errors", "conventions", "_validation", "materials", "plausibility", "_toml", "_atomic",
        "_resources", "_version", "_numba_cache"}
CORE = {"options", "results", "patch", "hertzian"}
METHODS = {"profiles", "geometry", "normal", "tangential", "reference"}
DRIVERS = {"contact", "transient", "fe", "sweeps", "dynamics", "wear"}
API = {"api", "prescribed", "cases"}
LEAVES = {"cli", "casefile", "plotting", "validation", "citations", "__main__"}
_KERNEL = re.compile(r"(^wheelrail\.halfspace(\.|$))|(_kernels?$)")
_PLOTTING = re.compile(r"(^|\.)(plotting|plot|plots)(\.|$)")
NAMES = ("base", "kernels", "core", "methods", "drivers", "API", "leaves")


def layer(module: str) -> int:
    """Layer number of a dotted module name (see the module docstring)."""
    parts = module.split(".")
    top = parts[1] if len(parts) > 1 else ""
    if top in BASE and len(parts) == 2:
        return 0
    if _KERNEL.search(module):
        return 1
    if top in CORE and len(parts) == 2:
        return 2
    if top in LEAVES or parts[-1] in ("plot", "plots"):
        return 6
    if module == "wheelrail" or top in API:
        return 5
    if top in DRIVERS:
        return 4
    if top in METHODS:
        return 3
    raise AssertionError(f"module {module} has no layer: add it to tests/unit/test_layers.py")


def modules(root: pathlib.Path = ROOT) -> dict:
    """Dotted name -> (path, is_package) of every module under ``root``."""
    out = {}
    for p in root.rglob("*.py"):
        parts = list(p.relative_to(root.parent).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        out[".".join(parts[:-1] if is_pkg else parts)] = (p, is_pkg)
    return out


def imports(name: str, path: pathlib.Path, is_pkg: bool, known) -> list:
    """(target module, line, at module level) of every wheelrail import in ``path``."""
    package = name.split(".") if is_pkg else name.split(".")[:-1]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    top = set()
    for n in tree.body:
        for m in ast.walk(n) if isinstance(n, (ast.If, ast.Try)) else (n,):
            top.add(id(m))
    out = []
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            targets = [f"{mod}.{a.name}" if f"{mod}.{a.name}" in known else mod
                       for a in node.names]
        elif isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        for t in targets:
            while t and t not in known and "." in t:
                t = t.rsplit(".", 1)[0]
            if t in known and t != name:
                out.append((t, node.lineno, id(node) in top))
    return out


def graph(root: pathlib.Path = ROOT):
    """Edges {module: {target: (line, at module level)}} including enclosing packages."""
    known = modules(root)
    edges = collections.defaultdict(dict)
    for name, (path, is_pkg) in known.items():
        for t, line, top in imports(name, path, is_pkg, known):
            edges[name].setdefault(t, (line, top))
            parts = t.split(".")
            for i in range(2, len(parts)):
                pkg = ".".join(parts[:i])
                if pkg in known and pkg != name and not name.startswith(pkg + "."):
                    edges[name].setdefault(pkg, (line, top))
    return known, edges


def cycles(nodes, edges) -> list:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10_000))

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in nodes:
        if v not in index:
            visit(v)
    return out


def upward(edges) -> list:
    return [f"{m} ({NAMES[layer(m)]}) imports {t} ({NAMES[layer(t)]}), line {line}"
            for m, ts in edges.items() for t, (line, _) in ts.items() if layer(t) > layer(m)]


def lazy(edges) -> list:
    """Function-level imports of wheelrail modules other than plotting, outside the CLI."""
    return [f"{m}:{line} imports {t} inside a function"
            for m, ts in edges.items() if not m.startswith("wheelrail.cli")
            for t, (line, top) in ts.items() if not top and not _PLOTTING.search(t)]


@pytest.fixture(scope="module")
def package_graph():
    return graph()


def test_every_module_has_a_layer(package_graph):
    known, _ = package_graph
    for name in known:
        layer(name)


def test_no_import_cycle(package_graph):
    known, edges = package_graph
    assert cycles(known, edges) == []


def test_no_import_points_up(package_graph):
    _, edges = package_graph
    assert upward(edges) == []


def test_function_level_imports_only_for_optional_leaves(package_graph):
    _, edges = package_graph
    assert lazy(edges) == []


def test_the_walker_sees_planted_violations(tmp_path):
    """A copy of the package with a kernel importing a method inside a function, a cycle
    and a function-level import: all three are found."""
    import shutil

    root = tmp_path / "wheelrail"
    shutil.copytree(ROOT, root, ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    (root / "halfspace" / "_probe.py").write_text(
        "def f():\n    from ..normal.bem import solve_normal\n", encoding="utf-8")
    (root / "options.py").write_text((root / "options.py").read_text(encoding="utf-8")
                                     + "\nfrom .tangential import polach\n", encoding="utf-8")
    known, edges = graph(root)
    assert any("wheelrail.halfspace._probe" in u and "wheelrail.normal.bem" in u
               for u in upward(edges))
    assert any("wheelrail.halfspace._probe" in u for u in lazy(edges))
    assert any("wheelrail.options" in c and "wheelrail.tangential.polach" in c
               for c in cycles(known, edges))


def test_no_source_file_over_1000_lines():
    long = {str(p.relative_to(ROOT)): n for p in ROOT.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 1000}
    assert long == {}
