"""Fuzzed and corrupted profile files: the readers return a Profile or raise ProfileError,
never an uncaught numpy/ValueError/IndexError/... traceback."""

import tempfile
import warnings
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import wheelrail as wr
from wheelrail.errors import ProfileError
from wheelrail.profiles import Profile

_Y = np.linspace(-30, 30, 13)
_Z = 0.05 * np.abs(_Y) ** 1.5

SIMPACK = ("! test\nheader.begin\n  version = 1\n  type = 0\nheader.end\nspline.begin\n"
           "  comment = 'fuzz base'\n  units.len.f = 1000.\n  mirror.y = 0\n  point.begin\n"
           + "".join(f"    {y:.4f}  {z:.4f}\n" for y, z in zip(_Y, _Z))
           + "  point.end\nspline.end\n")
MINIPROF = ("Filename=x\nXYPoints=13\nColumnDef=X,Y\n\n"
            + "".join(f"{y:.4f} {-z:.4f}\n" for y, z in zip(_Y, _Z)))
MINIPROF_OLD = ("MINIPROF 101 148\nname\n32.5 28.0 10.8 (Sd/Sh/qR)\n\n"
                + "".join(f"{y + 30:.3f} {z - 0.5:.3f} 0.000\n" for y, z in zip(_Y * 2, _Z)))
CSV = "# kind: rail\n# units: mm\ny,z\n" + "".join(f"{y:.4f},{-z:.4f}\n" for y, z in zip(_Y, _Z))
BASES = [(SIMPACK, ".prr"), (MINIPROF, ".ban"), (MINIPROF_OLD, ".whl"), (CSV, ".csv")]

FUZZ = settings(max_examples=60, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def _check(text_or_bytes, ext, kind=None):
    with tempfile.TemporaryDirectory() as d:
        f = Path(d) / f"fuzz{ext}"
        if isinstance(text_or_bytes, bytes):
            f.write_bytes(text_or_bytes)
        else:
            f.write_text(text_or_bytes, encoding="utf-8", errors="surrogatepass")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                p = wr.profiles.read(f, kind=kind)
            except ProfileError as exc:
                assert str(exc)
                return None
        assert isinstance(p, Profile)
        assert np.all(np.isfinite(p.y)) and np.all(np.isfinite(p.z))
        assert np.all(np.diff(p.y) > 0)
        return p


def test_bases_are_valid():
    for text, ext in BASES:
        assert _check(text, ext) is not None


_edit = st.tuples(st.sampled_from(["replace", "delete", "insert", "dupline", "dropline", "trunc"]),
                  st.floats(0, 1), st.text(min_size=1, max_size=6))


@FUZZ
@given(base=st.sampled_from(range(len(BASES))), edits=st.lists(_edit, min_size=1, max_size=6))
def test_corrupted_files(base, edits):
    text, ext = BASES[base]
    for op, where, junk in edits:
        i = int(where * len(text))
        lines = text.split("\n")
        j = min(int(where * len(lines)), len(lines) - 1)
        if op == "replace":
            text = text[:i] + junk + text[i + len(junk):]
        elif op == "delete":
            text = text[:i] + text[i + len(junk):]
        elif op == "insert":
            text = text[:i] + junk + text[i:]
        elif op == "dupline":
            text = "\n".join(lines[:j] + [lines[j]] * 3 + lines[j + 1:])
        elif op == "dropline":
            text = "\n".join(lines[:j] + lines[j + 1:])
        else:
            text = text[:i]
    _check(text, ext, kind=None)


_token = st.sampled_from([
    "header.begin", "header.end", "spline.begin", "spline.end", "point.begin", "point.end",
    "type = 1", "units.len.f = 1000", "units.len.f = 0", "rotate = 1e308", "mirror.y = 2",
    "ColumnDef=X,Y", "ColumnDef=Y", "MINIPROF", "# kind: wheel", "# units: km", "y,z", "nan",
    "inf", "-1e400", "1e-320", "1,5;2,5", "\"", "!", "%", "=", ",", ";", "\t", " ", "\n", "\n\n",
    "0 0", "1 1", "2 4", "3 9", "4 16", "5 25", "1e6 1e6", "-0.0 0.0", "0x10 2", "1_0 3",
    "__import__('os')", "'quoted ! text'",
])


@FUZZ
@given(tokens=st.lists(_token, max_size=80),
       ext=st.sampled_from([".prr", ".prw", ".ban", ".whl", ".csv", ".txt", ""]),
       kind=st.sampled_from([None, "rail", "wheel"]))
def test_random_token_files(tokens, ext, kind):
    _check(" ".join(tokens), ext, kind)


@FUZZ
@given(data=st.binary(max_size=400), ext=st.sampled_from([".prr", ".ban", ".csv"]))
def test_random_bytes(data, ext):
    _check(data, ext, kind="rail")


# ----------------------------------------------------------------------------- Profile invariants
_coords = st.lists(st.one_of(st.floats(-0.1, 0.1), st.sampled_from([np.nan, np.inf, 5.0, 0.0])),
                   min_size=0, max_size=30)


@FUZZ
@given(y=_coords, z=_coords)
def test_profile_constructor_never_leaks_other_errors(y, z):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            p = Profile(y, z)
        except ProfileError:
            return
    assert np.all(np.diff(p.y) > 0) and len(p) >= 4


@FUZZ
@given(n=st.integers(4, 40), seed=st.integers(0, 2**16), angle=st.floats(-0.05, 0.05),
       dy=st.floats(-0.01, 0.01), dz=st.floats(-0.01, 0.01))
def test_copies_are_consistent(n, seed, angle, dy, dz):
    rng = np.random.default_rng(seed)
    y = np.cumsum(rng.uniform(1e-4, 5e-3, n))
    z = 0.5 * np.sin(20 * y) * 1e-2
    p = Profile(y, z)
    assert p.mirrored().mirrored() == p
    s = p.shifted(dy, dz)
    yq = np.linspace(p.y_min, p.y_max, 7)
    np.testing.assert_allclose(s(yq + dy), p(yq) + dz, atol=1e-12)
    try:
        r = p.rotated(angle).rotated(-angle)
    except ProfileError:  # steep parts may fold over: documented error
        return
    np.testing.assert_allclose(r.y, p.y, atol=1e-12)
    np.testing.assert_allclose(r.z, p.z, atol=1e-12)
