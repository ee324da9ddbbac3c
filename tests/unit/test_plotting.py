"""wheelrail.plotting: field normalisation and the figure functions (Agg, no display)."""

from __future__ import annotations

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.plotting import creep_curves, field_arrays, pressure_map, traction_field

PNG = b"\x89PNG\r\n\x1a\n"


def _strip_fields():
    """A strip grid stored [i_y, i_x] like FASTSIM: 3 strips, 4 elements each, own lengths."""
    ny, nx = 3, 4
    y = np.array([-1.0, 0.0, 1.0])[:, None] * np.ones((1, nx))
    dx = np.array([0.5, 1.0, 0.5])
    x = (1.0 - (np.arange(nx) + 0.5)[None, :] * dx[:, None]) * 2.0
    px = np.arange(ny * nx, dtype=float).reshape(ny, nx)
    slip = np.zeros((ny, nx), bool)
    slip[:, -1] = True  # trailing element slides
    return {"x": x, "y": y, "px": px, "py": -px, "slip": slip, "dx": 2 * dx, "dy": np.ones(ny)}


def test_field_arrays_orients_strip_grid():
    f = field_arrays(_strip_fields())
    assert f["x"].shape == (4, 3)  # [i_x, i_y]
    assert np.allclose(f["y"], f["y"][:1, :])  # y constant along i_x
    assert f["px"][1, 0] == 1.0 and f["py"][1, 0] == -1.0
    assert f["adhesion"].sum() == 9
    # element areas dx_j * dy_j per strip: adhesion area = 3 elements of each strip
    assert np.sum(f["dA"][f["adhesion"]]) == pytest.approx(3 * (1.0 + 2.0 + 1.0))


def test_field_arrays_axes_and_uniform_cells():
    x, y = np.linspace(-1, 1, 5), np.linspace(-2, 2, 3)
    px = np.ones((3, 5))  # stored [i_y, i_x]
    f = field_arrays({"x": x, "y": y, "px": px, "adhesion": np.ones((3, 5), bool)})
    assert f["x"].shape == (5, 3) and f["py"].shape == (5, 3)
    assert np.allclose(f["dA"], 0.5 * 2.0)
    assert field_arrays({"x": x, "p": px}) is None  # no traction
    assert field_arrays(None) is None


def test_field_arrays_of_fastsim_match_its_adhesion_fraction():
    c = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.Material(2.1e11, 0.28))
    r = wr.creep_forces(c, (-7e-4, 2e-4, 0.0), 0.3, method="fastsim", nx=10, ny=8)
    f = field_arrays(r.fields)
    assert f["x"].shape == (10, 8)
    frac = np.sum(f["dA"][f["adhesion"]]) / np.sum(f["dA"][f["inside"]])
    assert frac == pytest.approx(r.info["adhesion_fraction"], rel=1e-12)
    # the traction field integrates to the forces
    assert np.sum(f["px"] * f["dA"]) == pytest.approx(r.Fx, rel=1e-9)


def test_field_arrays_of_fastsim_single_element_strips():
    """nx = 1: the arrays are still [i_x, i_y] (FASTSIM gives its own layout; guessing the
    orientation from y being constant along a row fails when a row has one element)."""
    c = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.Material(2.1e11, 0.28))
    r = wr.creep_forces(c, (-7e-4, 2e-4, 0.0), 0.3, method="fastsim", nx=1, ny=8)
    f = field_arrays(r.fields)
    assert f["x"].shape == f["px"].shape == f["dA"].shape == (1, 8)
    assert np.all(np.diff(f["y"][0]) > 0)  # y varies along i_y
    assert np.sum(f["px"] * f["dA"]) == pytest.approx(r.Fx, rel=1e-9)


def test_creep_curves_clips_unbounded_law(tmp_path):
    s = np.linspace(0, 1e-2, 11)
    curves = {"linear": -400 * s, "other": -np.tanh(400 * s)}
    fig = creep_curves(s, curves, path=tmp_path / "c.png")
    lines = {ln.get_label(): ln for ln in fig.axes[0].get_lines()}
    y = np.asarray(lines["linear"].get_ydata(), float)
    assert np.all(np.isnan(y[np.abs(400 * s) > 1.5])) and np.all(np.isfinite(y[:4]))
    assert (tmp_path / "c.png").read_bytes()[:8] == PNG
    with pytest.raises(ValueError, match="shape"):
        creep_curves(s, {"bad": s[:3]})


def test_traction_field_and_pressure_map(tmp_path):
    traction_field(_strip_fields(), path=tmp_path / "t.png", title="strips")
    assert (tmp_path / "t.png").read_bytes()[:8] == PNG
    with pytest.raises(ValueError, match="no tangential traction"):
        traction_field({"p": np.ones((2, 2))})
    c = wr.hertz(7500.0, 1.0, 2.0, wr.STEEL)
    fig = pressure_map(c, path=tmp_path / "p.png")
    assert (tmp_path / "p.png").read_bytes()[:8] == PNG
    assert f"{c.p0 / 1e6:.0f} MPa" in fig.axes[0].get_title()
    with pytest.raises(ValueError, match="one grid"):
        pressure_map(x=np.zeros(3), y=np.zeros(2), p=np.zeros((2, 2)))


def test_subsurface_section_marks_the_hertz_maximum(tmp_path):
    """Circular Hertz contact: the section's von Mises maximum lies on the axis at z ≈ 0.48 a
    (Johnson 1985, fig. 3.7, ν = 0.3), and the figure is written."""
    import numpy as np

    import wheelrail as wr
    from wheelrail.halfspace import Grid, subsurface_stresses
    from wheelrail.plotting import subsurface_section

    mat = wr.Material(2.1e11, 0.3)
    c = wr.hertz(1e4, 1.0, 1.0, mat)
    g = Grid.from_bounds(-c.a, c.a, -c.a, c.a, 25, 25)
    p = c.pressure(g.X, g.Y)
    s = subsurface_stresses(g, None, None, p, mat, np.linspace(0.1, 1.5, 29) * c.a)
    fig = subsurface_section(s, path=tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 0
    _, z, x, _ = s.max_location("von_mises")
    assert abs(x) < 0.1 * c.a
    assert z / c.a == pytest.approx(0.48, abs=0.06)
    assert fig.axes
