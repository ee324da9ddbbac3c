"""The numbers and outputs the documentation quotes are what the commands print.

Doctest-style: every ```console block preceded by a ``<!-- checked: ... -->``
marker in README.md or docs/*.md is run — each ``$ wheelrail ...`` line as a
command in a temporary directory — and every output line written under it in
the page must appear, in order, in what the command prints (stdout and stderr;
run times ``(0.4 s)``, the output directory and trailing ``# comments`` are
normalised away). Numbers quoted in prose next to such a block are checked
below against the files the commands write, and the measured-signs table of
conventions.md §5 against the API call that produces it.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
MARKER = "<!-- checked:"
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))


def _blocks():
    """(page, [(command, [expected lines])]) of every checked console block."""
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for m in re.finditer(re.escape(MARKER) + r".*?-->\n```console\n(.*?)```", text, re.S):
            cmds = []
            for line in m.group(1).splitlines():
                if line.startswith("$ "):
                    cmds.append((line[2:].split("  #")[0].split(" # ")[0].strip(), []))
                elif cmds and line.strip():
                    cmds[-1][1].append(line)
            out.append((page.relative_to(ROOT).as_posix(), cmds))
    return out


BLOCKS = _blocks()


def _normalise(line):
    line = line.split("   #")[0]  # "# exit 2" annotations
    line = re.sub(r"\(\d+(\.\d+)? s\)", "(… s)", line)
    line = re.sub(r"→ \S*/", "→ /…/", line)
    return " ".join(line.split())


def _run(command, cwd):
    argv = command.split()
    assert argv[0] == "wheelrail", command
    env = dict(os.environ, COLUMNS="80", NO_COLOR="1", TERM="dumb")
    res = subprocess.run([sys.executable, "-m", "wheelrail.cli.main"] + argv[1:],
                         capture_output=True, text=True, cwd=cwd, env=env, timeout=600)
    return res.stdout + res.stderr


def test_there_are_checked_blocks():
    pages = {p for p, _ in BLOCKS}
    assert "docs/cli.md" in pages
    assert sum(len(c) for _, c in BLOCKS) >= 6


@pytest.mark.parametrize("page, cmds", BLOCKS, ids=[f"{p}#{i}" for i, (p, _) in
                                                     enumerate(BLOCKS)])
def test_console_block_matches_the_command(page, cmds, tmp_path):
    (tmp_path / "bad.toml").write_text("[contact]\nFn = -1\n")
    for command, expected in cmds:
        got = [_normalise(x) for x in _run(command, tmp_path).splitlines()]
        pos = 0
        for line in expected:
            want = _normalise(line)
            try:
                pos = got.index(want, pos) + 1
            except ValueError:
                pytest.fail(f"{page}: `{command}` did not print\n  {want!r}\ngot:\n"
                            + "\n".join(got))
        if command.startswith("wheelrail creep-curve --component phi"):
            _check_phi_numbers(page, tmp_path / "phi.csv")


def _check_phi_numbers(page, csv):
    """cli.md quotes exact_Fy and fastsim_Fy at φ = 2 1/m from phi.csv (1 decimal)."""
    text = (ROOT / page).read_text(encoding="utf-8")
    quoted = dict(re.findall(r"`(exact_Fy|fastsim_Fy) = (-?\d+\.\d)`", text))
    data = np.genfromtxt(csv, delimiter=",", names=True)
    last = data[np.argmax(data["phi"])]
    assert set(quoted) == {"exact_Fy", "fastsim_Fy"}
    for k, v in quoted.items():
        assert f"{last[k]:.1f}" == v, (k, last[k], v)


def test_conventions_measured_signs_table():
    """conventions.md §5: the linear theory's Fx, Fy, Mz on the default case (§10) and the
    exact theory's Fy, Mz quoted beside them are what the API gives now."""
    import wheelrail as wr

    text = (ROOT / "docs" / "conventions.md").read_text(encoding="utf-8")
    sec = text[text.index("- **Measured signs**"):text.index("- **Per-method notes:**")]
    rows = re.findall(r"\| ([ξηφ]) = ([^|]*?) (?:\(driving\) |1/m )?\| ([^|]+) \| ([^|]+) \| "
                      r"([^|]+) \|", sec)
    assert len(rows) == 3
    hc = wr.hertz(7500.0, A=0.5 / 0.46, B=0.5 / 0.30, material=wr.Material(210e9, 0.28))
    for sym, val, fx, fy, mz in rows:
        v = float(val.replace("−", "-").replace("e−", "e-"))
        cr = {"ξ": (v, 0, 0), "η": (0, v, 0), "φ": (0, 0, v)}[sym]
        r = wr.creep_forces(hc, cr, mu=0.3, method="linear")
        for q, got in (("Fx", r.Fx), ("Fy", r.Fy)):
            want = float({"Fx": fx, "Fy": fy}[q].replace("−", "-").replace("+", ""))
            assert round(got) == want or (want == 0 and abs(got) < 0.5), (sym, q, got, want)
        want_mz = float(mz.replace("−", "-").replace("+", ""))
        assert round(r.Mz, 2) == want_mz or (want_mz == 0 and abs(r.Mz) < 0.005), (sym, r.Mz)
    exact = re.findall(r"Fy = (−?\d+) N and Mz = ([+−]?\d+\.\d+) N·m for (η|φ) = "
                       r"\+?(\d[\d.e−]*\d)", " ".join(sec.split()))
    assert len(exact) == 2
    for fy, mz, sym, val in exact:
        v = float(val.replace("−", "-"))
        cr = (0, v, 0) if sym == "η" else (0, 0, v)
        r = wr.creep_forces(hc, cr, mu=0.3, method="exact")
        assert round(r.Fy) == float(fy.replace("−", "-")), (sym, r.Fy, fy)
        assert round(r.Mz, 2) == float(mz.replace("−", "-").replace("+", "")), (sym, r.Mz, mz)
