"""Automatic potential contact area (wheelrail.contact.window) against closed forms.

References
----------
- Hertz: K.L. Johnson, *Contact Mechanics* (1985) eqs. (3.64)–(3.66), implemented
  independently in ``wheelrail.hertz`` / ``wheelrail.hertz_from_penetration``.
- Second moment of the Hertz pressure p0·√(1 − x²/a² − y²/b²): ∫x² p dA / ∫p dA = a²/5
  (direct integration), used to read the semi-axes off the grid pressure.
- Interaction of two distant patches: Boussinesq's point-load displacement
  u_n = P / (π E* d) of both surfaces at distance d (Johnson 1985 eq. 3.22 with the
  combined modulus) lowers the effective approach of the other patch; with Hertz
  P ∝ δ^{3/2} and δ = a²/R, P = 4E*a³/(3R), the relative load change of each patch is
  ΔP/P ≈ −(3/2)·(4/(3π))·a/d = −(2/π)·a/d.
"""

import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError, NoContactError
from wheelrail.normal.bem import ContactTruncatedWarning, solve_normal
from wheelrail.halfspace import Grid
from wheelrail.contact import contact_patches, potential_contact_grid, solve_gap_auto
from wheelrail.tangential.exact import solve_gap

STEEL = wr.Material(2.1e11, 0.28)
# wheel rolling radius 0.46 m, rail crown radius 0.15 m (flat wheel profile)
A, B = 0.5 / 0.46, 0.5 / 0.15
LOAD = 60e3
OFFSET = 1e-4      # arbitrary datum of the gap: h_min ≠ 0 must not matter for load control


def hertz_gap(x, y):
    return A * x**2 + B * y**2 + OFFSET


def semi_axes_from_moments(sol):
    """a, b [m] from the second moments of the pressure (a² = 5 <x²> for Hertz)."""
    p, X, Y = sol.pressure, sol.grid.X, sol.grid.Y
    w = p.sum()
    xc, yc = (p * X).sum() / w, (p * Y).sum() / w
    return (np.sqrt(5 * (p * (X - xc) ** 2).sum() / w),
            np.sqrt(5 * (p * (Y - yc) ** 2).sum() / w))


def test_hertzian_gap_with_prescribed_load():
    hc = wr.hertz(LOAD, A, B, STEEL)
    sol = solve_gap_auto(hertz_gap, STEEL, Fn=LOAD, elements=60)
    n = sol.normal
    assert not n.truncated
    assert n.info["window_enlargements"] == 0
    assert n.info["contact_patches"] == 1
    # window: odd counts, element aspect ~1, 61 elements along the longer (x) side
    g = sol.grid
    assert g.nx == 61 and g.nx % 2 == 1 and g.ny % 2 == 1
    assert g.dx / g.dy == pytest.approx(1.0, abs=0.05)
    # the window contains the rigid interpenetration region x² A < δ times the margin
    assert g.bounds[1] >= 1.2 * np.sqrt(hc.penetration / A) * (1 - 1e-9)
    a, b = semi_axes_from_moments(n)
    assert a == pytest.approx(hc.a, rel=0.02)
    assert b == pytest.approx(hc.b, rel=0.02)
    assert n.p_max == pytest.approx(hc.p0, rel=0.02)
    assert n.penetration - OFFSET == pytest.approx(hc.penetration, rel=0.02)
    # the Hertz estimate of the approach used for the window is exact for this gap
    assert n.info["approach_estimate"] - OFFSET == pytest.approx(hc.penetration, rel=1e-3)


def test_potential_contact_grid_rotated_hertzian_gap():
    """Principal curvatures are found when the ellipse is not aligned with x, y."""
    th = 0.4
    c, s = np.cos(th), np.sin(th)

    def h(x, y):
        u, v = c * x + s * y, -s * x + c * y
        return A * u**2 + B * v**2

    hc = wr.hertz(LOAD, A, B, STEEL)
    grid, h0 = potential_contact_grid(h, Fn=LOAD, materials=STEEL, elements=45)
    assert h0.shape == grid.shape
    sol = solve_normal(grid, h0, STEEL, Fn=LOAD)
    assert not sol.truncated
    assert sol.p_max == pytest.approx(hc.p0, rel=0.02)
    assert sol.penetration == pytest.approx(hc.penetration, rel=0.02)


