"""Every long job estimated before it starts.

The campaign: a sweep with ``num = 1000000000`` sat 90 s and failed with
``MemoryError: Unable to allocate 7.45 GiB``; a sweep of 1e6 exact points
(about 11 h) and a transient run with ``travel = 1000`` (5e6 steps) started
without a word; ``element_size = 1e-8`` went around the BEM memory guard to a
4.18 TiB MemoryError. Here each is refused at once with the estimate, the
limit and how to raise it, and ``--estimate-only`` prints the estimate without
computing or writing anything.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from _helpers import POINT_CASE, assert_clean_failure, run_cli

from wheelrail import _resources

SWEEP = """
[sweep]
method = "{method}"
mu = 0.3
Fn = 10000.0
A = 1.087
B = 1.667
xi = {{start = -0.003, stop = 0.003, num = {num}}}
{extra}
"""

TRANSIENT = Path(__file__).parents[2] / "docs" / "examples" / "transient_cattaneo_carter.toml"

BEM = POINT_CASE + '[method]\nnormal = "bem"\n[method.bem]\nelement_size = {size}\n'


def _sweep(tmp_path, method="fastsim", num=5, extra=""):
    p = tmp_path / "s.toml"
    p.write_text(SWEEP.format(method=method, num=num, extra=extra))
    return p


def test_billion_point_axis_refused_at_once(tmp_path, capsys):
    case = _sweep(tmp_path, num=1_000_000_000)
    t0 = time.process_time()
    code, _, err = run_cli(["sweep", case, "--out", tmp_path / "o.zarr"], capsys)
    assert_clean_failure(code, err, "s.toml", "xi", "1000000000")
    assert time.process_time() - t0 < 30  # not a timing claim: it must not allocate 8 GB
    assert not (tmp_path / "o.zarr").exists()


def test_hours_of_exact_points_refused_with_estimate(tmp_path, capsys):
    # 1e6 exact points cost 0.5-3 ms each on the 2-core machine (17 min - 1 h depending on the
    # load): against the 1 h default limit the outcome would depend on the load, so the limit
    # is 1 min here; no 10-element exact point takes under 0.06 ms, so 1e6 of them cannot fit
    case = _sweep(tmp_path, method="exact", num=1_000_000, extra="[sweep.options]\nelements = 10")
    code, _, err = run_cli(["--time-limit", "1min", "sweep", case, "--out", tmp_path / "o.zarr"],
                           capsys)
    assert_clean_failure(code, err, "1000000 points", "exact", "time limit", "--time-limit",
                         "WHEELRAIL_TIME_LIMIT")
    assert not (tmp_path / "o.zarr").exists()


def test_time_limit_override_by_flag_and_environment(tmp_path, capsys, monkeypatch):
    case = _sweep(tmp_path, method="exact", num=1_000_000, extra="[sweep.options]\nelements = 10")
    code, out, err = run_cli(["--time-limit", "off", "sweep", case, "--out",
                              tmp_path / "o.zarr", "--estimate-only"], capsys)
    assert code == 0 and "estimate: sweep of 1000000 points" in out, err
    monkeypatch.setenv("WHEELRAIL_TIME_LIMIT", "1000h")
    code, out, err = run_cli(["sweep", case, "--out", tmp_path / "o.zarr", "--estimate-only"],
                             capsys)
    assert code == 0 and "ms per point measured" in out, err
    assert not (tmp_path / "o.zarr").exists()


def test_sweep_estimate_only_writes_nothing(tmp_path, capsys):
    case = _sweep(tmp_path, num=50)
    code, out, err = run_cli(["sweep", case, "--out", tmp_path / "o.zarr", "--estimate-only"],
                             capsys)
    assert code == 0, err
    assert "estimate: sweep of 50 points (creep/fastsim)" in out
    assert list(tmp_path.iterdir()) == [case]


@pytest.mark.parametrize("text,value", [("90s", 90.0), ("30min", 1800.0), ("3h", 10800.0),
                                        ("3600", 3600.0), ("off", None)])
def test_parse_duration(text, value):
    assert _resources.parse_duration(text) == value


@pytest.mark.parametrize("text", ["soon", "-1h", "0", "nan"])
def test_bad_time_limit_names_the_value(text, tmp_path, capsys):
    code, _, err = run_cli([f"--time-limit={text}", "sweep", _sweep(tmp_path), "--out",
                            tmp_path / "o.zarr"], capsys)
    assert_clean_failure(code, err, text)


def _transient(tmp_path, **changes):
    text = TRANSIENT.read_text()
    for key, value in changes.items():
        lines = [f"{key} = {value}" if ln.split("=")[0].strip() == key else ln
                 for ln in text.splitlines()]
        text = "\n".join(lines) + "\n"
    p = tmp_path / "t.toml"
    p.write_text(text)
    return p


def test_transient_of_days_refused_before_it_starts(tmp_path, capsys):
    case = _transient(tmp_path, travel=1000)
    code, _, err = run_cli(["transient", case, "--out", tmp_path / "o"], capsys)
    assert_clean_failure(code, err, "20000000 steps", "time limit", "--time-limit")
    assert not (tmp_path / "o").exists()


def test_transient_of_5000_elements_refused_by_memory(tmp_path, capsys):
    case = _transient(tmp_path, elements=5000)
    code, _, err = run_cli(["transient", case, "--out", tmp_path / "o"], capsys)
    assert_clean_failure(code, err, "grid cells", "memory limit")


def test_transient_estimate_only(tmp_path, capsys):
    code, out, err = run_cli(["transient", _transient(tmp_path), "--out", tmp_path / "o",
                              "--estimate-only"], capsys)
    assert code == 0, err
    assert "estimate: transient run of 1800 steps on about 1521 grid cells" in out
    assert not (tmp_path / "o").exists()


def test_tiny_element_size_meets_the_bem_guard(tmp_path, capsys):
    p = tmp_path / "bem.toml"
    p.write_text(BEM.format(size="1e-8"))
    code, _, err = run_cli(["solve", p], capsys)
    assert_clean_failure(code, err, "element_size = 1e-08", "memory limit", "--memory-limit")
    assert "MemoryError" not in err[-1]


def test_bem_estimate_only_writes_no_json(tmp_path, capsys):
    p = tmp_path / "bem.toml"
    p.write_text(BEM.format(size="2e-4"))
    code, out, err = run_cli(["solve", p, "--json", tmp_path / "r.json", "--estimate-only"],
                             capsys)
    assert code == 0, err
    assert "estimate: normal BEM with element_size = 0.0002 m" in out
    assert not (tmp_path / "r.json").exists()


def test_estimate_only_measures_real_solves_not_failures(tmp_path, monkeypatch):
    """Under --estimate-only the exact solver's own guard must not turn the measured points
    into quick failures (which made the estimate of an exact sweep 15 x too small)."""
    from wheelrail.sweeps import evaluators, load_sweep
    from wheelrail.sweeps.estimate import estimate_sweep

    spec = load_sweep(_sweep(tmp_path, method="exact", num=4,
                             extra="[sweep.options]\nelements = 8"))
    ev = evaluators.get_evaluator(spec.evaluator)
    statuses = []
    real = type(ev).evaluate

    def recording(self, spec, cols):
        out = real(self, spec, cols)
        statuses.extend(int(s) for s in out["status"])
        return out

    monkeypatch.setattr(type(ev), "evaluate", recording)
    with _resources.estimating():
        est = estimate_sweep(spec)
    assert statuses and set(statuses) == {evaluators.STATUS_CODES["ok"]}, statuses
    assert est.points == 4


def test_estimate_only_propagates_through_catch_all_handlers():
    with _resources.estimating():
        with pytest.raises(_resources.EstimateOnly):
            try:
                _resources.check("job", 10.0, 1e6)
            except Exception:  # noqa: BLE001 - what a per-point handler does
                pytest.fail("EstimateOnly was caught as an Exception")
