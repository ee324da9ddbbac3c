"""Figures of the wheel-rail module (wheelrail.plotting.wheelrail)."""

from __future__ import annotations

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.plotting.wheelrail import (adhesion_maps, contact_profiles, patch_field_arrays,
                                          sweep_forces)

pytest.importorskip("matplotlib")
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def setup():
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    motion = wr.Motion(speed=20.0, omega=20.0 / 0.46 * (1 - 1e-3))
    pos = wr.WheelRailPosition(ws, tr, y=0.005, yaw=0.002, roll=None, vertical_load=10e3)
    return ws, tr, motion, pos


@pytest.fixture(scope="module")
def hertz_fastsim(setup):
    _, _, motion, pos = setup
    return wr.solve(pos, motion=motion, mu=0.3, normal="hertz", tangential="fastsim")


@pytest.fixture(scope="module")
def bem_exact(setup):
    _, _, motion, pos = setup
    return wr.solve(pos, motion=motion, mu=0.3, normal="bem", tangential="exact",
                    element_size=5e-4)


def test_contact_profiles_draws_every_patch(hertz_fastsim, tmp_path):
    res = hertz_fastsim
    fig = contact_profiles(res, path=tmp_path / "p.png")
    assert (tmp_path / "p.png").read_bytes()[:8] == PNG
    axes = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert len(axes) == 4
    for col, side in enumerate(("left", "right")):
        top, bottom = axes[col], axes[2 + col]
        n = len(res.side(side))
        # one band on the rail head and one pressure map per patch
        assert len(top.collections) == n and len(bottom.collections) == n
        # the top view spans the patches' lateral extent on the rail: the centre of each
        # patch (σ · y_track) lies inside the drawn cells
        for k, pr in enumerate(res.side(side)):
            u = (-1.0 if side == "left" else 1.0) * pr.patch.frame.track_y * 1e3
            bb = bottom.collections[k].get_datalim(bottom.transData)
            assert bb.x0 - 1e-6 <= u <= bb.x1 + 1e-6
            # the pressure colours are the patch pressures in MPa
            assert np.max(bottom.collections[k].get_array()) <= pr.p_max / 1e6 * (1 + 1e-9)


def test_adhesion_area_of_fastsim_fields_matches_result(hertz_fastsim):
    """The adhesion cells drawn (from the fields) are the patch's adhesion fraction
    (FASTSIM reports the fraction of its cells times the exact ellipse area)."""
    fractions = []
    for pr in hertz_fastsim.patches:
        f = patch_field_arrays(pr)
        drawn = float(np.sum(f["dA"][f["inside"] & f["adhesion"]]))
        frac = drawn / float(np.sum(f["dA"][f["inside"]]))
        assert frac == pytest.approx(pr.adhesion_area / pr.area, rel=1e-9, abs=1e-12)
        fractions.append(frac)
    assert max(fractions) > 0.05      # this position has an adhesion zone to draw


def test_bem_patch_fields_cut_to_the_patch(bem_exact, tmp_path):
    """On a boundary-element grid the field arrays of a patch hold exactly its elements:
    their area is the patch area, their adhesion area the patch's."""
    for pr in bem_exact.patches:
        f = patch_field_arrays(pr)
        assert float(np.sum(f["dA"][f["inside"]])) == pytest.approx(pr.area, rel=1e-9)
        adh = float(np.sum(f["dA"][f["inside"] & f["adhesion"]]))
        assert adh == pytest.approx(pr.adhesion_area, rel=1e-9, abs=1e-12)
    fig = adhesion_maps(bem_exact, path=tmp_path / "a.png")
    assert (tmp_path / "a.png").read_bytes()[:8] == PNG
    assert sum(ax.get_visible() for ax in fig.axes) == len(bem_exact.patches)


def test_closed_form_law_says_no_field(setup):
    _, _, motion, pos = setup
    res = wr.solve(pos, motion=motion, mu=0.3, normal="hertz", tangential="linear")
    fig = adhesion_maps(res)
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert sum("no traction field" in t for t in texts) == len(res.patches)


def test_sweep_forces_marks_failed_rows(setup, tmp_path):
    ws, tr, motion, _ = setup
    ds = wr.wheelset_sweep(ws, tr, y=[0.0, 0.002, 0.004], vertical_load=10e3, motion=motion,
                           progress=False)
    bad = ds.copy()
    bad["status"] = ("y", np.array(["ok", "error", "ok"]))
    fig = sweep_forces(bad, path=tmp_path / "s.png")
    assert (tmp_path / "s.png").read_bytes()[:8] == PNG
    fn_ax = fig.axes[0]
    lines = [ln for ln in fn_ax.get_lines() if ln.get_label().startswith(("left", "right"))]
    assert {ln.get_label() for ln in lines} >= {"left 1", "right 1"}
    ydata = lines[0].get_xdata()
    assert np.allclose(ydata, [0.0, 2.0, 4.0])                       # mm
    vlines = [ln for ln in fn_ax.get_lines() if np.allclose(ln.get_xdata(), 2.0)
              and ln.get_linestyle() == ":"]
    assert vlines, "the failed position is marked"
    assert "1 position: 1 error" in fig._suptitle.get_text()


def test_sweep_figure_names_the_status_of_rows_that_are_not_ok():
    """A flange climb is a result, not a failure: the sweep figure's title says which
    status its dotted positions have."""
    from wheelrail.plotting.wheelrail import _status_note

    note = _status_note(["flange_climb", "flange_climb", "not_converged"])
    assert note == "3 positions: 2 flange climb, 1 not converged" and "failed" not in note