def test_small_margin_is_enlarged_until_untruncated():
    generous = solve_gap_auto(hertz_gap, STEEL, Fn=LOAD, margin=1.2)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ContactTruncatedWarning)
        small = solve_gap_auto(hertz_gap, STEEL, Fn=LOAD, margin=0.5)
    assert not small.normal.truncated
    assert small.normal.info["window_enlargements"] >= 1
    # the first (margin 0.5) window was indeed too small: it truncates the contact
    grid0, h0 = potential_contact_grid(hertz_gap, Fn=LOAD, materials=STEEL, margin=0.5)
    with pytest.warns(ContactTruncatedWarning):
        assert solve_normal(grid0, h0, STEEL, Fn=LOAD).truncated
    assert small.Fn == pytest.approx(generous.Fn, rel=1e-9)
    assert small.normal.p_max == pytest.approx(generous.normal.p_max, rel=0.005)
    assert small.normal.penetration == pytest.approx(generous.normal.penetration, rel=0.005)


def test_still_truncated_after_max_enlarge_warns_with_sizes():
    with pytest.warns(ContactTruncatedWarning, match=r"after 0 enlargement.*61x\d+ elements"):
        sol = solve_gap_auto(hertz_gap, STEEL, Fn=LOAD, margin=0.5, max_enlarge=0)
    assert sol.normal.truncated


