"""The Python examples of the documentation run as written.

Every ```python block of README.md and docs/*.md is checked in two ways:

- statically, all of them: the block compiles and every attribute chain on
  ``wr`` (``wr.tangential.Fastsim``, ``wr.dynamics.simulate``, ...) and on names
  bound to such a chain (``D = wr.dynamics``; ``D.WheelsetModel``) exists in the
  package — a renamed or removed public name fails here;
- by running them, except the pages whose examples are long runs (vehicle
  dynamics, finite elements: minutes each). Blocks of one page run in order in
  one namespace, in a temporary directory, or in ``../shared/data/profiles`` for
  the page whose examples read the measured profiles there.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import wheelrail

ROOT = Path(__file__).resolve().parents[2]
#: pages whose examples are long runs: checked statically only
LONG = {"dynamics.md", "fe.md", "fe_plastic.md", "fe_transition.md", "wear.md"}
#: pages written by the docs build (docs/_ext/_methods_page.py; ignored by git): their
#: blocks are call fragments (``wr.solve(problem, ...)``), checked statically only
GENERATED = {"methods.md"}
PAGES = [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").glob("*.md")
                                      if p.name not in GENERATED)
#: pages whose examples read files from ../shared/data/profiles
NEEDS_PROFILES = {"profiles.md"}
PROFILES_DIR = ROOT.parent / "shared" / "data" / "profiles"


def _blocks_of(text):
    return re.findall(r"```python\n(.*?)```", text, re.DOTALL)


def _blocks(page):
    return _blocks_of(page.read_text(encoding="utf-8"))


def _methods_page():
    """methods.md as the docs build writes it, generated here from the registries
    (docs/_ext/_methods_page.py): the tests run before the docs build, so on a fresh clone
    the file is absent, and elsewhere it may be stale."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "_methods_page", ROOT / "docs" / "_ext" / "_methods_page.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.page()


ALL = [(p, i, code) for p in PAGES for i, code in enumerate(_blocks(p))]
ALL += [(ROOT / "docs" / "methods.md", i, code)
        for i, code in enumerate(_blocks_of(_methods_page()))]


def _chains(tree):
    """(root name, attribute path, line) of every attribute chain in ``tree``."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and not isinstance(getattr(node, "_parent", None),
                                                              ast.Attribute):
            path, cur = [], node
            while isinstance(cur, ast.Attribute):
                path.append(cur.attr)
                cur = cur.value
            if isinstance(cur, ast.Name):
                out.append((cur.id, path[::-1], node.lineno))
        for child in ast.iter_child_nodes(node):
            child._parent = node
    return out


def _resolve(obj, path):
    for name in path:
        obj = getattr(obj, name)
    return obj


def _missing_names(code):
    """Attribute chains on ``wr`` (and aliases of its modules) that do not exist."""
    tree = ast.parse(code)
    roots = {"wr": wheelrail}
    # aliases: NAME = wr.a.b (module or class), resolved in order of appearance
    for node in tree.body:
        if (isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name) and isinstance(node.value, ast.Attribute)):
            path, cur = [], node.value
            while isinstance(cur, ast.Attribute):
                path.append(cur.attr)
                cur = cur.value
            if isinstance(cur, ast.Name) and cur.id in roots:
                try:
                    roots[node.targets[0].id] = _resolve(roots[cur.id], path[::-1])
                except AttributeError:
                    pass                      # reported below
    missing = []
    for root, path, line in _chains(tree):
        if root not in roots:
            continue
        obj = roots[root]
        for k, name in enumerate(path):
            if not hasattr(obj, name):
                # stop at instances of classes: their attributes may be set at run time;
                # modules and classes must have the name
                if isinstance(obj, type) or type(obj).__name__ == "module":
                    missing.append(f"line {line}: {root}." + ".".join(path[:k + 1]))
                break
            obj = getattr(obj, name)
            if not (isinstance(obj, type) or type(obj).__name__ == "module"):
                break                         # a function or value: its result is not checked
    return missing


@pytest.mark.parametrize("page,index,code", ALL,
                         ids=[f"{p.name}#{i}" for p, i, _ in ALL])
def test_snippet_names_exist(page, index, code):
    """Every wr.* name the example uses exists (statically, also for the long pages)."""
    missing = _missing_names(code)
    assert not missing, f"{page.name} python block {index}: " + ", ".join(missing)


def test_the_checker_finds_a_missing_name():
    """The static check is not vacuous: a renamed name and an alias's name are found."""
    code = ("import wheelrail as wr\nD = wr.dynamics\nwr.tangential.Fastsimm(nx=3)\n"
            "D.WheelsetModell\nwr.hertz(1.0)\n")
    assert sorted(_missing_names(code)) == ["line 3: wr.tangential.Fastsimm",
                                           "line 4: D.WheelsetModell"]


RUN = [p for p in PAGES if p.name not in LONG | GENERATED and _blocks(p)]


@pytest.mark.parametrize("page", RUN, ids=[p.name for p in RUN])
def test_snippets_run(page, tmp_path, monkeypatch):
    """The page's examples run in order without an error (figures to a non-GUI backend)."""
    import matplotlib

    matplotlib.use("Agg")
    if page.name in NEEDS_PROFILES:
        if not PROFILES_DIR.is_dir():
            pytest.skip(f"needs {PROFILES_DIR}")
        monkeypatch.chdir(PROFILES_DIR)
    else:
        monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    ns = {"__name__": "__docs__"}
    for i, code in enumerate(_blocks(page)):
        try:
            exec(compile(code, f"{page.name} python block {i}", "exec"), ns)  # noqa: S102
        except Exception as exc:
            raise AssertionError(f"{page.name} python block {i} fails: "
                                 f"{type(exc).__name__}: {exc}") from exc
