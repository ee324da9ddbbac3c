"""The README's Python and TOML snippets run as written (they are the first thing users copy)."""

import re
from pathlib import Path

import numpy as np
import pytest

import wheelrail as wr

README = Path(__file__).resolve().parents[2] / "README.md"


def _blocks(lang):
    return re.findall(rf"```{lang}\n(.*?)```", README.read_text(encoding="utf-8"), re.S)


def test_readme_python_snippet_runs_and_gives_consistent_numbers():
    ns: dict = {}
    exec(compile(_blocks("python")[0], "README.md", "exec"), ns)  # noqa: S102 - our own README
    c, r, R, x, tab = ns["c"], ns["r"], ns["R"], ns["x"], ns["tab"]
    assert c.a == pytest.approx(3.033e-3, rel=1e-3)
    assert r.Fx > 0 and r.Fy < 0          # braking wheel (xi < 0), eta > 0 dominates
    assert R.Fx.shape == (100_000,)
    assert np.all(np.hypot(R.Fx, R.Fy) <= 0.3 * 7500.0 * (1 + 1e-12))
    assert x.Fx > 0
    assert tab.sizes["y"] == 201


def test_readme_case_file_solves(tmp_path):
    case = wr.load_case(_blocks("toml")[0])
    out = wr.run_case(case)
    assert out["method"] == "fastsim" and out["Fx"] > 0
    for key in ("a", "b", "p0", "penetration", "Fn", "Fx", "Fy", "Mz"):
        assert key in out
