"""Shared setup of the transient tests at non-integer step ratios (private test helper).

Baeza et al. §3.1 ("Cattaneo to Carter", Table 1: F3 = 10 kN, F1 = 2 kN applied at
once, μ = 0.4, E = 210 GPa, ν = 0.3) on a reduced grid (``N`` = 16 elements over 2a)
so that the tests stay fast, and the measures the tests compare runs by. The time
discretisation error of the transient is O(h) (tests/convergence/
test_transient_convergence.py), so a history at a non-integer ratio dx/h must lie on
the interpolation in h between the runs at the neighbouring integer ratios.
Used by tests/reference/test_transient_step_ratio.py and
tests/transient/test_transient_second_order.py (fixture ``baeza_31`` in conftest.py).
"""

import numpy as np

import wheelrail as wr
from wheelrail.normal.bem import hertz_grid

#: elements over 2a
N = 16


def contact():
    """``(hc, dx)``: the Hertzian contact of Baeza et al. §3.1 and the element length of
    its ``N``-element grid [m]."""
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.Material(2.1e11, 0.3))
    grid, _ = hertz_grid(hc, elements=N)
    return hc, grid.dx


def run(hc, step, scheme, travel=3.0):
    """The force-controlled run (F1 = 2 kN) over ``travel`` semi-axes a."""
    return wr.transient_rolling(hc, travel=travel * float(hc.a), step=step, mu=0.4,
                                Fx=2000.0, elements=N, frames=2, scheme=scheme)


def integer_ratio_runs(hc, dx, ratios, scheme):
    """``{m: run at step dx/m}`` for the integer ratios ``m``."""
    return {m: run(hc, dx / m, scheme) for m in ratios}


def history_difference(r, runs, dx, ratio):
    """Largest |ξ − ξ_ref| / |ξ_ref(end)| after two elements of travel (after the Cattaneo
    start); ξ_ref interpolated linearly in h between the runs at the integer ratios
    ⌊dx/h⌋ and ⌈dx/h⌉, each interpolated to the travels of ``r``."""
    lo, hi = int(np.floor(ratio)), int(np.ceil(ratio))
    sel = r.x >= 2 * dx
    a, b = (np.interp(r.x[sel], runs[m].x, runs[m].xi) for m in (lo, hi))
    w = (1 / ratio - 1 / hi) / (1 / lo - 1 / hi)  # weight of the coarser step
    ref = w * a + (1 - w) * b
    return float(np.max(np.abs(r.xi[sel] - ref)) / abs(runs[hi].xi[-1]))


def worst_increment_before_peak(r):
    """Smallest step-to-step increase of |ξ| before its peak, relative to |ξ_end|
    (step 1, the Cattaneo shift, excluded)."""
    xi = np.abs(r.xi[2:])
    k = int(np.argmax(xi))
    return float(np.min(np.diff(xi[: k + 1])) / xi[-1])


def slip_fraction_difference(r, ref, dx):
    """Largest difference of the slipping fraction of the contact between ``r`` and the
    run ``ref`` at the same travel, after two elements of travel."""
    f = r.n_slip / np.maximum(r.n_contact, 1)
    f_ref = np.interp(r.x, ref.x, ref.n_slip / np.maximum(ref.n_contact, 1))
    return float(np.max(np.abs(f - f_ref)[r.x >= 2 * dx]))
