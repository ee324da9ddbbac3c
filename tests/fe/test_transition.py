"""The one- to two-point contact transition model: meshes with flange and gauge face, the
general contact search, the track and suspension inputs (tiny meshes, seconds each)."""

import dataclasses

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.fe.mesh import MeshQualityError
from wheelrail.fe.transition import pose_contact, seed004_case
from wheelrail.fe.transition.mesh import (
    extrude_section,
    rail_section,
    spacing_axis,
    sweep_section,
    wheel_section,
)
from wheelrail.fe.transition.model import flange_contact_offset, rigid_pose, yawed_contact
from wheelrail.fe.transition.track import WheelSuspension, TrackStructure

S1002 = wr.profiles.load("S1002")
R54 = wr.profiles.load("54E1")


def test_spacing_axis_two_bands():
    x = spacing_axis(0.0, 0.1, [(0.01, 0.02), (0.07, 0.08)], 1e-3, 1.3, 8e-3)
    d = np.diff(x)
    assert x[0] == 0.0 and x[-1] == pytest.approx(0.1)
    for a, b in ((0.01, 0.02), (0.07, 0.08)):
        inside = (x[:-1] >= a) & (x[1:] <= b)
        assert inside.sum() >= 8
        np.testing.assert_allclose(d[inside], 1e-3, rtol=0.05)
    assert d.max() <= 8e-3 * 1.05 and d.max() > 3e-3          # graded between the bands


def test_sections_follow_the_profiles_with_flange_and_gauge_face():
    rows, curve, _ = rail_section(R54, 3e-3, [(-0.03, -0.02)])
    a = np.arctan(1 / 40)
    # surface nodes lie on the inclined profile, gauge face (|slope| > 1) included
    y0 = np.cos(a) * R54.y - np.sin(a) * R54.z
    z0 = np.sin(a) * R54.y + np.cos(a) * R54.z
    t = np.linspace(0, y0.size - 1, 40 * y0.size)             # densified polyline
    y0 = np.interp(t, np.arange(y0.size), y0)
    z0 = np.interp(t, np.arange(z0.size), z0)
    d = np.min(np.hypot(rows[0, :, 0, None] - y0[None], rows[0, :, 1, None] - z0[None]), axis=1)
    assert d.max() < 2e-5
    assert np.degrees(curve.contact_angle(curve.s_of_point(*rows[0, 1]))) > 60
    wrows, wcurve, _ = wheel_section(S1002, 3e-3, [(-0.04, -0.03)])
    assert wrows[0, :, 1].min() == pytest.approx(S1002.z.min(), abs=1e-4)     # flange tip
    # the first layer lies one layer depth inside along the normal
    np.testing.assert_allclose(np.hypot(*(wrows[1] - wrows[0]).T), 3e-3, rtol=1e-6)


def test_hex_quality_of_rail_and_full_wheel():
    rows, _, _ = rail_section(R54, 3e-3, [(-0.03, -0.02)])
    rail = extrude_section(rows, np.linspace(-0.02, 0.02, 9))
    q = rail.meta["quality"]
    assert q["min_jacobian_ratio"] > 0.05 and q["max_aspect"] < 60
    wrows, _, _ = wheel_section(S1002, 3e-3, [(-0.04, -0.03)])
    th = spacing_axis(-np.pi, np.pi, [(-0.05, 0.05)], 3e-3 / 0.46, 1.3, 0.04 / 0.46)[:-1]
    wheel = sweep_section(wrows, th, 0.46, periodic=True)
    assert wheel.meta["quality"]["min_jacobian_ratio"] > 0.05
    # periodic: every node belongs to an element, the ring closes
    assert np.unique(wheel.elements).size == wheel.n_nodes


def test_too_deep_layers_fold_with_a_clear_error():
    # the flange tip's radius of curvature is ~ 10 mm: 20 mm of offset layers fold
    with pytest.raises(MeshQualityError, match="wheel rim|folds"):
        wheel_section(S1002, 3e-3, [(-0.04, -0.03)], layer_depth=0.02, rim=0.04)


def test_contact_search_finds_tread_and_flange_patches_at_a_yawed_pose():
    case = seed004_case(0.02, mesh_size=2e-3)
    yf = flange_contact_offset(case)
    ps = pose_contact(case, yf - 5e-4, overlap=1e-4, yaw=0.025, half_length=0.04)
    assert len(ps) == 2
    flange, tread = ps
    assert np.degrees(flange["contact_angle"]) > 60 > np.degrees(tread["contact_angle"])
    assert flange["x"] > tread["x"] + 0.01           # the flange contact leads the axle


def test_flange_contact_angle_against_the_rigid_contact_search():
    """First flange contact of S1002 on 54E1 1:40: FE patch angle against wr.contact_points
    (independent rigid search with the wheelset constraint) and the 65–75° of the flange."""
    case = seed004_case(0.02, mesh_size=2e-3)
    yf = flange_contact_offset(case)
    (flange,) = pose_contact(case, yf + 3e-4, overlap=5e-5)
    ws = wr.Wheelset(S1002, nominal_radius=0.46)
    tr = wr.Track(R54, inclination=1 / 40)
    ang = None
    for y in np.arange(0.0060, 0.0070, 1e-4):
        cp = wr.contact_points(ws, tr, y)
        a = np.degrees(cp.right.contact_angle[cp.right.primary])
        if a > 45:
            ang = a
            break
    assert ang is not None and 65 < ang < 75
    fe = np.degrees(flange["contact_angle"])
    assert 65 < fe < 75
    assert fe == pytest.approx(ang, abs=2.0)
    assert fe == pytest.approx(np.degrees(rigid_pose(case, yf + 3e-4)["contact_angle"]), abs=2.0)


def _first_flange(has_flange, lo, hi, n=14):
    """Smallest lateral offset in [lo, hi] where ``has_flange`` turns true (bisection)."""
    for _ in range(n):
        m = 0.5 * (lo + hi)
        lo, hi = (lo, m) if has_flange(m) else (m, hi)
    return hi


