"""``wheelrail compare``: table per wheel, sweep CSV and figure, bad method labels."""

import csv

from wheelrail.cli.main import main

CASE = """
[wheelset]
profile = "S1002"
[track]
profile = "60E1"
inclination = "1/40"
[motion]
speed = 20.0
omega = 43.43
[position]
y = {y}
vertical_load = 70000.0
[friction]
mu = 0.3
"""
PNG = b"\x89PNG\r\n\x1a\n"


def _write(tmp_path, y):
    p = tmp_path / "c.toml"
    p.write_text(CASE.format(y=y), encoding="utf-8")
    return str(p)


def test_registered():
    from wheelrail.cli.main import COMMANDS

    assert ("compare", "wheelrail.cli.compare") in COMMANDS


def test_single_position_table(tmp_path, capsys):
    case = _write(tmp_path, "0.003")
    assert main(["compare", case, "--side", "right",
                 "--methods", "hertz,kik-piotrowski,stripes,bem+exact"]) == 0
    out = capsys.readouterr().out
    for lab in ("hertz", "kik-piotrowski", "stripes", "bem+exact", "p_max MPa", "time ms"):
        assert lab in out
    assert "%" in out          # deviation from the reference


def test_patch_figure(tmp_path, capsys):
    case = _write(tmp_path, "0.0")
    out = tmp_path / "f"
    assert main(["compare", case, "--side", "right", "--patches", "--out", str(out),
                 "--methods", "kik-piotrowski,multi-hertz/sauvage"]) == 0
    assert (out / "compare_patches.png").read_bytes()[:8] == PNG


def test_sweep_csv_and_plot(tmp_path, capsys):
    case = _write(tmp_path, "0.0")
    out = tmp_path / "o"
    assert main(["compare", case, "--sweep", "--y", "-2", "2", "2", "--side", "left",
                 "--methods", "kik-piotrowski,linder", "--out", str(out)]) == 0
    rows = list(csv.DictReader(open(out / "compare.csv")))
    assert len(rows) == 4 and {r["method"] for r in rows} == {"kik-piotrowski", "linder"}
    assert all(r["status"] == "ok" and float(r["Fn"]) > 6e4 for r in rows)
    assert (out / "compare_sweep.png").read_bytes()[:8] == PNG


def test_unknown_method_label(tmp_path, capsys):
    case = _write(tmp_path, "0.0")
    assert main(["compare", case, "--methods", "kalker"]) == 2
    assert "'kalker'" in capsys.readouterr().err
