"""`wheelrail fe CASE.toml`: indentation run writes its outputs; bad case files give one-line errors."""

import json

import numpy as np
import pytest

from _fe_case import indent_case

from wheelrail.cli.main import main

CASE = indent_case()


def test_fe_indent_writes_summary_vtu_patch_and_figure(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    out = tmp_path / "out"
    assert main(["fe", str(case), "--out", str(out)]) == 0
    assert (out / "patch.png").stat().st_size > 10_000
    summary = json.loads((out / "summary.json").read_text())
    assert summary["mode"] == "indent"
    assert abs(summary["Fn"] - 7500.0) < 10.0
    assert 0.5 < summary["p_max"] / summary["hertz"]["p_max"] < 1.2
    assert (out / "mesh.vtu").stat().st_size > 1000
    assert (out / "patch.nc").is_file()
    import meshio
    m = meshio.read(out / "mesh.vtu")
    assert m.cells[0].type == "hexahedron" and "von_mises" in m.cell_data


def test_fe_estimate_only_prints_steps(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE.replace('mode = "indent"', 'mode = "roll"'))
    assert main(["fe", str(case), "--estimate-only"]) == 0
    assert "explicit steps" in capsys.readouterr().out


@pytest.mark.parametrize("plastic, threads, ns", [(False, 1, 163.7), (True, 1, 214.7),
                                                   (False, 2, 106.3), (True, 2, 127.3)])
def test_fe_time_estimate_matches_the_measured_step(monkeypatch, plastic, threads, ns):
    """The estimate of a large explicit run against the measured wall time of the whole run
    (build, time loop, results) with the one-region time loop: Toumi et al.'s case on the
    1 mm mesh, 47 736 reduced hex8 x 7 533 steps, on the idle 2-core machine
    (docs/fe_plastic.md, "Cost": 163.7 / 214.7 ns per element and step on one thread, 106.3 /
    127.3 ns on two; elastic / plastic). The per-element constants come from the time loop of
    the same runs, the build and per-step constants from other runs: this checks that the
    parts add up to the measured whole (within 3 %)."""
    import wheelrail.cli.fe as F
    from wheelrail.fe import seed000_case

    monkeypatch.setattr(F, "_kernels_cached", lambda: True)
    case = seed000_case(plastic=plastic, mesh_size=1e-3, element="reduced")
    n, steps = 47_736, 7_533
    measured = ns * 1e-9 * n * steps
    est = F.seconds_estimate(case, n, steps, plastic, threads=threads)
    assert est == pytest.approx(measured, rel=0.03)
    assert F.seconds_estimate(case, n, steps, plastic, threads=8) == pytest.approx(
        F.seconds_estimate(case, n, steps, plastic, threads=2))


def test_fe_estimate_names_the_threads(tmp_path, capsys):
    import numba

    case = tmp_path / "case.toml"
    case.write_text(CASE.replace('mode = "indent"', 'mode = "roll"'))
    numba.set_num_threads(1)
    try:
        assert main(["fe", str(case), "--estimate-only"]) == 0
    finally:
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    out = " ".join(capsys.readouterr().out.split())
    assert "explicit steps" in out and "on 1 thread " in out


def test_fe_bad_key_is_a_usage_error(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE + "mesh_sise = 1.0\n")
    assert main(["fe", str(case)]) == 2
    assert "mesh_sise" in capsys.readouterr().err


ROLL = """
[fe]
wheel = "cylinder"
rail = "60E1"
radius = 0.46
Fn = 7500.0
mu = 0.2
creepage = [7e-4, 0.0, 0.0]
mesh_size = 2e-3
element = "reduced"
mass_scaling = 400.0
depth = 3.0
half_width = 3.0
half_length = 3.0
travel = 0.006
"""


def test_fe_roll_continues_from_a_restart_file(tmp_path):
    """`--restart FILE` continues a run: the same steady force as the uninterrupted run, and
    the run writes DIR/restart.npz (the latest state) itself."""
    from wheelrail.cli.fe import case_from_toml
    from wheelrail.fe import solve

    case_file = tmp_path / "roll.toml"
    case_file.write_text(ROLL)
    case, _ = case_from_toml(case_file)
    full = solve(case, progress=False, restart_file=tmp_path / "r_{step}.npz", restart_every=300)
    mid = sorted(tmp_path.glob("r_*.npz"), key=lambda p: int(p.stem[2:]))[0]
    out = tmp_path / "out"
    assert main(["fe", str(case_file), "--out", str(out), "--no-figures",
                 "--restart", str(mid)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["restarted_at_step"] == int(mid.stem[2:]) > 0
    assert summary["Fx"] == full.Fx                       # bit for bit
    import pandas as pd
    hist = pd.read_csv(out / "history.csv")
    for name in ("Fx", "Fy", "Fn", "friction", "contact_work", "energy_error"):
        np.testing.assert_array_equal(hist[name].values, full.dataset[name].values)
    assert (out / "restart.npz").is_file()
    # a restart file of another case is rejected, naming the differing quantity
    from wheelrail.errors import InputError
    with pytest.raises(InputError, match="mu = 0.2"):
        solve(case.replace(mu=0.3), progress=False, restart=mid)


def test_fe_seed000_case_file_cone_on_arc(tmp_path):
    """wheel = "cone", rail = "arc": seed 000's Hertzian set-up from a case file."""
    from wheelrail.cli.fe import case_from_toml
    from wheelrail.fe.model import contact_geometry

    f = tmp_path / "seed.toml"
    f.write_text(CASE.replace('"cylinder"', '"cone"').replace('"60E1"', '"arc"')
                 + "inclination = 0.09966865249116204\n")
    case, mode = case_from_toml(f)
    g = contact_geometry(case)
    assert mode == "indent" and abs(g["y_c"]) < 1e-6
    assert g["hertz"].a / g["hertz"].b == pytest.approx(1.334, abs=0.002)


PLASTIC = ROLL + """yield_stress = 1.725e8
hardening_saturation = 4.9e8
hardening_rate = 36.7
"""


def test_fe_plastic_roll_writes_fields_and_restarts_with_the_plastic_state(tmp_path):
    """An elasto-plastic [fe] case: fields.nc and the plastic-strain section are written, and
    a run continued from its restart file (which carries the plastic state) ends with the
    same forces and plastic strains."""
    import xarray as xr

    from wheelrail.cli.fe import case_from_toml
    from wheelrail.fe import J2Plastic, Voce

    f = tmp_path / "plastic.toml"
    f.write_text(PLASTIC)
    case, _ = case_from_toml(f)
    assert case.material == J2Plastic(2.1e11, 0.28, 1.725e8, hardening=Voce(4.9e8, 36.7))
    out = tmp_path / "out"
    assert main(["fe", str(f), "--out", str(out), "--restart-every", "400"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["equivalent_plastic_strain_max"] > 0
    assert summary["steady"]["Fx_scatter"] < 0.1
    for name in ("plastic_strain_section", "von_mises_surface", "plastic_strain_surface"):
        assert (out / f"{name}.png").read_bytes()[:4] == b"\x89PNG"
    fields = xr.open_dataset(out / "fields.nc")
    assert float(fields.rail_equivalent_plastic_strain.max()) == pytest.approx(
        summary["equivalent_plastic_strain_max"])
    assert "equivalent_plastic_strain" in __import__("meshio").read(out / "mesh.vtu").cell_data
    from wheelrail.fe import solve

    full = solve(case, progress=False, restart_file=tmp_path / "r_{step}.npz", restart_every=400)
    assert full.Fx == summary["Fx"]
    mid = sorted(tmp_path.glob("r_*.npz"), key=lambda p: int(p.stem[2:]))[0]
    out2 = tmp_path / "out2"
    assert main(["fe", str(f), "--out", str(out2), "--no-figures", "--restart", str(mid)]) == 0
    s2 = json.loads((out2 / "summary.json").read_text())
    assert s2["restarted_at_step"] == int(mid.stem[2:]) > 0
    assert s2["Fx"] == summary["Fx"]
    fields2 = xr.open_dataset(out2 / "fields.nc")
    np.testing.assert_array_equal(fields2.rail_equivalent_plastic_strain.values,
                                  fields.rail_equivalent_plastic_strain.values)


def test_fe_named_case_keys_old_names_warn_and_plastic_is_kept(tmp_path):
    """The named-case keys: ``toumi2016`` keeps the case's own material, so ``plastic = true``
    gives the J2 body of Toumi et al. (2016) (yield 489 MPa); the old key ``seed000`` still
    works with a DeprecationWarning; giving both names is an error naming them."""
    from wheelrail.cli.fe import case_from_toml
    from wheelrail.errors import CaseFileError

    f = tmp_path / "toumi.toml"
    f.write_text('[fe]\ntoumi2016 = "printed"\nplastic = true\n')
    case, _ = case_from_toml(f)
    assert case.Fn == pytest.approx(7500.0) and case.material.yield_stress == 489e6
    f.write_text('[fe]\ntoumi2016 = "printed"\n')
    assert not hasattr(case_from_toml(f)[0].material, "yield_stress")
    f.write_text('[fe]\nseed000 = "printed"\n')
    with pytest.warns(DeprecationWarning, match="'seed000' is deprecated, use 'toumi2016'"):
        case, _ = case_from_toml(f)
    assert case.Fn == pytest.approx(7500.0)
    f.write_text('[fe]\nseed004 = "reduced"\ntransition = "reduced"\n')
    with pytest.raises(CaseFileError, match="'transition' and its old name 'seed004'"):
        case_from_toml(f)


def test_fe_toumi2016_table3_case_file_and_bad_material(tmp_path, capsys):
    from wheelrail.cli.fe import case_from_toml
    from wheelrail.fe import toumi2016_load

    f = tmp_path / "seed.toml"
    f.write_text('[fe]\ntoumi2016 = "table3"\nmaterial = "r900a"\nmesh_size = 2e-3\n')
    case, _ = case_from_toml(f)
    assert case.Fn == pytest.approx(toumi2016_load()) and case.material.yield_stress == 489e6
    f.write_text('[fe]\ntoumi2016 = "printed"\nmaterial = "steel"\n')
    assert main(["fe", str(f)]) == 2
    assert "material must be 'r900a'" in capsys.readouterr().err