def test_yawed_first_flange_contact_against_the_wheelset_contact_search():
    """First flange touch of the yawed wheel (S1002 on 54E1 1:40) against wr.contact_points
    with yaw (an independent search: whole wheelset with roll, yawed about its centre):
    the contact angle does not depend on the angle of attack (≈ 70°, the flange flank of
    S1002), the flange contact's lead ahead of the axle grows in proportion to it."""
    ws = wr.Wheelset(S1002, nominal_radius=0.46)
    tr = wr.Track(R54, inclination=1 / 40)

    def cp_flange(y, yaw):
        r = wr.contact_points(ws, tr, y, yaw=yaw).right
        k = np.flatnonzero(r.contact_angle > np.radians(45))
        return (r.contact_angle[k[0]], r.x[k[0]]) if k.size else None

    leads = []
    for aoa in (0.015, 0.025):
        case = seed004_case(aoa)
        yf = flange_contact_offset(case)
        y1 = _first_flange(lambda y: yawed_contact(case, y, aoa)["flange"]["gap"] <= 0,
                           yf - 1e-3, yf)
        f = yawed_contact(case, y1, aoa)["flange"]
        y2 = _first_flange(lambda y: cp_flange(y, aoa) is not None, 0.0055, 0.0065)
        ang, x = cp_flange(y2, aoa)
        assert np.degrees(f["angle"]) == pytest.approx(np.degrees(ang), abs=0.5)
        assert 68 < np.degrees(f["angle"]) < 72
        assert f["x"] == pytest.approx(x, rel=0.05)
        assert y1 < yf                       # the yawed flange touches before the unyawed
        leads.append(f["x"] / aoa)
    assert leads[0] == pytest.approx(leads[1], rel=0.02)   # lead ∝ α (≈ 1.33 m · α)
    # no yaw: the same contact as the 2-D rigid search
    case = seed004_case(0.02)
    yf = flange_contact_offset(case)
    for y in (yf - 2e-3, yf + 5e-4):
        r = yawed_contact(case, y, 0.0)
        p = rigid_pose(case, y)
        assert r["z_off"] == pytest.approx(p["z_off"], abs=2e-6)
        hit = r["flange"] if r["flange"]["gap"] <= r["tread"]["gap"] else r["tread"]
        assert hit["angle"] == pytest.approx(p["contact_angle"], abs=np.radians(1.0))


def test_fe_contact_search_at_the_rigid_yawed_flange_pose():
    """The FE contact search on a 1 mm mesh, with the wheel yawed by 20 mrad at the rigid
    yawed pose (:func:`yawed_contact`) lowered by 50 µm: one flange patch at the rigid
    contact angle (≈ 70°) and lead (within two elements)."""
    case = seed004_case(0.020, mesh_size=1e-3)
    y = flange_contact_offset(case) - 2e-4
    rig = yawed_contact(case, y, 0.020)
    (flange,) = pose_contact(case, y, overlap=5e-5, yaw=0.020, half_length=0.05,
                             z_off=rig["z_off"])
    assert np.degrees(flange["contact_angle"]) == pytest.approx(
        np.degrees(rig["flange"]["angle"]), abs=1.5)
    assert flange["x"] == pytest.approx(rig["flange"]["x"], abs=2e-3)


def test_track_and_suspension_inputs_are_validated():
    t = TrackStructure()
    assert t.length == pytest.approx(2 * 0.6 + 2 * 0.3)
    with pytest.raises(InputError, match="n_sleepers"):
        TrackStructure(n_sleepers=1)
    with pytest.raises(InputError, match="pad_stiffness"):
        TrackStructure(pad_stiffness=-1.0)
    with pytest.raises(InputError, match="pad_length"):
        TrackStructure(pad_length=0.7)
    with pytest.raises(InputError, match="sleeper_hold"):
        TrackStructure(sleeper_hold="top")
    s = WheelSuspension()
    assert s.wheel_load(200.0) == pytest.approx((8000 + 300 + 200) * 9.81)
    with pytest.raises(InputError, match="torque"):
        WheelSuspension(torque=float("nan"))
    with pytest.raises(InputError, match="lateral_stiffness"):
        WheelSuspension(lateral_stiffness=-1.0)
    with pytest.raises(InputError, match="roll_stiffness"):
        WheelSuspension(roll_stiffness=float("nan"))
    with pytest.raises(InputError, match="roll_damping"):
        WheelSuspension(roll_damping=-1.0)
    with pytest.raises(InputError, match="axle_roll_inertia"):
        WheelSuspension(axle_roll_inertia=float("inf"))
    with pytest.raises(InputError, match="diameter"):
        WheelSuspension.half_axle_roll_stiffness(diameter=0.0)
    # E I / L, I = π d⁴/64 = 5.153e-5 m⁴ for a 180 mm solid shaft (Timoshenko & Gere)
    assert WheelSuspension.half_axle_roll_stiffness(0.18, 0.75, 2.1e11) == pytest.approx(
        2.1e11 * 5.153e-5 / 0.75, rel=1e-3)
    with pytest.raises(InputError, match="lateral_damping"):
        WheelSuspension(lateral_damping=float("inf"))
    assert WheelSuspension(lateral_stiffness=0.0).lateral_stiffness == 0.0
    with pytest.raises(InputError, match="traction"):
        seed004_case(0.02, traction=0.7)
    with pytest.raises(InputError, match="size"):
        seed004_case(0.02, size="huge")


def test_railpad_lateral_stiffness_is_separate_from_the_longitudinal(tiny_transition):
    """Each rail seat's pad is spread over the seat's foot nodes; the springs of one
    direction add up to the seat's stiffness per sleeper. A lateral value of its own
    (a fastening's 15 MN/m, Huo & Dai 2019, Table 2) changes only the lateral springs."""
    from wheelrail.fe.transition.model import build_transition_model

    case, model = tiny_transition
    t = TrackStructure()
    assert t.pad_springs()[1] == (t.pad_shear_stiffness, t.pad_shear_damping)
    # unset, the lateral values follow the shear ones, also through a replace
    assert dataclasses.replace(t, pad_shear_stiffness=1e8).pad_springs()[1][0] == 1e8
    track = dataclasses.replace(case.track, pad_lateral_stiffness=1.5e7,
                                pad_lateral_damping=5e4)
    soft = build_transition_model(case.replace(track=track))

    def sums(m):
        sp = m.springs
        pad = np.diff(sp.B.indptr) > 1           # pads tie a foot node to a sleeper face
        return [(sp.kv[pad & (sp.d == d)].sum(), sp.cv[pad & (sp.d == d)].sum())
                for d in range(3)]

    n = case.track.n_sleepers
    (kx0, cx0), (ky0, cy0), (kz0, cz0) = sums(model)
    (kx1, cx1), (ky1, cy1), (kz1, cz1) = sums(soft)
    assert ky0 == pytest.approx(n * case.track.pad_shear_stiffness, rel=1e-12)
    assert kz0 == pytest.approx(n * case.track.pad_stiffness, rel=1e-12)
    assert (ky1, cy1) == pytest.approx((n * 1.5e7, n * 5e4), rel=1e-12)
    assert (kx1, cx1, kz1, cz1) == (kx0, cx0, kz0, cz0)
    with pytest.raises(InputError, match="pad_lateral_stiffness"):
        TrackStructure(pad_lateral_stiffness=0.0)


