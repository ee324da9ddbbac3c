"""Damaged profile files: each is refused with one line naming the file and the likely cause.

Once, values in metres inside a millimetre file were read as a
0.07 mm wide profile (then a misleading gauge message), truncated MiniProf
files (50 of 147 declared points) and single spikes went undetected. Files are
generated here from the built-in 60E1 and S1002 profiles (no shared data needed).
"""

from __future__ import annotations

import numpy as np
import pytest
from _helpers import assert_clean_failure, run_cli

import wheelrail as wr
from wheelrail.errors import ProfileError


def _points(kind="rail", n=120):
    p = wr.profiles.load("60E1" if kind == "rail" else "S1002")
    y = np.linspace(p.y_min, p.y_max, n)
    return y * 1e3, np.asarray(p(y)) * 1e3  # mm, z up


def text(kind="rail", scale=1.0, spike=None, units="mm", n=120, rows=None):
    y, z = _points(kind, n)
    if spike is not None:
        z = z.copy()
        z[n // 2] += spike
    lines = [f"# kind: {kind}", f"# units: {units}"]
    lines += [f"{a * scale:.6f} {b * scale:.6f}" for a, b in zip(y, z)][:rows]
    return "\n".join(lines) + "\n"


def simpack(kind="rail", scale=1.0, spike=None, n=120):
    y, z = _points(kind, n)
    if spike is not None:
        z = z.copy()
        z[n // 2] += spike
    body = "\n".join(f"    {a * scale:.6f} {-b * scale:.6f}" for a, b in zip(y, z))
    return ("header.begin\n  version = 1\n  type = %d\nheader.end\nspline.begin\n"
            "  approx.smooth = 0.0\n  units.len.f = 1000.0\n  units.ang.f = 1.0\n"
            "  point.begin\n%s\n  point.end\nspline.end\n" % (1 if kind == "wheel" else 0, body))


def miniprof(scale=1.0, spike=None, n=147, declared=None, rows=None):
    y, z = _points("rail", n)
    if spike is not None:
        z = z.copy()
        z[n // 2] += spike
    data = [f"{-a * scale:.7E}\t{-b * scale:.7E}" for a, b in zip(y, z)][:rows]
    head = ["Filename=x.ban", "MPTypeNo=299", f"XYPoints={declared if declared is not None else n}",
            "ColumnDef=X,Y"]
    return "\n".join(head + data) + "\n"


# (file name, content, tokens the message must contain)
DAMAGED = [
    ("m_in_mm.txt", text(scale=1e-3), ["metres", "mm"]),
    ("m_in_mm_wheel.txt", text("wheel", scale=1e-3), ["metres"]),
    ("m_in_mm.prr", simpack(scale=1e-3), ["metres", "units.len.f"]),
    ("m_in_mm.prw", simpack("wheel", scale=1e-3), ["metres"]),
    ("m_in_mm.ban", miniprof(scale=1e-3), ["metres"]),
    ("truncated.ban", miniprof(rows=50), ["147", "50", "truncated"]),
    ("truncated_one.ban", miniprof(rows=146), ["147", "146", "truncated"]),
    ("extra_rows.ban", miniprof(declared=100), ["100", "147", "extra rows"]),
    ("bad_count.ban", miniprof(declared="many"), ["many"]),
    ("spike.txt", text(spike=50.0), ["spike", "50"]),
    ("spike_down.txt", text(spike=-30.0), ["spike", "below"]),
    ("spike.prr", simpack(spike=50.0), ["spike"]),
    ("spike_wheel.prw", simpack("wheel", spike=40.0), ["spike"]),
    ("spike.ban", miniprof(spike=50.0), ["spike"]),
    ("small_spike.txt", text(spike=3.0), ["spike", "3"]),
    ("empty.txt", "", ["empty.txt"]),
    ("only_header.txt", "# kind: rail\ny z\n", ["0 data row"]),
    ("one_column.txt", "# kind: rail\n" + "\n".join(str(i) for i in range(20)) + "\n", ["column"]),
    ("word.txt", text().replace("\n", "\nabc def\n", 1).replace("abc def\n", "", 0)[:0]
     + "# kind: rail\n1 2\n3 4\nfoo 5\n6 7\n8 9\n", ["foo", "line 4"]),
    ("nan.txt", "# kind: rail\n1 2\n3 nan\n5 6\n7 8\n9 10\n", ["nan", "not finite"]),
    ("inf.txt", "# kind: rail\n1 2\n3 inf\n5 6\n7 8\n9 10\n", ["inf"]),
    ("huge.txt", "# kind: rail\n1 2\n3 1e9\n5 6\n7 8\n9 10\n", ["1e9", "implausibly large"]),
    ("three_points.txt", "# kind: rail\n1 2\n3 4\n5 6\n", ["3 data row"]),
    ("same_y.txt", "# kind: rail\n" + "".join(f"0 {i}\n" for i in range(10)), ["same_y.txt"]),
    ("zigzag.txt", "# kind: rail\n" + "".join(f"{(i % 2) * 10 - i * 0.1} {i}\n" for i in range(40)),
     ["single-valued"]),
    ("ragged.txt", "# kind: rail\n1 2\n3 4 5\n6 7\n8 9\n", ["columns"]),
    ("no_kind.txt", "1 2\n3 4\n5 6\n7 8\n9 10\n", ["wheel or a rail"]),
    ("binary.prr", "\x00\x01\x02\x03" * 10, ["binary"]),
    ("keyword_after_data.ban", miniprof() + "Tilt=3\n", ["keyword", "Tilt"]),
    ("simpack_no_points.prr", simpack().replace(simpack().split("point.begin\n")[1].split(
        "  point.end")[0], ""), ["prr"]),
]


@pytest.mark.parametrize("name,content,tokens", DAMAGED, ids=[d[0] for d in DAMAGED])
def test_damaged_file_is_refused_with_cause(name, content, tokens, tmp_path):
    p = tmp_path / name
    p.write_text(content, encoding="latin-1")
    with pytest.raises(ProfileError) as exc:
        wr.profiles.read(p)
    msg = str(exc.value)
    assert "\n" not in msg and name in msg
    for t in tokens:
        assert t.lower() in msg.lower(), (t, msg)


@pytest.mark.parametrize("name,content,tokens", DAMAGED[:16], ids=[d[0] for d in DAMAGED[:16]])
def test_damaged_file_on_the_command_line(name, content, tokens, tmp_path, capsys):
    p = tmp_path / name
    p.write_text(content, encoding="latin-1")
    kind = "--wheel" if "wheel" in name or name.endswith(".prw") else "--rail"
    code, _, err = run_cli(["geometry", "--no-plots", "--points", "3", "--out", tmp_path / "o",
                            kind, p], capsys)
    assert_clean_failure(code, err, name, *tokens)
    assert not (tmp_path / "o" / "contact_table.csv").exists()


@pytest.mark.parametrize("make", [lambda: text(), lambda: simpack(), lambda: miniprof(),
                                  lambda: text("wheel"), lambda: simpack("wheel")],
                         ids=["text", "simpack", "miniprof", "text-wheel", "simpack-wheel"])
def test_undamaged_files_still_read(make, tmp_path):
    """The damage checks do not fire on intact files (a test that can fail the other way)."""
    content = make()
    ext = {"# k": ".txt", "heade": ".prr", "Filen": ".ban"}[content[:3] if content.startswith("# k")
                                                              else content[:5]]
    if "type = 1" in content:
        ext = ".prw"
    p = tmp_path / f"ok{ext}"
    p.write_text(content)
    prof = wr.profiles.read(p)
    assert prof.y_max - prof.y_min > 0.05


def test_flange_back_origin_gets_a_tape_circle_with_warning(tmp_path):
    """A wheel file with all y >= 0 (origin on the flange back) is moved to the tape circle."""
    y, z = _points("wheel")
    p = tmp_path / "flange_back.prw"
    content = simpack("wheel")
    body = "\n".join(f"    {a + 70.0:.6f} {-b:.6f}" for a, b in zip(y, z))
    content = content.split("point.begin\n")[0] + "point.begin\n" + body + "\n  point.end\nspline.end\n"
    p.write_text(content)
    with pytest.warns(wr.profiles.ProfileWarning, match="flange back"):
        prof = wr.profiles.read(p)
    ref = wr.profiles.load("S1002")
    s = np.linspace(-0.04, 0.04, 9)
    np.testing.assert_allclose(prof(s), ref(s), atol=1e-4)  # 120 samples; a wrong origin is mm off
