"""`wheelrail compile`: every kernel family's warm-up runs (in this process and in spawned
worker processes), a second run finds the kernels cached, bad families and job counts are
refused with one line."""

from __future__ import annotations

import pytest

from wheelrail.cli import compile as C
from wheelrail.cli.main import main


def test_transient_family_compiles_in_process_and_then_loads(capsys):
    assert main(["compile", "transient", "-j", "1"]) == 0
    out = capsys.readouterr().out
    assert "transient" in out and "done in" in out
    again = C.compile_families(["transient"], jobs=1)
    assert again[0]["family"] == "transient" and again[0]["cpu"] < 5.0


def test_families_run_in_separate_processes():
    import os

    res = C.compile_families(["transient", "transient"], jobs=2)
    assert len(res) == 2
    assert {r["family"] for r in res} == {"transient"}
    assert all(r["pid"] != os.getpid() for r in res)


@pytest.mark.parametrize("argv, words", [
    (["compile", "kernels"], ("unknown kernel family 'kernels'", "fe, dynamics")),
    (["compile", "transient", "--jobs", "0"], ("--jobs must be >= 1",)),
])
def test_bad_arguments_are_refused_with_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(w in err for w in words)
