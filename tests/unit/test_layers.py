"""The layer rule of the package (DESIGN.md): arrows point one way.

Walks every module's import statements (also imports inside functions) with
``ast`` and checks that

* ``wheelrail.halfspace`` (kernels) imports no method package (normal,
  tangential, geometry, contact, transient, fe, sweeps) and no CLI;
* no method package imports the CLI;
* plotting is a leaf: no method package imports it at module level.
"""

from __future__ import annotations

import ast
import pathlib

import pytest

import wheelrail

ROOT = pathlib.Path(wheelrail.__file__).parent
METHOD_PACKAGES = ("normal", "tangential", "geometry", "contact", "transient", "fe", "sweeps")


def _imports(path: pathlib.Path) -> list[tuple[str, int, bool]]:
    """(absolute module imported, line, at module level) for every import in ``path``."""
    rel = path.relative_to(ROOT.parent).with_suffix("")
    parts = list(rel.parts)
    package = parts[:-1] if parts[-1] != "__init__" else parts[:-1]
    if parts[-1] == "__init__":
        package = parts[:-1]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    top = {id(n) for n in tree.body}
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            names = [mod] + [f"{mod}.{a.name}" for a in node.names]
            for n in names:
                out.append((n, node.lineno, id(node) in top))
        elif isinstance(node, ast.Import):
            for a in node.names:
                out.append((a.name, node.lineno, id(node) in top))
    return out


def _modules(sub: str):
    """The modules of package ``sub`` (none if it does not exist yet)."""
    base = ROOT / sub
    if base.is_dir():
        return sorted(base.rglob("*.py"))
    return [ROOT / f"{sub}.py"] if (ROOT / f"{sub}.py").exists() else []


def _violations(files, forbidden, top_only=False):
    bad = []
    for f in files:
        for mod, line, at_top in _imports(f):
            if top_only and not at_top:
                continue
            for pkg in forbidden:
                target = f"wheelrail.{pkg}"
                if mod == target or mod.startswith(target + "."):
                    bad.append(f"{f.relative_to(ROOT)}:{line} imports {mod}")
    return bad


def test_kernels_import_no_method_and_no_cli():
    assert _violations(_modules("halfspace"), METHOD_PACKAGES + ("cli", "plotting")) == []


@pytest.mark.parametrize("package", METHOD_PACKAGES)
def test_methods_never_import_the_cli(package):
    assert _violations(_modules(package), ("cli",)) == []


@pytest.mark.parametrize("package", METHOD_PACKAGES)
def test_methods_import_plotting_only_lazily(package):
    assert _violations(_modules(package), ("plotting",), top_only=True) == []


def test_the_walker_sees_a_violation(tmp_path):
    """The checker is not vacuous: a relative import of a method from a kernel is found."""
    fake = ROOT / "halfspace" / "_layer_probe_tmp.py"
    fake.write_text("def f():\n    from ..normal.bem import solve_normal\n", encoding="utf-8")
    try:
        bad = _violations([fake], ("normal",))
    finally:
        fake.unlink()
    assert bad and "wheelrail.normal.bem" in bad[0]