def test_two_separated_bumps_give_two_patches():
    """Tread + flange like gap: min of two shifted quadratics, prescribed penetration.

    Separation d = 40 a (a = 1 mm): the Boussinesq interaction lowers each patch
    load by ≈ (2/π) a/d = 1.6 % (module docstring), below the 3 % of the claim.
    One window covers both patches; the element size is the same along x and y,
    so the window is long and narrow (401 × 31 elements, still small).
    """
    R = 0.5
    delta = 2e-6
    hc = wr.hertz_from_penetration(delta, 1 / (2 * R), 1 / (2 * R), STEEL)
    a = float(hc.a)
    d = 40 * a

    def single(x, y):
        return (x**2 + (y - d / 2) ** 2) / (2 * R)

    def gap(x, y):
        return np.minimum(single(x, y), (x**2 + (y + d / 2) ** 2) / (2 * R))

    search = (-5 * a, 5 * a, -d / 2 - 5 * a, d / 2 + 5 * a)
    sol = solve_gap_auto(gap, STEEL, penetration=delta, elements=400, search=search)
    g = sol.grid
    assert not sol.normal.truncated
    r_rigid = np.sqrt(2 * R * delta)      # radius of {h < δ} around each bump
    assert g.bounds[2] < -d / 2 - r_rigid and g.bounds[3] > d / 2 + r_rigid
    labels, loads = contact_patches(sol)
    assert sol.normal.info["contact_patches"] == 2 == loads.size
    assert set(np.unique(labels)) == {0, 1, 2}
    assert loads.sum() == pytest.approx(sol.Fn, rel=1e-12)
    # one patch on each side
    ys = [g.Y[labels == k].mean() for k in (1, 2)]
    assert min(ys) == pytest.approx(-d / 2, abs=g.dy) and max(ys) == pytest.approx(d / 2, abs=g.dy)
    # single bump at the same penetration, same element size and same element offset
    k = (d / 2 - g.y0) / g.dy
    ny1 = g.nx + (g.nx + 1) % 2
    g1 = Grid(g.x0, d / 2 - (k - np.floor(k) + ny1 // 2) * g.dy, g.dx, g.dy, g.nx, ny1)
    alone = solve_normal(g1, single(g1.X, g1.Y), STEEL, penetration=delta)
    assert not alone.truncated
    for load in loads:
        assert load == pytest.approx(alone.Fn, rel=0.03)
        # and the difference is the (small) interaction, of the predicted size and sign
        assert load / alone.Fn - 1 == pytest.approx(-2 / np.pi * a / d, rel=0.25)
    assert alone.Fn == pytest.approx(hc.Fn, rel=0.03)


def test_real_profiles_window_contains_the_contact():
    """S1002 wheel on 60E1 rail (y = 6 mm): gap from geometry.separation via an
    interpolant; the auto window must hold the whole contact, i.e. a window larger
    by 8 elements on each side (same elements) gives the same pressure."""
    from scipy.interpolate import RegularGridInterpolator

    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    sep = wr.geometry.separation(ws, tr, 0.006)
    x = np.linspace(-0.02, 0.02, 81)
    f = RegularGridInterpolator((x, sep.eta), sep.distance(x), method="cubic")

    def gap(X, Y):
        return f(np.stack([X, Y], -1))

    search = (x[0], x[-1], sep.eta[0], sep.eta[-1])
    sol = solve_gap_auto(gap, STEEL, Fn=LOAD, search=search)
    g = sol.grid
    assert not sol.normal.truncated and sol.normal.info["contact_patches"] == 1
    big = Grid(g.x0 - 8 * g.dx, g.y0 - 8 * g.dy, g.dx, g.dy, g.nx + 16, g.ny + 16)
    ref = solve_normal(big, gap(big.X, big.Y), STEEL, Fn=LOAD)
    assert np.abs(ref.pressure[8:-8, 8:-8] - sol.pressure).max() < 1e-4 * ref.p_max
    assert sol.normal.penetration == pytest.approx(ref.penetration, rel=1e-5)


def test_rolling_problem_on_the_auto_window():
    """creepage/mu are passed to solve_gap; at small creepage Fx tends to Kalker's linear
    theory (Fx = −G c² C11 ξ, ``wr.creep_forces(method="linear")``); 31 elements: ~4 %."""
    xi = 1e-4
    sol = solve_gap_auto(hertz_gap, STEEL, Fn=LOAD, creepage=(xi, 0.0, 0.0), mu=0.3, elements=31)
    assert sol.tangential is not None and not sol.normal.truncated
    same = solve_gap(sol.grid, hertz_gap(sol.grid.X, sol.grid.Y), STEEL, Fn=LOAD,
                     creepage=(xi, 0.0, 0.0), mu=0.3)
    assert sol.Fx == pytest.approx(same.Fx, rel=1e-12)
    linear = wr.creep_forces(wr.hertz(LOAD, A, B, STEEL), (xi, 0.0, 0.0), 0.3, method="linear")
    assert sol.Fx == pytest.approx(float(linear.Fx), rel=0.06)


def test_contact_patches_of_a_known_mask():
    class Fake:
        grid = Grid.from_bounds(0, 5, 0, 4, nx=5, ny=4)
        contact = np.array([[1, 1, 0, 0], [0, 0, 0, 1], [0, 0, 0, 1], [1, 0, 0, 0],
                            [0, 1, 0, 0]], dtype=bool)     # (3,0), (4,1) touch diagonally only
        pressure = np.where(contact, 1.0, 0.0) * np.arange(1, 5)[None, :]

    labels, loads = contact_patches(Fake)
    assert loads.tolist() == [8.0, 3.0, 2.0, 1.0]      # decreasing: {(1,3),(2,3)}, {(0,0),(0,1)}, ...
    assert labels[1, 3] == labels[2, 3] == 1 and labels[0, 0] == labels[0, 1] == 2
    assert labels[4, 1] == 3 and labels[3, 0] == 4 and (labels[~Fake.contact] == 0).all()


# --------------------------------------------------------------------------- errors
def test_no_contact_names_minimum_and_penetration():
    with pytest.raises(NoContactError, match=r"minimum gap 0\.0001 m.*penetration 5e-05 m"):
        potential_contact_grid(hertz_gap, penetration=5e-5)
    with pytest.raises(NoContactError):
        solve_gap_auto(hertz_gap, STEEL, penetration=5e-5)


def test_search_box_without_the_minimum():
    with pytest.raises(InputError, match="boundary"):
        potential_contact_grid(hertz_gap, penetration=2e-4, search=(0.005, 0.02, -0.01, 0.01))


def test_search_box_too_small_for_the_contact():
    with pytest.raises(InputError, match="reaches the .* edge of the search box"):
        potential_contact_grid(hertz_gap, penetration=2e-4, search=(-0.004, 0.004, -0.01, 0.01))


@pytest.mark.parametrize("kwargs, match", [
    ({"Fn": LOAD}, "materials"),
    ({"Fn": LOAD, "penetration": 1e-4, "materials": STEEL}, "exactly one"),
    ({"materials": STEEL}, "exactly one"),
    ({"Fn": -1.0, "materials": STEEL}, "Fn"),
    ({"penetration": 2e-4, "margin": 0.0}, "margin"),
    ({"penetration": 2e-4, "elements": 2}, "elements"),
    ({"penetration": 2e-4, "search": (0.01, -0.01, -0.01, 0.01)}, "search"),
    ({"penetration": 2e-4, "search": (0.0, 1.0)}, "search"),
])
def test_argument_errors(kwargs, match):
    with pytest.raises(InputError, match=match):
        potential_contact_grid(hertz_gap, **kwargs)


def test_gap_must_be_a_vectorised_callable():
    with pytest.raises(InputError, match="callable"):
        potential_contact_grid(np.zeros((3, 3)), penetration=1e-5)
    with pytest.raises(InputError, match="shape"):
        potential_contact_grid(lambda x, y: np.zeros(3), penetration=1e-5)
    with pytest.raises(InputError, match="finite"):
        potential_contact_grid(lambda x, y: x * np.nan, penetration=1e-5)
    with pytest.raises(InputError, match="max_enlarge"):
        solve_gap_auto(hertz_gap, STEEL, Fn=LOAD, max_enlarge=-1)