def test_tread_and_flange_nodes_that_touch_on_the_grid_are_split_by_contact_angle():
    """On a coarse wheel-surface grid the flange-root (tread) and flange contacts are
    neighbours: 8-connectivity merges them, the contact-angle split keeps them apart."""
    from wheelrail.fe.transition.contact import patches, split_patches

    status = np.zeros((6, 8), np.int64)
    status[1:5, 2:6] = 1                       # one connected block of closed nodes
    angle = np.zeros((6, 8))
    angle[:, 2:4] = np.radians(70.0)           # flange side of the block
    angle[:, 4:6] = np.radians(20.0)           # flange root
    angle[0, 0] = np.radians(10.0)
    status[0, 0] = 1                           # a separate one-node island on the tread
    force = np.where(status > 0, 1.0, 0.0)
    force[0, 0] = 0.1
    _, n = patches(status)
    assert n == 2                              # the block is one patch by connectivity
    lab, counts = split_patches(status, angle, force)
    assert counts == (2, 1)
    assert np.all(lab[1:5, 2:4] == 2) and np.all(lab[1:5, 4:6] == 1)
    assert lab[0, 0] == 3                      # the weaker tread island goes to "others"
    assert np.all(lab[status == 0] == 0)


def test_a_patch_closed_without_pressure_is_reported_empty_not_nan():
    """Closed nodes that carry no normal force (just touching) have no mean normal: the
    summary reports an empty patch (Fn 0, no centre) instead of NaN forces and warnings."""
    import warnings

    from wheelrail.fe.transition.contact import patch_summary

    n = 4
    xs = np.zeros((n, 3))
    zeros = np.zeros((n, 3))
    normal = np.tile([0.0, 0.0, 1.0], (n, 1))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = patch_summary(np.ones(n, bool), xs, zeros, np.zeros(n), zeros, normal,
                          np.full(n, 1e-6), np.ones(n, np.int64), 0.6)
    assert s["Fn"] == 0.0 and s["Fz"] == 0.0 and s["n_nodes"] == 0
    assert np.isnan(s["contact_angle"])        # no contact, no angle
    p = patch_summary(np.ones(n, bool), xs, zeros, np.array([0.0, 1e3, 0.0, 0.0]), zeros,
                      normal, np.full(n, 1e-6), np.ones(n, np.int64), 0.6)
    assert p["Fn"] == 1e3 and p["contact_angle"] == 0.0


@pytest.fixture(scope="module")
def tiny_transition():
    from wheelrail.fe.transition.model import build_transition_model

    case = seed004_case(0.025, mesh_size=5e-3, travel=1.2e-3, settle=0.5e-3,
                        flange_clearance=3e-3, output_interval=6e-6)
    return case, build_transition_model(case)


def test_restart_continues_a_transition_run_exactly(tiny_transition, tmp_path):
    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    # with a record of the flange line's velocities from 0.3 mm of travel on (asked for
    # longer than the run: it ends with the run)
    case = case.replace(wave_travel=0.3e-3, wave_time=1e-3, wave_line="flange")
    f = tmp_path / "restart.npz"
    a = run_transition(case, model=model, restart_file=f, restart_every=60)
    with np.load(f) as z:
        k = int(z["step"])
        # past the settle distance the start damping is off entirely (it fades in steps
        # of 2 % and is set to 0 at the settle distance, not left at its last step)
        assert float(z["s"]) > case.settle and float(z["fade"]) == 0.0
    assert 0 < k < a.info["steps"] - 1
    # the histories up to the restart's step, as the uninterrupted run has them
    from wheelrail.fe.transition import read_transition_restart

    pp, hh, prog = read_transition_restart(f)
    assert prog == {"step": k, "steps": a.info["steps"]}
    nt = pp.sizes["time"]
    assert 0 < nt < a.patches.sizes["time"]
    np.testing.assert_array_equal(pp["Fn"].values, a.patches["Fn"].values[:nt])
    np.testing.assert_array_equal(hh["Fz_total"].values, a.history["Fz_total"].values[:nt])
    b = run_transition(case, model=model, restart=f)
    # the cost per step counts the steps run in the continuation only
    assert b.info["steps_run"] == a.info["steps"] - (k + 1)
    assert b.info["ns_per_element_step"] == pytest.approx(
        b.info["cpu_s"] / (b.info["steps_run"] * model.n_elements) * 1e9)
    np.testing.assert_allclose(b.patches["Fn"].values, a.patches["Fn"].values, rtol=1e-9,
                               atol=1e-6)
    np.testing.assert_allclose(b.u, a.u, rtol=1e-9, atol=1e-15)
    # the wave record: it starts at the requested travel, on the gauge-corner line (the
    # rigid flange contact at 70.3 deg), and a continuation returns the rows it ran
    wa, wb = a.info["wave"], b.info["wave"]
    dt = a.info["time_step"]
    assert wa["t"][0] == pytest.approx(0.3e-3 / case.speed, abs=1.01 * dt)
    assert wa["v"].shape == (wa["t"].size, wa["x"].size, 3)
    assert np.degrees(np.arccos(abs(wa["normal"][2]))) == pytest.approx(70.3, abs=4.0)
    assert np.abs(wa["v"][-1]).max() > 0
    assert wa["t"][-1] == pytest.approx(case.travel / case.speed, abs=1.01 * dt)
    assert wb["t"][0] > wa["t"][0] and wb["t"][-1] == wa["t"][-1]
    tail = wa["t"].size - wb["t"].size
    np.testing.assert_allclose(wb["v"], wa["v"][tail:], rtol=1e-9, atol=1e-12)
    with np.load(f) as z:
        other = dict(z)
    # a restart file written before the lateral and roll degrees of freedom (no y, vy,
    # phi, vphi, m_roll0; 12 history columns) continues the same way
    old = {k2: v2 for k2, v2 in other.items()
           if k2 not in ("y", "vy", "phi", "vphi", "m_roll0")}
    old["hist"] = old["hist"][:, :12]
    np.savez(tmp_path / "old.npz", **old)
    c = run_transition(case, model=model, restart=tmp_path / "old.npz")
    np.testing.assert_array_equal(c.patches["Fn"].values, b.patches["Fn"].values)
    assert np.all(c.history["lateral"].values == 0.0)
    assert np.all(c.history["roll_angle"].values == 0.0)
    n_old = old["hist"].shape[0]
    assert np.all(c.history["roll_moment"].values[:n_old] == 0.0)     # padded rows
    np.testing.assert_array_equal(c.history["roll_moment"].values[n_old:],
                                  a.history["roll_moment"].values[n_old:])
    assert np.abs(a.history["roll_moment"].values[n_old:]).min() > 0.0
    other["n_nodes"] = model.n_nodes + 1
    np.savez(tmp_path / "other.npz", **other)
    with pytest.raises(InputError, match="another case"):
        run_transition(case, model=model, restart=tmp_path / "other.npz")


