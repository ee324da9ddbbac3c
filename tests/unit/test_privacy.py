"""Packages use each other's public names only: a private name (``_name``), or any name of a
private module (``normal/_gap.py``), imported from another package must be on the
allow-list below, each entry with its reason.

"Package" is the top level under ``wheelrail`` (``normal``, ``fe``, ``cli``, ...; a
top-level module such as ``hertzian`` counts as its own package). Imports inside one
package are free. The package-wide private base modules (``wheelrail/_validation.py``,
``_toml.py``, ``_atomic.py``, ``_resources.py``, ``_version.py``, ``_numba_cache.py``)
exist to be shared by every package and are not counted. Every ``import`` statement is
read with :mod:`ast`, at module level and inside functions; relative imports are resolved.
tests/unit/test_layers.py checks the direction of the imports; this test checks their
privacy. A planted violation is detected (the walker is not vacuous).
"""

from __future__ import annotations

import ast
import pathlib

import wheelrail

ROOT = pathlib.Path(wheelrail.__file__).parent

#: (importing package, exporting module) -> (names, reason). Shrink it; do not grow it
#: without a reason that a public name would not serve.
ALLOWED = {
    ("cli", "wheelrail.plotting._common"): (
        {"finish", "new_figure"},
        "the figure helpers of the plotting package, shared by the commands that draw"),
    ("transient", "wheelrail.plotting._common"): (
        {"finish", "new_figure"},
        "the same figure helpers for the transient figures"),
    ("cli", "wheelrail.cases.files._reader"): (
        {"Reader", "read_friction", "read_methods", "read_toml", "configure"},
        "the dynamics and wear commands read their case files with the case-file package's "
        "reader (configure: the wear law's options as the methods' are)"),
    ("cli", "wheelrail.dynamics"): (
        {"_motion"},
        "the first-run notice asks numba whether the dynamics time loop is cached"),
    ("cli", "wheelrail.fe"): (
        {"_explicit"},
        "the run estimate asks numba whether the FE time loop is cached"),
    ("cli", "wheelrail.geometry.contact_search"): (
        {"_SIGMA"},
        "the geometry command prints the contact search's sampling width"),
    ("cli", "wheelrail.validation._report"): (
        {"_err", "_tol"},
        "the command prints the report's errors and tolerances as the report formats them"),
    ("normal", "wheelrail.geometry._local_cubic"): (
        {"local_cubic"},
        "the separation line's interpolation: one kernel for the reference separation "
        "(geometry) and its compiled twin (normal), so both give one line"),
    ("contact", "wheelrail.geometry.contact_search"): (
        {"_Pose"},
        "the wheel-rail drivers take the contact search's pose record as it is"),
    ("contact", "wheelrail.geometry.points"): (
        {"_side_from_row"},
        "the wheel-rail drivers map contact rows to wheel sides as the geometry does"),
    ("contact", "wheelrail.geometry.elastic"): (
        {"_regularised_B"},
        "the wheel-rail driver regularises the lateral curvature as the elastic geometry does"),
    ("contact", "wheelrail.hertzian"): (
        {"_vertical_approach"},
        "the vertical approach of a tilted Hertz contact, one implementation"),
    ("contact", "wheelrail.normal._gap"): (
        {"DEFAULT_SEARCH", "_enlarged_bounds", "_evaluate", "_grid_on", "_window",
         "contact_patches", "potential_contact_grid"},
        "the automatic window is built on the gap-problem machinery of the BEM"),
    ("dynamics", "wheelrail.normal._kp_kernel"): (
        {"kp_line_regions", "kpec_line_regions"},
        "the compiled dynamics contact calls the Kik-Piotrowski kernel itself (no copy)"),
    ("dynamics", "wheelrail.normal._patch_kernel"): (
        {"weighted_means"},
        "the compiled dynamics contact calls the patch kernel itself (no copy)"),
    ("dynamics", "wheelrail.normal._strips"): (
        {"_LN_MAX", "_hertz_table"},
        "the dynamics' fast path reads the strip methods' Hertz table"),
    ("dynamics", "wheelrail.tangential._fastsim_kernel"): (
        {"fastsim_hertz_batch"},
        "the compiled dynamics laws call the FASTSIM kernel itself (no copy)"),
    ("dynamics", "wheelrail.tangential._table_kernel"): (
        {"point_forces"},
        "the compiled dynamics laws call the table-law kernel itself (no copy)"),
    ("dynamics", "wheelrail.tangential.fastsim"): (
        {"_kalker_table", "_profile", "_resample_weights", "_strip_t"},
        "the dynamics' fast FASTSIM path reuses the method's tables and strip weights"),
    ("dynamics", "wheelrail.contact.wheelrail"): (
        {"_creepage_at"},
        "the creepages at a contact point, one implementation"),
    ("dynamics", "wheelrail.geometry._curves"): (
        {"PiecewiseCubic", "SAMPLE_STEP"},
        "the dynamics' compiled contact samples the profiles' splines"),
    ("dynamics", "wheelrail.geometry.contact_search"): (
        {"_side_args"},
        "the dynamics' compiled contact search takes the geometry's per-side arrays"),
    ("normal", "wheelrail.geometry.contact_search"): (
        {"_SIGMA", "_Pose"},
        "the separation sampling width and pose record of the contact search"),
    ("normal", "wheelrail.geometry._checks"): (
        {"check_side"},
        "the same check of a wheel side as the geometry"),
    ("normal", "wheelrail.hertzian"): (
        {"_checked_curvatures", "_make", "_vertical_approach"},
        "the Hertz normal method builds its contacts with the Hertz module's constructors"),
    ("normal", "wheelrail.halfspace._memo"): (
        {"grid_key", "memo"},
        "the BEM memoises its influence matrices with the half-space's cache"),
    ("sweeps", "wheelrail.tangential.table"): (
        {"_coefficients", "_spin_length", "_spline_operator"},
        "the table builder writes the coefficients that the table law reads and fits "
        "the law's own spline in its refined regions"),
    ("tangential", "wheelrail.halfspace.rolling"): (
        {"_BlockConvolution", "_block_convolution", "_contact_box",
         "_rolling_and_influence_kernels"},
        "the exact theory uses the half-space's FFT convolution internals"),
    ("tangential", "wheelrail.normal._bem_solver"): (
        {"MIN_ACROSS", "check_resolution"},
        "the exact theory checks its grid resolution as the BEM does"),
    ("transient", "wheelrail.halfspace.rolling"): (
        {"_BlockConvolution", "_block_multiply"},
        "transient rolling uses the half-space's FFT convolution internals"),
    ("transient", "wheelrail.tangential.exact._kernels"): (
        {"_SPIN_SHIFT"},
        "transient rolling shares the exact theory's spin-shift constant"),
    ("validation", "wheelrail.normal._base"): (
        {"GapProblem"},
        "GapProblem is public (wr.GapProblem); imported from the module that defines it"),
}

