"""Resource guards: estimates, refusal past the memory limit, progress for long solves.

An audit found an exact solve with 1000 elements running 168 s at 2.7 GB printing
nothing; a BEM normal solve with 3000 elements passed 8 GB. The estimates are
checked against those audit figures (within a factor of 2) and against
``benchmarks/bench_resources.py``.
"""

from __future__ import annotations

import pytest

import wheelrail as wr
from wheelrail import _resources as res


def test_estimates_match_the_audit_figures():
    # exact theory, 1000 elements: margin 1.1 -> 1101^2 cells; audit: 2.7 GB
    e = res.estimate("exact", 1101**2)
    assert 1.35e9 < e.memory < 5.4e9
    # 600 elements (661^2 cells): 18.5 s CPU, 1.15 GB peak measured by
    # benchmarks/bench_resources.py (2-core machine, load 13); within a factor 2
    e = res.estimate("exact", 661**2)
    assert 9.2 < e.seconds < 37 and 0.57e9 < e.memory < 2.3e9
    # normal BEM, 3000 elements: margin 1.25 -> 3751^2 cells; audit: > 8 GB
    assert res.estimate("bem_normal", 3751**2).memory > 8e9


@pytest.mark.parametrize("text,value", [("8GB", 8e9), ("500MB", 5e8), ("2e9", 2e9),
                                        ("1GiB", 2**30), ("off", None), ("none", None)])
def test_parse_size(text, value):
    assert res.parse_size(text) == value


@pytest.mark.parametrize("text", ["0", "-1GB", "lots", "nan", "inf GB", ""])
def test_parse_size_refuses(text):
    with pytest.raises(wr.errors.InputError, match="memory limit"):
        res.parse_size(text)


def test_guard_refuses_before_allocating_and_can_be_overridden():
    hc = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.STEEL)
    grid, gap = wr.hertz_grid(hc, 40)
    with res.limit("50MB"):
        with pytest.raises(res.ResourceLimitError, match=r"51x51 grid: 2601 grid cells: about 152 MB"):
            wr.solve_normal(grid, gap, wr.STEEL, Fn=7500.0)
    with res.limit(None):
        assert wr.solve_normal(grid, gap, wr.STEEL, Fn=7500.0).Fn == pytest.approx(7500.0)


def test_environment_variable(monkeypatch):
    monkeypatch.setenv("WHEELRAIL_MEMORY_LIMIT", "1MB")
    assert res.memory_limit() == 1e6
    monkeypatch.setenv("WHEELRAIL_MEMORY_LIMIT", "off")
    assert res.memory_limit() is None
    monkeypatch.delenv("WHEELRAIL_MEMORY_LIMIT")
    assert 0 < res.memory_limit() <= 4 * 2**30


class _FakeStatus:
    def __init__(self, log, text):
        self.log = log
        log.append(("start", text))

    def start(self):
        pass

    def update(self, text):
        self.log.append(("update", text))

    def stop(self):
        self.log.append(("stop", None))


class _FakeConsole:
    is_terminal = True

    def __init__(self):
        self.log = []

    def status(self, text):
        return _FakeStatus(self.log, text)


def test_long_solves_show_progress_short_ones_do_not():
    con = _FakeConsole()
    with res.reporting(con):
        res.guard("exact", 100, "small")          # ~0.1 s: nothing shown
        assert con.log == []
        res.guard("exact", 200_000, "big one")    # ~40 s: spinner with the estimate
    assert con.log[0][0] == "start" and "big one" in con.log[0][1] and " s" in con.log[0][1]
    assert con.log[-1] == ("stop", None)