def test_a_run_stopped_early_continues_with_its_fields_recorded(tiny_transition, tmp_path):
    """``stop_travel`` ends a run part way, writes the restart file at the stop, and a
    continuation with a field window from there (an output option: the motion is the
    same) reproduces the uninterrupted run and records the fields it ran."""
    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    full = run_transition(case, model=model)
    f = tmp_path / "stop.npz"
    stop = 0.5e-3
    a = run_transition(case, model=model, restart_file=f, stop_travel=stop)
    dt = a.info["time_step"]
    k_stop = a.info["stopped_at"]
    assert 0 < k_stop < full.info["steps"] and a.info["steps_run"] == k_stop
    with np.load(f) as z:
        assert int(z["step"]) == k_stop - 1
        assert float(z["s"]) == pytest.approx(stop, abs=1.01 * dt * case.speed)
    # the last output is the stop, at the travel asked for
    assert a.patches["travel"].values[-1] == pytest.approx(stop, abs=1.01 * dt * case.speed)
    assert a.contact_fields is None
    later = case.replace(field_travel=(stop, case.travel))
    b = run_transition(later, model=model, restart=f)
    assert b.info["stopped_at"] is None
    assert b.info["steps_run"] == full.info["steps"] - k_stop
    np.testing.assert_allclose(b.u, full.u, rtol=1e-9, atol=1e-15)
    # outputs every output_interval, plus the one at the stop
    t_full, t_b = full.patches["time"].values, b.patches["time"].values
    extra = np.setdiff1d(t_b, t_full)
    assert extra.size == 1 and extra[0] == pytest.approx(a.patches["time"].values[-1])
    keep = np.isin(t_b, t_full)
    np.testing.assert_allclose(b.patches["Fn"].values[keep], full.patches["Fn"].values,
                               rtol=1e-9, atol=1e-6)
    tr = b.contact_fields["travel"].values
    assert tr.size > 0 and tr.min() > stop
    with pytest.raises(InputError, match="at or past the stop"):
        run_transition(case, model=model, restart=f, stop_travel=0.2e-3)
    with pytest.raises(InputError, match="stop_travel"):
        run_transition(case, model=model, stop_travel=-1.0)


def test_prescribed_creepage_holds_the_rolling_and_the_contact_brakes_it(tiny_transition):
    """With ``creepage`` the wheel turns at ω = (1 + creepage) V / r0 from the first rolling
    step, whatever the contact does; a driven wheel's contact moment opposes the rolling
    (Kalker's convention: a positive creepage of the wheel gives a negative force on it)."""
    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    c = case.replace(creepage=0.01)
    r = run_transition(c, model=model)
    h = r.history
    np.testing.assert_allclose(h["creepage"].values, 0.01, rtol=1e-12)
    r0 = model.pose["r0"]
    np.testing.assert_allclose(h["omega"].values, 1.01 * c.speed / r0, rtol=1e-12)
    assert r.info["torque"] == 0.0
    # the patch's longitudinal force and the contact moment act against the spin-up once
    # the patch has built up (last third of the run)
    late = h["travel"].values > 0.6 * c.travel
    assert np.all(h["torque_contact"].values[late] < 0.0)
    with pytest.raises(InputError, match="creepage"):
        case.replace(creepage=0.5)


