"""``compare`` keeps every case setting and fits 80 columns.

The campaign: ``compare --sweep --y …`` dropped the case's yaw (Fs = −69 N at
y = 5 mm where ``wheelrail wheelset`` gives 2734 N); the time column charged
the start-up to the first method (Hertz 552 ms against 2 ms); at 80 columns
the method names were cut to ``multi…`` and ``kik-p…``.
"""

from __future__ import annotations

import csv
from types import SimpleNamespace

import numpy as np
from _helpers import run_cli, wheelset_case
from rich.console import Console

from wheelrail.cli import compare



def test_sweep_over_y_keeps_the_case_yaw(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_text(wheelset_case(y="0.005", position="yaw = 0.004"))
    code, out, err = run_cli(["compare", p, "--sweep", "--y", "5", "5", "1", "--methods", "hertz",
                              "--out", tmp_path / "o", "--no-plots", "--side", "right"], capsys)
    assert code == 0, err
    rows = list(csv.DictReader(open(tmp_path / "o" / "compare.csv")))
    assert float(rows[0]["yaw"]) == 0.004
    # the same position solved directly (what `wheelrail wheelset` does)
    from wheelrail.cases.files import load_wheelset_case

    case = load_wheelset_case(p)
    direct = compare.run_methods(case.position(0), case.motion, case.mu,
                                 compare._select("hertz"), ("right",))
    assert float(rows[0]["Fs"]) == direct["hertz"]["right"]["Fs"]


def test_yaw_at_constant_proportional_and_list():
    ys = np.array([0.0, 0.002, 0.006])
    const = SimpleNamespace(y=np.array([0.005]), yaw=np.array([0.003]))
    assert np.all(compare.yaw_at(const, ys) == 0.003)
    prop = SimpleNamespace(y=np.array([-0.004, 0.0, 0.004]), yaw=np.array([-0.0012, 0.0, 0.0012]))
    np.testing.assert_allclose(compare.yaw_at(prop, ys), 0.3 * ys)
    lst = SimpleNamespace(y=np.array([0.0, 0.01]), yaw=np.array([0.001, 0.002]))
    np.testing.assert_allclose(compare.yaw_at(lst, np.array([0.005])), [0.0015])


def test_first_call_is_timed_again_without_start_up(monkeypatch):
    """Structural, not a timing claim: a cheap method is solved twice the first time."""
    import wheelrail.api as api

    calls = []
    monkeypatch.setattr(api, "solve", lambda *a, **k: calls.append(k["normal"]) or
                        SimpleNamespace(side=lambda s: []))
    monkeypatch.setattr(compare, "_TIMED", set())
    methods = compare._select("hertz,linder")
    compare.run_methods(None, None, 0.3, methods, ("left",))
    assert calls == ["hertz", "hertz", "linder", "linder"]
    compare.run_methods(None, None, 0.3, methods, ("left",))
    assert calls[4:] == ["hertz", "linder"]


def _result():
    q = {"patches": 1, "Fn": 10450.0, "area": 1.2e-5, "p_max": 1.6e9, "Fx": 2890.0, "Fs": 1110.0,
         "Mz": 0.86, "time": 0.0045}
    return {label: {"right": dict(q)} for label, *_ in compare.METHODS}


def test_table_fits_80_columns_with_full_method_names():
    con = Console(width=80, record=True)
    compare.print_tables(con, _result(), "right", "wheelrail compare c.toml: y = 5 mm, right")
    text = con.export_text()
    assert max(len(ln) for ln in text.splitlines()) <= 80
    for label, *_ in compare.METHODS:
        assert label in text
    assert "…" not in text


def test_validate_table_at_80_columns_is_not_one_word_per_line(tmp_path, monkeypatch, capsys):
    from wheelrail.cli import main as cli_main

    con = Console(width=80, record=True, highlight=False)
    monkeypatch.setattr(cli_main, "make_console", lambda: con)
    assert cli_main.main(["validate", "--quick", "--only", "hertz-table2", "--out",
                          str(tmp_path)]) == 0
    text = con.export_text()
    lines = text.splitlines()
    assert max(len(ln) for ln in lines) <= 80
    table = [ln for ln in lines if "hertz" in ln.lower()]
    assert len(table) >= 3  # each of the 3 rows starts on a line naming its method
    body = [ln for ln in lines if ln.strip() and not ln.startswith(("report:", "3 rows"))]
    assert len(body) <= 3 * 3 + 8, text  # not one word per line


def test_a_label_given_twice_is_one_method():
    """``--methods hertz,hertz`` compares Hertz with nothing: warned like one label."""
    import pytest

    with pytest.warns(UserWarning, match="one method compares with nothing"):
        methods = compare._select("hertz, hertz")
    assert [m[0] for m in methods] == ["hertz"]
    assert [m[0] for m in compare._select("linder,hertz,linder")] == ["linder", "hertz"]
