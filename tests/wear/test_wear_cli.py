"""``wheelrail wear CASE.toml``: the example case end to end, resume, estimate, bad keys.

The example (docs/examples/wear_route.toml: a bogie on a 300 m curve, 80 % of
50 km, and tangent track) must wear the outer (left, the curve turns right)
wheels' flange: Sd falls on the left side and not on the right — the known
behaviour of curving wear (Jendel, Wear 253 (2002) 89–99; Braghin et al.,
Wear 261 (2006) 1253–1264).
"""

from pathlib import Path

import pytest
import xarray as xr

from wheelrail.cli.main import main
from wheelrail.cli.wear import read_wear_case
from wheelrail.errors import CaseFileError

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "wear_route.toml"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("wear") / "out"
    code = main(["wear", str(EXAMPLE), "--out", str(out)])
    return code, out


def test_example_runs_and_writes_outputs(run, capsys):
    code, out = run
    assert code == 0
    for name in ("wear.nc", "summary.json", "profiles.png", "dimensions.png",
                 "checkpoint/state.json"):
        assert (out / name).is_file(), name
    ds = xr.open_dataset(out / "wear.nc")
    assert ds.sizes["step"] >= 3
    assert float(ds.mileage[-1]) == pytest.approx(50e3)
    sd = ds.Sd.sel(side="left").values
    assert sd[-1] < sd[0] - 10e-6                      # the outer flange thins (> 10 µm)
    right = ds.Sd.sel(side="right").values
    assert sd[0] - sd[-1] > 5 * abs(right[0] - right[-1])   # the inner one much less
    ds.close()


def test_rerun_resumes_from_the_checkpoint(run, capsys):
    code, out = run
    capsys.readouterr()
    assert main(["wear", str(EXAMPLE), "--out", str(out), "--no-figures"]) == 0
    text = capsys.readouterr().out
    assert "step 0:" not in text                       # nothing recomputed
    assert "50 km" in text


def test_estimate_only_computes_nothing(tmp_path, capsys):
    out = tmp_path / "est"
    assert main(["wear", str(EXAMPLE), "--out", str(out), "--estimate-only"]) == 0
    assert "estimate: wear step of 2 case(s)" in capsys.readouterr().out
    assert not out.exists()


def _case(extra_route="", extra_wear="", top="", replace=("", "")):
    text = EXAMPLE.read_text().replace(*replace)
    text = text.replace('name = "R300"', 'name = "R300"\n' + extra_route)
    text = text.replace('law = "usfd"', 'law = "usfd"\n' + extra_wear)
    return top + text


@pytest.mark.parametrize("kw, where", [
    ({"extra_wear": "stepdepth = 1e-4"}, "[wear]: unknown key(s) 'stepdepth'"),
    ({"extra_route": "radious = 300.0"}, "[route.cases[0]]: unknown key(s) 'radious'"),
    ({"extra_wear": "mileage_km = 3"}, "'mileage_km'"),
    ({"top": "[vehicle]\nkind = 'bogie'\n"}, "top level: unknown table(s) 'vehicle'"),
    ({"extra_wear": "options = {rule = 'nope'}"}, "[wear.options] rule"),
    ({"replace": ('profiles = "sides"', 'profiles = "both"')}, "[wear] profiles"),
])
def test_bad_keys_are_refused_naming_table_and_key(kw, where):
    with pytest.raises(CaseFileError) as exc:
        read_wear_case(_case(**kw))
    assert where in str(exc.value)


def test_curve_keys_need_a_radius():
    text = _case().replace('radius = 300.0', '')
    with pytest.raises(CaseFileError, match=r"\[route.cases\[0\]\] cant: belongs to a curve"):
        read_wear_case(text)


def test_bad_key_exit_code_and_message(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(_case(extra_wear="smoothing_window = 1e-3"))
    assert main(["wear", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "[wear]" in err and "smoothing_window" in err


def test_rail_update_keys():
    kw = read_wear_case(_case(extra_wear="update_rail = true\nrail_passages = 0.5"))["evolve"]
    assert kw["update_rail"] is True and kw["rail_passages"] == 0.5
    with pytest.raises(CaseFileError, match=r"\[wear\] rail_passages: missing"):
        read_wear_case(_case(extra_wear="update_rail = true"))
    with pytest.raises(CaseFileError, match=r"\[wear\] rail_passages: needs update_rail"):
        read_wear_case(_case(extra_wear="rail_passages = 0.5"))
