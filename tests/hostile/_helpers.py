"""Shared checks and cases of the hostile-input suite: one-line errors, no tracebacks, no debris."""

from __future__ import annotations

import json
from pathlib import Path

from wheelrail.cli.main import main

#: A point contact (7.5 kN, wheel 0.46 m on a 0.30 m rail head, ξ = −1e-3, μ = 0.3).
POINT_CASE = """[contact]
Fn = 7500.0
wheel_rolling_radius = 0.46
rail_profile_radius = 0.30
[creepage]
xi = -0.001
[friction]
mu = 0.3
"""
#: The point contact solved with a small FASTSIM grid.
SOLVE_CASE = POINT_CASE + "[method.fastsim]\nnx = 8\nny = 8\n"

#: A small sweep: linear theory (Kalker 1967) at 4 × 2 creepages, stored in chunks of 2 rows.
SWEEP_CASE = """
[sweep]
method = "linear"
mu = 0.3
Fn = 10000.0
A = 1.087
B = 1.667
xi = {start = -0.003, stop = 0.003, num = 4}
eta = [0.0, 0.001]
chunk = 2
"""


def sweep_case(directory, text=SWEEP_CASE) -> Path:
    """Write the sweep case ``text`` (default :data:`SWEEP_CASE`) to ``directory/s.toml``."""
    path = Path(directory) / "s.toml"
    path.write_text(text)
    return path


def wheelset_case(speed="20.0", y="0.002", motion="", position="") -> str:
    """A wheelset case (S1002 on 60E1, 10 kN, μ = 0.3); ``motion``, ``position``: extra
    lines of those tables."""
    return (f'[wheelset]\nprofile = "S1002"\n[track]\nprofile = "60E1"\n[motion]\n'
            f"speed = {speed}\n{motion}\n[position]\ny = {y}\n{position}\n"
            f"vertical_load = 10e3\n[friction]\nmu = 0.3\n")


def run_cli(argv, capsys):
    """Run ``wheelrail argv`` in-process; returns (exit code, stdout, stderr lines)."""
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, [ln for ln in err.splitlines() if ln.strip()]


def assert_clean_failure(code, err, *must_name):
    """Non-zero exit, exactly one error line naming every string in ``must_name``, no traceback.

    Warning lines (``wheelrail: warning: ...``) may precede the error line.
    """
    assert code in (1, 2), (code, err)
    text = "\n".join(err)
    assert "Traceback" not in text
    errors = [ln for ln in err if ln.startswith("wheelrail: error: ")]
    others = [ln for ln in err if not ln.startswith(("wheelrail: error: ", "wheelrail: warning: "))]
    assert len(errors) == 1 and not others, err
    assert "np.float64" not in errors[0]
    for token in must_name:
        assert token.lower() in errors[0].lower(), (token, errors[0])


def assert_clean_warnings(err):
    """Every stderr line is a one-line ``wheelrail: warning:`` (no source lines, no tracebacks)."""
    for ln in err:
        assert ln.startswith("wheelrail: warning: "), ln


def assert_no_debris(directory: Path):
    """No temporary files left and every JSON file in ``directory`` parses."""
    directory = Path(directory)
    if not directory.exists():
        return
    for p in directory.rglob("*"):
        assert ".tmp" not in p.name, f"temporary file left behind: {p}"
        if p.suffix == ".json":
            json.loads(p.read_text())
        if p.is_file():
            assert p.stat().st_size > 0, f"empty output file {p}"