def test_cli_runs_a_tiny_transition_case_with_estimate_restart_and_figure(tmp_path, capsys):
    import json

    from wheelrail.cli.main import main

    case = tmp_path / "t.toml"
    case.write_text('[fe]\ntransition = "reduced"\nangle_of_attack = 0.025\nmesh_size = 5e-3\n'
                    'travel = 1.2e-3\nsettle = 0.5e-3\nflange_clearance = 3e-3\n'
                    'output_interval = 6e-6\nfield_travel = [0.6e-3, 1.2e-3]\n'
                    'wave_time = 1e-3\nwave_travel = 0.2e-3\nwave_line = "flange"\n')
    out = tmp_path / "out"
    assert main(["fe", str(case), "--out", str(out), "--estimate-only"]) == 0
    text = capsys.readouterr().out
    assert "FE transition" in text and "estimate:" in text and not out.exists()
    assert main(["fe", str(case), "--out", str(out), "--restart-every", "60"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["mode"] == "transition" and summary["steps"] > 100
    for f in ("patches.nc", "history.nc", "restart.npz", "contact_fields.nc"):
        assert (out / f).is_file()
    assert (out / "transition.png").stat().st_size > 10_000
    for kind in ("stress", "slip"):
        assert (out / f"contact_fields_{kind}.png").stat().st_size > 10_000
    with np.load(out / "wave.npz") as z:
        assert str(z["line"]) == "flange" and z["v"].shape == (z["t"].size, z["x"].size, 3)
        assert z["t"][0] == pytest.approx(0.2e-3 / (80 / 3.6), abs=1.01 * summary["time_step"])
    bad = tmp_path / "bad.toml"
    bad.write_text('[fe]\ntransition = "reduced"\nangle_of_attak = 0.025\n')
    assert main(["fe", str(bad), "--out", str(out)]) != 0
    assert "angle_of_attak" in capsys.readouterr().err
    # --stop-travel: part of the run, with the restart file at the stop
    part = tmp_path / "part"
    assert main(["fe", str(case), "--out", str(part), "--stop-travel", "0.4e-3",
                 "--no-figures"]) == 0
    assert "stopped at 0.4 mm" in capsys.readouterr().out
    part_summary = json.loads((part / "summary.json").read_text())
    assert 0 < part_summary["stopped_at"] < summary["steps"]
    assert "stopped_at" not in summary           # the whole run: no stop
    with np.load(part / "restart.npz") as z:
        assert int(z["step"]) == part_summary["stopped_at"] - 1
    plain = tmp_path / "plain.toml"
    plain.write_text('[fe]\nwheel = "cylinder"\nrail = "60E1"\nradius = 0.46\nFn = 7500.0\n'
                     'creepage = [7e-4, 0.0, 0.0]\nmu = 0.2\n')
    assert main(["fe", str(plain), "--out", str(part), "--stop-travel", "0.01"]) != 0
    assert "--stop-travel" in capsys.readouterr().err


def test_case_file_suspension_and_track_tables(tmp_path, capsys):
    """[fe.suspension] and [fe.track] tables become WheelSuspension / TrackStructure fields; an
    unknown field is refused with its name."""
    from wheelrail.cli.fe import case_from_toml
    from wheelrail.cli.main import main

    f = tmp_path / "t.toml"
    f.write_text('[fe]\ntransition = "reduced"\nangle_of_attack = 0.025\n'
                 '[fe.suspension]\nlateral_stiffness = 0.0\nlateral_damping = 1e3\n'
                 'roll_stiffness = 1.44e7\n[fe.track]\nn_sleepers = 3\n')
    case, mode = case_from_toml(f)
    assert mode == "transition"
    assert case.suspension.lateral_stiffness == 0.0
    assert case.suspension.lateral_damping == 1e3
    assert case.suspension.roll_stiffness == 1.44e7 and case.suspension.roll_damping == 0.0
    assert case.track.n_sleepers == 3
    f.write_text('[fe]\ntransition = "reduced"\n[fe.suspension]\nlateral_stifness = 0.0\n')
    assert main(["fe", str(f), "--out", str(tmp_path / "o"), "--estimate-only"]) != 0
    assert "lateral_stifness" in capsys.readouterr().err


def test_contact_fields_of_a_tiny_run_add_up_to_the_patch_histories(tiny_transition, tmp_path):
    """The surface fields recorded at the outputs in a travel window: the nodal pressures
    and shear stresses integrate to the per-patch forces of the same outputs (computed
    from the contact forces directly by ``patch_summary``), the adhering area by the
    tolerance definition matches the patch's adhering fraction, the micro-slip lies in the
    contact plane, and the maps are drawn; a bad window is refused."""
    import xarray as xr

    from wheelrail.fe.plots import plot_contact_fields
    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    r = run_transition(case.replace(field_travel=(0.6e-3, 1.1e-3), field_stride=2),
                       model=model)
    f = r.contact_fields
    assert f is not None and set(f.dims) == {"time", "row", "col"}
    s = f.travel.values
    assert s.min() >= 0.6e-3 and s.max() <= 1.1e-3 and f.sizes["time"] >= 2
    P = r.patches
    every = np.flatnonzero((P.travel.values >= 0.6e-3) & (P.travel.values <= 1.1e-3))
    np.testing.assert_array_equal(f.time.values, P.time.values[every[::2]])
    for i, tt in enumerate(f.time.values):
        k = int(np.flatnonzero(P.time.values == tt)[0])
        sel = f.patch.values[i] == 1
        A = f.area.values[i][sel]
        assert sel.sum() == P.n_nodes.values[k, 0] > 0
        assert np.sum(f.pressure.values[i][sel] * A) == pytest.approx(P.Fn.values[k, 0],
                                                                      rel=1e-9)
        # shear on the rail = −(tangential force on the wheel), along the rail
        assert np.sum(f.traction_x.values[i][sel] * A) == pytest.approx(
            -P.F_long.values[k, 0], rel=1e-9, abs=1e-6)
        adh = np.sum(A[f.state.values[i][sel] == 2]) / A.sum()
        assert adh == pytest.approx(P.adhesion.values[k, 0], abs=1e-12)
        assert (f.state.values[i][~sel & (f.patch.values[i] == 0)] == 0).all()
        # micro-slip ⟂ the contact normal (prismatic rail: n = (0, −sin φ, cos φ))
        phi = f.contact_angle.values[i][sel]
        vn = -f.slip_y.values[i][sel] * np.sin(phi) + f.slip_z.values[i][sel] * np.cos(phi)
        v = np.hypot(np.hypot(f.slip_x.values[i][sel], f.slip_y.values[i][sel]),
                     f.slip_z.values[i][sel])
        assert np.all(np.abs(vn) <= 0.02 * v.max() + 1e-12)
    # the patch's shear direction from the fields: the mean stress's angle is the patch
    # history's theta (from the contact forces), up to its sign
    from wheelrail.fe.transition.analysis import shear_direction

    sd = shear_direction(f, patch=1)
    k = [int(np.flatnonzero(P.time.values == tt)[0]) for tt in f.time.values]
    np.testing.assert_allclose(np.abs(sd.mean_stress.values),
                               np.degrees(P.theta.values[k, 0]), rtol=1e-9, atol=1e-9)
    assert (sd.n_nodes.values == P.n_nodes.values[k, 0]).all()
    assert np.isnan(shear_direction(f, patch=2).mean_angle.values).all()
    # the patch's mean micro-slip on the same nodes (its direction: a sliding patch's θ)
    from wheelrail.fe.transition.analysis import slip_direction

    sl = slip_direction(f, patch=1)
    assert (sl.n_nodes.values == sd.n_nodes.values).all()
    on = sd.n_nodes.values > 0
    assert np.isfinite(sl.angle.values[on]).all() and np.isnan(sl.angle.values[~on]).all()
    path = tmp_path / "fields.nc"
    f.to_netcdf(path)
    with xr.open_dataset(path) as g:
        np.testing.assert_array_equal(g.pressure.values, f.pressure.values)
    for kind in ("stress", "slip", "line"):
        plot_contact_fields(f, kind=kind, mu=case.mu, path=tmp_path / f"{kind}.png")
        assert (tmp_path / f"{kind}.png").stat().st_size > 10_000
    with pytest.raises(InputError, match="field_travel"):
        case.replace(field_travel=(0.01, 0.005))
    with pytest.raises(InputError, match="field_stride"):
        case.replace(field_stride=0)


def test_full_size_wheel_plate_passes_the_aspect_check():
    """The 1 mm case's wheel plate (radial size from ``plate_size``) swept over the fine
    arc at h/R: every element passes ``check_quality`` (aspect ≤ 60; with the former
    30 mm radial size the hub elements had 84.7)."""
    from wheelrail.fe.transition.mesh import wheel_plate_rows
    from wheelrail.fe.transition.model import PLATE_HUB, plate_size

    case = seed004_case(0.025, size="full")
    assert plate_size(case) < 0.03
    rows = wheel_plate_rows(-0.03, hub=PLATE_HUB, h_max=plate_size(case))
    th = spacing_axis(-0.02, 0.02, [(-0.01, 0.01)], case.mesh_size / case.radius,
                      case.grading, case.theta_h_max / case.radius)
    plate = sweep_section(rows, th, case.radius, name="wheel plate")
    assert plate.meta["quality"]["max_aspect"] <= 60
    with pytest.raises(MeshQualityError, match="aspect"):
        sweep_section(wheel_plate_rows(-0.03, hub=PLATE_HUB, h_max=0.03), th, case.radius,
                      name="wheel plate")


def test_sleepers_are_held_in_x_and_y_at_every_node_or_at_their_bottom(tiny_transition):
    """``sleeper_hold="body"`` (default) holds every sleeper node laterally and
    longitudinally (the sleepers move only vertically: they cannot pitch or roll on the
    vertical ballast springs); ``"bottom"`` holds the bottom face (3 x 4 nodes a sleeper
    with the default 2 x 3 x 2 elements)."""
    from dataclasses import replace as dc_replace

    from wheelrail.fe.transition.model import build_transition_model

    case, model = tiny_transition
    ex, ey, ez = case.track.sleeper_elements
    per = (ex + 1) * (ey + 1)
    assert model.held_xy.size == case.track.n_sleepers * per * (ez + 1)
    bottom = build_transition_model(case.replace(
        track=dc_replace(case.track, sleeper_hold="bottom")))
    assert bottom.held_xy.size == case.track.n_sleepers * per
    assert np.isin(bottom.held_xy, model.held_xy).all()
    # the held nodes are the sleepers': from their bottom (−0.359 m) up to their top at
    # the rail foot (the 54E1 rail is 159 mm high)
    z = model.nodes[model.held_xy, 2]
    assert z.min() == pytest.approx(-0.359, abs=1e-3) and z.max() == pytest.approx(-0.159, abs=1e-3)


def test_a_run_longer_than_its_model_is_refused(tiny_transition):
    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    with pytest.raises(InputError, match="fine zone"):
        run_transition(case.replace(travel=2 * case.travel), model=model)


def test_preload_phase_is_restartable_and_rolls_from_time_zero(tiny_transition, tmp_path):
    """A short preload: its outputs stand still (travel 0, negative times, no creepage),
    the rolling starts at t = 0 after ceil(preload / Δt) steps, and a restart inside the
    preload continues it exactly."""
    from wheelrail.fe.transition import run_transition, transition_time_estimate

    case0, model = tiny_transition
    case = case0.replace(preload=60e-6, travel=0.6e-3)
    est = transition_time_estimate(model, case=case)
    dt = est["time_step"]
    assert est["preload_steps"] == int(np.ceil(60e-6 / dt))
    assert est["steps"] == est["preload_steps"] + int(np.ceil(0.6e-3 / case.speed / dt))
    f = tmp_path / "r.npz"
    a = run_transition(case, model=model, restart_file=f, restart_every=est["preload_steps"] // 2)
    t = a.history.time.values
    s = a.history.travel.values
    pre = t < 0
    assert pre.sum() >= 8 and np.all(s[pre] == 0.0)
    assert np.all(np.isnan(a.history.creepage.values[pre]))
    assert np.all(s[~pre] > 0.0) and np.all(np.isfinite(a.history.creepage.values[~pre]))
    # the rolling starts at t = 0: travel = V t afterwards
    np.testing.assert_allclose(s[~pre], case.speed * t[~pre], rtol=1e-9)
    b = run_transition(case, model=model, restart=f)
    np.testing.assert_allclose(b.u, a.u, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(b.history.Fz_total.values, a.history.Fz_total.values,
                               rtol=1e-9, atol=1e-6)


def _check_second_order_law(got, load, inertia, t, dt):
    """``got`` (a displacement or angle from rest, every step) against inertia × got'' =
    load: exactly in the loop's semi-implicit Euler sums (v_k = v_{k-1} + dt F_k / M,
    x_k = x_{k-1} + dt v_k) and within 10 % at the end by the trapezoid rule."""
    euler = np.cumsum(np.cumsum(load) * dt / inertia) * dt
    np.testing.assert_allclose(got, euler, rtol=1e-6, atol=1e-15)
    vel = np.concatenate(([0.0], np.cumsum(0.5 * (load[1:] + load[:-1]) * np.diff(t))))
    vel /= inertia
    x = np.concatenate(([0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * np.diff(t))))
    assert got[-1] == pytest.approx(x[-1], rel=0.10)


def test_free_lateral_motion_follows_newtons_law_and_a_stiff_restraint_the_path(
        tiny_transition):
    """With ``lateral_stiffness = 0`` the wheel's displacement along the axle from its
    heading path obeys M y'' = F_axle (Newton's second law for the half-axle and wheel
    mass M; F_axle the contact force's part along the axle, from the force histories
    output every step): exactly in the loop's semi-implicit Euler sums, and within 10 %
    by the trapezoid rule. A stiff restraint (1e11 N/m) keeps y within 2 F/k and the
    vertical force within 2 % of the held run's."""
    from dataclasses import replace

    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    case = case.replace(output_interval=1e-9)          # an output every step
    held = run_transition(case, model=model)
    assert np.all(held.history["lateral"].values == 0.0)
    free = run_transition(case.replace(suspension=replace(case.suspension,
                                                          lateral_stiffness=0.0)),
                          model=model)
    h = free.history
    t = h.time.values
    dt = free.info["time_step"]
    assert t.size == free.info["steps"]
    alpha = case.angle_of_attack
    f_ax = -np.sin(alpha) * h.Fx_total.values + np.cos(alpha) * h.Fy_total.values
    m_lat = case.suspension.axle_mass + float(model.mass[:model.n_wheel].sum())
    got = h["lateral"].values
    assert abs(got[-1]) > 1e-9
    _check_second_order_law(got, f_ax, m_lat, t, dt)
    stiff = run_transition(case.replace(suspension=replace(case.suspension,
                                                           lateral_stiffness=1e11,
                                                           lateral_damping=2e6)),
                           model=model)
    assert np.abs(stiff.history["lateral"].values).max() < 2 * np.abs(f_ax).max() / 1e11
    np.testing.assert_allclose(stiff.history["Fz_total"].values,
                               held.history["Fz_total"].values, rtol=0.02)


def test_roll_follows_eulers_law_and_a_stiff_restraint_holds_the_wheel(tiny_transition):
    """With ``roll_stiffness = 0`` the wheel's roll φ about its heading obeys
    I φ'' = M − M0 (Euler's law for the FE wheel's Σ m (y² + z²) plus the half-axle's
    share; M the contact moment about the heading axis, from the histories output every
    step; M0 its value at the end of the static preload): exactly in the loop's
    semi-implicit Euler sums, and within 10 % by the trapezoid rule. A stiff restraint
    (1e10 N m/rad) keeps φ within 2 max|M − M0|/k and the vertical force within 2 % of the
    held run's. Without a preload the roll spring has no static balance: refused."""
    from dataclasses import replace

    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    with pytest.raises(InputError, match="roll_stiffness.*preload"):
        run_transition(case.replace(suspension=replace(case.suspension, roll_stiffness=1e7)),
                       model=model)
    case = case.replace(output_interval=1e-9, preload=0.1e-3)     # an output every step
    held = run_transition(case, model=model)
    assert np.all(held.history["roll_angle"].values == 0.0)
    nw = model.n_wheel
    i_fe = float(np.sum(model.mass[:nw] * (model.nodes[:nw, 1] ** 2 + model.nodes[:nw, 2] ** 2)))
    free = run_transition(case.replace(suspension=replace(case.suspension, roll_stiffness=0.0)),
                          model=model)
    assert free.info["roll_inertia"] == pytest.approx(i_fe + 8.0, rel=1e-12)
    assert 10.0 < i_fe < 30.0         # a 211 kg wheel of radius 0.46 m: about m r² / 4 + rim
    h = free.history
    rolling = ~np.isnan(h.creepage.values)
    t = h.time.values[rolling]
    dt = free.info["time_step"]
    dm = h["roll_moment"].values[rolling]
    dm = dm - dm[0]
    got = h["roll_angle"].values[rolling]
    assert abs(got[-1]) > 1e-8
    assert np.all(h["roll_angle"].values[~rolling] == 0.0)
    i_roll = free.info["roll_inertia"]
    _check_second_order_law(got, dm, i_roll, t, dt)
    stiff = run_transition(case.replace(suspension=replace(case.suspension,
                                                           roll_stiffness=1e10)), model=model)
    hs = stiff.history
    dms = hs["roll_moment"].values[rolling]
    assert np.abs(hs["roll_angle"].values).max() < 2 * np.abs(dms - dms[0]).max() / 1e10
    assert np.abs(hs["roll_angle"].values).max() > 0.0
    np.testing.assert_allclose(hs["Fz_total"].values, held.history["Fz_total"].values,
                               rtol=0.02)


@pytest.mark.slow
def test_preload_brings_the_contact_to_the_static_wheel_load():
    """Dynamic relaxation before rolling: over the last 0.3 ms of a 0.8 ms preload the
    vertical contact force equals the static wheel load (sprung + half-axle + wheel mass
    times g: statics, independent of the FE) within 3 % and scatters by < 4 % (measured
    −0.9 % and 0.9 %; after 1.2 ms −0.5 % and 0.9 %, after 0.6 ms the scatter is still
    2.9 %); the start state alone (beam-model track, 60 % of the Hertz approach) is off by
    > 10 % at first. A coarse 5 mm model (15 k elements, 2 171 steps)."""
    from wheelrail.fe.transition import run_transition

    case = seed004_case(0.0, mesh_size=5e-3, travel=0.3e-3, settle=0.1e-3,
                        flange_clearance=3e-3, output_interval=30e-6, section_h_max=12e-3,
                        x_h_max=0.05, theta_h_max=0.1, preload=0.8e-3)
    r = run_transition(case)
    h = r.history
    t = h.time.values
    fz = h.Fz_total.values
    m_wheel = float(r.model.mass[:r.model.n_wheel].sum())
    q = (case.suspension.sprung_mass + case.suspension.axle_mass + m_wheel) * 9.81
    assert 150.0 < m_wheel < 300.0 and r.info["load"] == pytest.approx(q, rel=1e-3)
    late = (t < 0) & (t > -0.3e-3)
    assert late.sum() >= 8
    assert abs(fz[late].mean() / q - 1.0) < 0.03
    assert fz[late].std() / q < 0.04
    assert abs(fz[0] / q - 1.0) > 0.10


def test_climb_load_follows_the_contact_slope_of_the_rigid_pose():
    """The axle's rigid height over its lateral offset rises with the slope of the contact
    (envelope theorem: z′ = tan of the contact angle, the rail's slope at the contact point
    of :func:`rigid_pose`, computed independently of the heights), and the climbing
    inertia is M_u (V sin α)² z″ with z″ the change of that slope."""
    from wheelrail.fe.transition.analysis import climb_load
    from wheelrail.fe.transition.model import flange_contact_offset, rigid_pose

    case = seed004_case(0.025, flange_clearance=7e-3, travel=0.33)
    s = np.linspace(0.02, 0.16, 8)           # on the tread (contact angle 4-7 degrees)
    c = climb_load(case, s, 212.0)
    y0 = flange_contact_offset(case) - 7e-3
    np.testing.assert_allclose(c["y"], y0 + s * np.sin(0.025))
    tan = np.array([np.tan(rigid_pose(case, y)["contact_angle"]) for y in c["y"]])
    assert np.all(tan > 0.06)
    np.testing.assert_allclose(c["dz"], tan, rtol=0.05)
    # z'' from the slope's change over the window, against the mean of climb_load's z''
    d2 = (tan[-1] - tan[0]) / (c["y"][-1] - c["y"][0])
    assert np.mean(c["d2z"]) == pytest.approx(d2, rel=0.3)
    mu = case.suspension.axle_mass + 212.0
    np.testing.assert_allclose(c["inertia"], mu * (case.speed * np.sin(0.025)) ** 2 * c["d2z"])
    assert np.all(climb_load(case.replace(angle_of_attack=0.0), s, 212.0)["total"] == 0.0)
    with pytest.raises(InputError, match="travel"):
        climb_load(case, [-0.1], 212.0)


def test_shear_direction_averages_of_a_turning_shear():
    """Half the patch sheared at +60 deg, half at -60 deg (equal magnitudes), as under pure
    spin: the mean stress points along the rail (0 deg), the nodes' mean signed angle is
    0 deg, their mean |angle| 60 deg; a uniform 30 deg shear gives 30 deg three times."""
    import xarray as xr

    from wheelrail.fe.transition.analysis import shear_direction

    nt, nr, nc = 2, 4, 6
    ang = np.radians(np.where(np.arange(nc) < 3, 60.0, -60.0))[None, None, :] * np.ones((nt, nr, 1))
    ang[1] = np.radians(30.0)
    phi = np.radians(20.0)             # contact angle: the lateral tangent (0, cos, sin)
    q = 1e8
    ds = xr.Dataset({"traction_x": (("time", "row", "col"), -q * np.cos(ang)),
                     "traction_y": (("time", "row", "col"), q * np.sin(ang) * np.cos(phi)),
                     "traction_z": (("time", "row", "col"), q * np.sin(ang) * np.sin(phi)),
                     "area": (("time", "row", "col"), np.full((nt, nr, nc), 4e-6)),
                     "patch": (("time", "row", "col"), np.ones((nt, nr, nc), np.int8))},
                    coords={"time": [0.0, 1e-5], "travel": ("time", [0.0, 2e-4])})
    sd = shear_direction(ds, patch=1)
    np.testing.assert_allclose(sd.mean_stress.values, [0.0, 30.0], atol=1e-9)
    np.testing.assert_allclose(sd.mean_angle.values, [0.0, 30.0], atol=1e-9)
    np.testing.assert_allclose(sd.mean_abs_angle.values, [60.0, 30.0], atol=1e-9)
    with pytest.raises(InputError, match="patch"):
        shear_direction(ds, patch=4)
    with pytest.raises(InputError, match="traction_x"):
        shear_direction(ds.drop_vars("traction_x"))


def test_slip_direction_of_a_sliding_patch():
    """A patch sliding backwards along the rail at 0.8 m/s and sideways at 0.3 m/s in its
    tangent plane (contact angle 20 deg) has the mean slip (-0.8, 0.3) and the direction
    atan(0.3/0.8) = 20.6 deg against the negative longitudinal axis, as θ of the shear it
    drags the rail with; a node of another patch and an open time do not count."""
    import xarray as xr

    from wheelrail.fe.transition.analysis import shear_direction, slip_direction

    nt, nr, nc = 2, 3, 4
    phi = np.radians(20.0)              # the lateral tangent (0, cos φ, sin φ)
    sx, sl = -0.8, 0.3
    lab = np.ones((nt, nr, nc), np.int8)
    lab[0, 0, 0] = 2                    # the flange patch's node, sliding elsewhere
    lab[1] = 0                          # out of contact at the second time
    full = np.ones((nt, nr, nc))
    vx, vy, vz = sx * full, sl * np.cos(phi) * full, sl * np.sin(phi) * full
    vx[0, 0, 0], vy[0, 0, 0] = 5.0, -5.0
    q = 1e8 / np.hypot(sx, sl)          # Coulomb: the shear on the rail along the slip
    ds = xr.Dataset({n: (("time", "row", "col"), v) for n, v in (
        ("slip_x", vx), ("slip_y", vy), ("slip_z", vz), ("traction_x", q * vx),
        ("traction_y", q * vy), ("traction_z", q * vz), ("area", np.full((nt, nr, nc), 1e-6)),
        ("patch", lab))}, coords={"time": [0.0, 3e-6], "travel": ("time", [0.0, 6.7e-5])})
    sd = slip_direction(ds, patch=1)
    np.testing.assert_allclose(sd.slip_long.values[0], sx, rtol=1e-12)
    np.testing.assert_allclose(sd.slip_lat.values[0], sl, rtol=1e-12)
    assert sd.angle.values[0] == pytest.approx(np.degrees(np.arctan(0.3 / 0.8)), abs=1e-9)
    assert sd.n_nodes.values.tolist() == [nr * nc - 1, 0]
    assert np.isnan(sd.angle.values[1]) and np.isnan(sd.slip_long.values[1])
    assert sd.angle.values[0] == pytest.approx(shear_direction(ds, 1).mean_stress.values[0])
    assert sd.slip_long.attrs["units"] == "m/s"
    with pytest.raises(InputError, match="slip_y"):
        slip_direction(ds.drop_vars("slip_y"))
    with pytest.raises(InputError, match="patch"):
        slip_direction(ds, patch=0)


def test_fe_solve_runs_a_transition_case(tiny_transition):
    """One entry for every FE case: ``wr.fe.solve`` of a TransitionCase is
    ``run_transition`` of it (the same histories to the last digit), and its result prints
    as one line."""
    from wheelrail.fe.transition import run_transition

    case, model = tiny_transition
    a = wr.fe.solve(case, progress=False)
    b = run_transition(case, model=model)
    np.testing.assert_array_equal(a.u, b.u)
    np.testing.assert_array_equal(a.history["Fz_total"].values, b.history["Fz_total"].values)
    text = repr(a)
    assert text.startswith("TransitionResult(") and "\n" not in text and len(text) < 200
    with pytest.raises(wr.InputError, match="only rolls"):
        wr.fe.solve(case, mode="indent")
    with pytest.raises(wr.InputError, match="RollingCase or TransitionCase"):
        wr.fe.solve("case.toml")
