"""Case files written before the keys were renamed still read, with a warning naming the new key.

Renamed for one name per quantity: ``[contact] load`` → ``Fn``; ``[transient]``
``normal_force`` → ``Fn``, ``approach`` → ``penetration``, ``tangential_force`` → ``Fx``;
``[method.bem]`` ``elements`` → ``grid_elements`` (and ``margin``, ``tol``); ``[sweep]``
and ``[sweep.points]`` ``load`` → ``Fn``. The old file
must give the same case as the new one (compared field by field), and giving both names
is refused naming both.
"""

from __future__ import annotations

import numpy as np
import pytest
from _helpers import POINT_CASE, SOLVE_CASE, assert_clean_failure, run_cli

from wheelrail.cases.files import load_contact_case, load_transient_case
from wheelrail.cases.files._reader import RenamedKeyWarning

OLD_POINT = POINT_CASE.replace("Fn = 7500.0", "load = 7500.0")

TRANSIENT = """[contact]
Fn = 10000.0
A = 1.0
B = 1.5
[friction]
mu = 0.3
[transient]
travel = 0.002
step = 1e-4
elements = 12
{loads}
"""
NEW_T = TRANSIENT.format(loads="Fn = 10000.0\nFx = 2000.0")
OLD_T = TRANSIENT.format(loads="normal_force = 10000.0\ntangential_force = 2000.0")


def test_contact_load_reads_as_fn_with_a_warning():
    assert "load = 7500.0" in OLD_POINT
    with pytest.warns(RenamedKeyWarning, match=r"\[contact\] load: this key is now called 'Fn'"):
        old = load_contact_case(OLD_POINT)
    new = load_contact_case(POINT_CASE)
    assert old.hertz_contact.Fn == new.hertz_contact.Fn == 7500.0
    assert old.hertz_contact.a == new.hertz_contact.a


def test_renamed_key_is_a_deprecation_warning():
    assert issubclass(RenamedKeyWarning, DeprecationWarning)


def test_both_names_is_one_line(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_text(POINT_CASE.replace("Fn = 7500.0", "Fn = 7500.0\nload = 7500.0")
                 + "[method.fastsim]\nnx = 8\nny = 8\n")
    code, _, err = run_cli(["solve", p, "-q"], capsys)
    assert_clean_failure(code, err, "c.toml", "[contact] load", "former name of 'Fn'")


def test_solve_command_prints_the_warning_and_solves(tmp_path, capsys):
    p = tmp_path / "old.toml"
    p.write_text(SOLVE_CASE.replace("Fn = 7500.0", "load = 7500.0"))
    code, out, err = run_cli(["solve", p, "-q"], capsys)
    assert code == 0, err
    assert any(ln.startswith("wheelrail: warning: ") and "now called 'Fn'" in ln
               and "RenamedKeyWarning" in ln for ln in err), err


def test_transient_old_keys():
    with pytest.warns(RenamedKeyWarning) as rec:
        old = load_transient_case(OLD_T)
    text = " ".join(str(w.message) for w in rec)
    assert "normal_force: this key is now called 'Fn'" in text
    assert "tangential_force: this key is now called 'Fx'" in text
    new = load_transient_case(NEW_T)
    assert old.settings["Fn"](0.0) == new.settings["Fn"](0.0) == 10000.0
    assert old.settings["Fx"](0.0) == new.settings["Fx"](0.0) == 2000.0


def test_transient_approach_reads_as_penetration():
    text = TRANSIENT.format(loads="approach = 2e-5\nxi = -0.001")
    with pytest.warns(RenamedKeyWarning, match="approach: this key is now called 'penetration'"):
        case = load_transient_case(text)
    assert case.settings["penetration"](0.0) == 2e-5


def test_bem_elements_reads_as_grid_elements():
    text = POINT_CASE + '[method]\nnormal = "bem"\n[method.bem]\nelements = 16\n'
    with pytest.warns(RenamedKeyWarning, match=r"\[method.bem\] elements: this key is now "
                                               r"called 'grid_elements'"):
        case = load_contact_case(text)
    assert case.normal.grid_elements == 16


def test_exact_elements_is_not_renamed():
    """``elements`` is still the exact theory's own option: no warning, no rename."""
    import warnings

    text = POINT_CASE + '[method]\ntangential = "exact"\n[method.exact]\nelements = 16\n'
    with warnings.catch_warnings():
        warnings.simplefilter("error", RenamedKeyWarning)
        case = load_contact_case(text)
    assert case.tangential.elements == 16


SWEEP = """[sweep]
method = "linear"
mu = 0.3
{fn}A = 1.087
B = 1.667
{axes}"""


def test_sweep_load_reads_as_fn_with_a_warning():
    """A sweep file written before the renaming (``load``) gives the same spec, hash
    included, as one with ``Fn``: a store made from either resumes with the other."""
    from wheelrail.sweeps import load_sweep

    new = load_sweep(SWEEP.format(fn="Fn = 10000.0\n", axes="xi = [0.0, 0.001]\n"))
    with pytest.warns(RenamedKeyWarning, match=r"\[sweep\] load: this key is now called 'Fn'"):
        old = load_sweep(SWEEP.format(fn="load = 10000.0\n", axes="xi = [0.0, 0.001]\n"))
    assert old.fixed["Fn"] == new.fixed["Fn"] == 10000.0 and "load" not in old.fixed
    assert old.sha256 == new.sha256


def test_sweep_points_load_column():
    from wheelrail.sweeps import load_sweep

    pts = "[sweep.points]\n{col} = [10000.0, 5000.0]\nxi = [0.0, 0.001]\n"
    with pytest.warns(RenamedKeyWarning, match=r"\[sweep.points\] load: this key is now "
                                               r"called 'Fn'"):
        old = load_sweep(SWEEP.format(fn="", axes=pts.format(col="load")))
    new = load_sweep(SWEEP.format(fn="", axes=pts.format(col="Fn")))
    assert old.sha256 == new.sha256 and dict(old.axes)["Fn"].tolist() == [10000.0, 5000.0]


def test_sweep_with_both_names_is_one_line(tmp_path, capsys):
    p = tmp_path / "s.toml"
    p.write_text(SWEEP.format(fn="Fn = 1e4\nload = 1e4\n", axes="xi = [0.0]\n"))
    code, _, err = run_cli(["sweep", p, "--out", tmp_path / "o.zarr", "-q"], capsys)
    assert_clean_failure(code, err, "s.toml", "[sweep] load", "former name of 'Fn'")
    assert not (tmp_path / "o.zarr").exists()


def test_sweep_command_runs_an_old_file(tmp_path, capsys):
    """The old file runs to the same forces as the new one (linear theory, Kalker 1967)."""
    from wheelrail.sweeps import open_sweep

    for name, fn in (("old", "load"), ("new", "Fn")):
        p = tmp_path / f"{name}.toml"
        p.write_text(SWEEP.format(fn=f"{fn} = 10000.0\n", axes="xi = [0.0, 0.001]\n"))
        code, _, err = run_cli(["sweep", p, "--out", tmp_path / f"{name}.zarr", "-q"], capsys)
        assert code == 0, err
        if name == "old":
            assert any(ln.startswith("wheelrail: warning: ") and "now called 'Fn'" in ln
                       for ln in err), err
    old, new = (open_sweep(tmp_path / f"{n}.zarr") for n in ("old", "new"))
    assert np.array_equal(old["Fx"].values, new["Fx"].values)
    assert float(old["Fx"].values[1]) < 0.0       # Kalker's sign: xi > 0 gives Fx < 0