BASE_MODULES = {"_validation", "_toml", "_atomic", "_resources", "_version", "_numba_cache"}


def _module_name(path: pathlib.Path, root: pathlib.Path):
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    is_pkg = parts[-1] == "__init__"
    return (parts[:-1] if is_pkg else parts), is_pkg


def _package(dotted: str) -> str:
    parts = dotted.split(".")
    return parts[1] if len(parts) > 1 else ""


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_imports(root: pathlib.Path = ROOT) -> set:
    """(importing package, exporting module, name, importing module) of every private name
    imported across packages."""
    out = set()
    for path in sorted(root.rglob("*.py")):
        parts, is_pkg = _module_name(path, root)
        here = ".".join(parts)
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = parts if is_pkg else parts[:-1]
                    base = base[:len(base) - (node.level - 1)]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                pairs = [(target, a.name) for a in node.names]
            elif isinstance(node, ast.Import):
                pairs = [(a.name.rsplit(".", 1)[0], a.name.rsplit(".", 1)[-1])
                         for a in node.names if "." in a.name]
            else:
                continue
            for target, name in pairs:
                tparts = target.split(".")
                if tparts[0] != root.name or _package(target) == _package(here):
                    continue
                if len(tparts) == 1 and name in BASE_MODULES:
                    continue  # a package-wide private base module (module docstring)
                if len(tparts) == 2 and tparts[1] in BASE_MODULES:
                    continue
                if _is_private(name) or any(_is_private(t) for t in tparts[1:]):
                    out.add((_package(here), target, name, here))
    return out


def _violations(found) -> list:
    bad = []
    for pkg, target, name, here in sorted(found):
        names, _ = ALLOWED.get((pkg, target), (set(), ""))
        if name not in names:
            bad.append(f"{here} imports {name} from {target}")
    return bad


def test_no_package_imports_another_packages_private_name():
    assert _violations(private_imports()) == []


def test_every_allow_list_entry_has_a_reason():
    for key, (names, reason) in ALLOWED.items():
        assert names and len(reason) > 20, key


def test_a_planted_private_import_is_detected(tmp_path):
    pkg = tmp_path / "wheelrail"
    (pkg / "normal").mkdir(parents=True)
    (pkg / "contact").mkdir()
    for d in (pkg, pkg / "normal", pkg / "contact"):
        (d / "__init__.py").write_text("")
    (pkg / "_validation.py").write_text("def positive(name, v):\n    return v\n")
    (pkg / "normal" / "_gap.py").write_text("def _planted():\n    pass\n")
    (pkg / "normal" / "bem.py").write_text("from ._gap import _planted\n")  # same package
    (pkg / "contact" / "window.py").write_text(
        "from .._validation import positive\n"                               # base module
        "def f():\n    from ..normal._gap import _planted\n    return _planted\n")
    found = private_imports(pkg)
    assert {(p, t, n) for p, t, n, _ in found} == {("contact", "wheelrail.normal._gap",
                                                    "_planted")}
    assert _violations(found) == ["wheelrail.contact.window imports _planted from "
                                  "wheelrail.normal._gap"]
