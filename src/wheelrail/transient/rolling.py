"""Transient rolling on a grid fixed to the contact, exact Coulomb friction (time stepping).

The wheel rolls a distance ``h = V Δt`` (the *step*, a parameter independent of
the element size) per time step. In the frame moving with the contact the rail
particles cross the grid from the leading edge (largest x) backwards, so the
particle at ``x`` at time t was at ``x + h`` one step earlier. With the
displacement difference ``u = u(wheel) − u(rail)`` of
:mod:`wheelrail.halfspace.influence` the slip of the wheel relative to the
rail, divided by V, is (Baeza et al. eqs. 2.8–2.10)::

    s(x) = w(x) + (u(x, t) − u(x + h, t − Δt)) / h,   w = (ξ − φ y, η + φ x),

and with the influence kernel ``C`` (eq. 2.13)::

    s = w + (C p + C_tn pn − C_h p_o) / h,          (Baeza et al., eq. 2.19)

where ``C_h`` is the influence kernel evaluated at the offsets shifted by
``h`` (exactly, from Love's rectangle formulae: no interpolation of the old
displacement) and ``p_o`` the tractions (tangential and normal) of the
previous step. Each step is one frictional problem ``s = b + (C/h) p`` with
the Coulomb bound ``μ pn``, solved by the stepping core shared with steady
rolling (:func:`wheelrail.tangential.exact.newton_step`). With ``h = dx``
and ``p_o = p`` this is exactly Kalker's discretised steady rolling, so a run
held at constant loads ends on :func:`~wheelrail.tangential.exact.solve_rolling`. The spin's
rigid slip φx is evaluated dx/6 upstream of each element centre, as in that solver
(Vollebregt's CONTACT, FACPHI = 1/6); at the centre a run held at constant spin ended
O(dx) off the steady solution (Fy 5 % at 12 elements).

For ``h < dx`` the slip at the element centres alone (``scheme="centre"``,
Baeza et al.'s eq. 2.10 as written) ends on a different steady problem, kernel
``(C − C_h)/h``, which tends to the centred derivative ``−∂C/∂x`` whose
self-coefficient vanishes: ill-conditioned and off Kalker's solution (−1.9 %
in ξ for Baeza et al. §3.1 at 30 elements). The default ``scheme="averaged"``
averages the slip relation over the points ``x_I + k h`` inside the element
length upstream of the centre (:func:`step_weights`); the carried
displacements then telescope, and held steady the run ends on Kalker's
discretisation for any ``h`` (:func:`step_kernels`).

Normal force varying along the travel: the normal problem is solved at every
step on the same grid (Polonsky–Keer, warm started); elements leaving the
contact get zero traction (bound ``μ pn = 0``), elements entering start
without traction but with the displacement carried from the previous step,
which keeps the tractions physical (Baeza et al., Fig. 1).

Prescribed tangential force F1(x): the longitudinal creepage ξ is the unknown
of each step, found by a safeguarded secant iteration on ``Fx(ξ) = F1`` (Fx
decreases monotonically with ξ).

References
----------
.. [1] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the
   wheel–rail contact instationary process on contact parameters (Baeza et al.),
   eqs. (2.5)–(2.13), (2.19)–(2.20), §3.1.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.2 (transient discretisation, steady state as its limit).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validation import as_float_array, integer, positive
from ..errors import ConvergenceError, InputError
from ..halfspace.influence import influence_kernel, kernel_offsets, rectangle_influence
from ..halfspace.rolling import _BlockConvolution
from ..materials import as_material_pair
from ..normal.bem import hertz_grid, solve_normal
from ..tangential.exact import newton_step
from ..tangential.exact._kernels import _SPIN_SHIFT
from .regularised import dense_block, regularised_step
from .strips import (
    DenseOperator,
    hertz_pressure,
    preconditioner_kernel,
    strip_grid,
    strip_step_operators,
)

__all__ = ["TransientResult", "transient_rolling"]

_SCALARS = ("xi", "eta", "phi", "Fn", "Fx", "Fy", "p_max", "penetration",
            "n_contact", "n_adhesion", "n_slip")
_UNITS = {"x": "m", "xi": "1", "eta": "1", "phi": "1/m", "Fn": "N", "Fx": "N", "Fy": "N",
          "p_max": "Pa", "penetration": "m", "n_contact": "1", "n_adhesion": "1", "n_slip": "1"}


@dataclass(frozen=True)
class TransientResult:
    """History of a transient rolling run (frozen).

    Attributes
    ----------
    x : ndarray, shape (n,)
        Travel of the contact [m] at the end of each step (``x[0] = 0``: the
        unloaded start, tangential tractions zero).
    history : dict of ndarray, shape (n,)
        ``xi, eta [-], phi [1/m]`` creepages, ``Fn, Fx, Fy`` [N] forces on the
        wheel, ``p_max`` [Pa], ``penetration`` [m], ``n_contact, n_adhesion,
        n_slip`` element counts.
    grid : Grid
        The grid fixed to the contact.
    frame_x : ndarray, shape (m,)
        Travel at the stored traction fields [m].
    px, py, pn : ndarray, shape (m, nx, ny)
        Tangential tractions on the wheel and pressure [Pa] at ``frame_x``.
    state : ndarray of int8, shape (m, nx, ny)
        0 out of contact, 1 adhesion, 2 slip.
    info : dict
        Parameters and solver counts (``newton``, ``krylov``: totals).
    """

    x: np.ndarray
    history: dict
    grid: object
    frame_x: np.ndarray
    px: np.ndarray
    py: np.ndarray
    pn: np.ndarray
    state: np.ndarray
    info: dict = field(default_factory=dict)

    def __getattr__(self, name):
        hist = object.__getattribute__(self, "history")
        if name in hist:
            return hist[name]
        raise AttributeError(name)

    @property
    def dataset(self):
        """``xarray.Dataset`` over ``x`` (travel, m) with the scalar histories (NetCDF-ready)."""
        import xarray as xr

        data = {k: ("x", np.asarray(v), {"units": _UNITS[k]}) for k, v in self.history.items()}
        attrs = {k: v for k, v in self.info.items() if isinstance(v, (int, float, str))}
        return xr.Dataset(data, coords={"x": ("x", self.x, {"units": "m",
                                                           "long_name": "travel"})},
                          attrs=attrs)

    @property
    def fields(self):
        """``xarray.Dataset`` of the stored traction fields over (frame, gx, gy)."""
        import xarray as xr

        g = self.grid
        dims = ("x_frame", "gx", "gy")
        coords = {"x_frame": self.frame_x, "gx": g.x, "gy": g.y}
        if hasattr(g, "area"):  # Paul–Hashemi strips: element centres differ per strip
            coords.update({"X": (("gx", "gy"), g.X, {"units": "m"}),
                           "Y": (("gx", "gy"), g.Y, {"units": "m"})})
        return xr.Dataset(
            {"px": (dims, self.px, {"units": "Pa"}), "py": (dims, self.py, {"units": "Pa"}),
             "pn": (dims, self.pn, {"units": "Pa"}),
             "state": (dims, self.state, {"meaning": "0 out, 1 adhesion, 2 slip"})},
            coords=coords)

    def fields_at(self, x):
        """Traction fields at the stored step nearest to travel ``x`` [m] (xarray.Dataset)."""
        x = float(as_float_array("x", x))
        if not (self.x[0] - 1e-12 <= x <= self.x[-1] + 1e-12):
            raise InputError(f"x = {x!r} m lies outside the travel [{self.x[0]}, {self.x[-1]}] m")
        k = int(np.argmin(np.abs(self.frame_x - x)))
        return self.fields.isel(x_frame=k)


def _as_function(name, value):
    """A function of travel x [m] -> float, from a constant or a callable."""
    if value is None:
        return None
    if callable(value):
        return value
    v = float(as_float_array(name, value))
    if not math.isfinite(v):
        raise InputError(f"{name} must be finite, got {value!r}")
    return lambda x, v=v: v


def _evaluate(name, fun, x):
    try:
        v = float(fun(x))
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name}({x!r}) did not return a number: {exc}") from exc
    if not math.isfinite(v):
        raise InputError(f"{name}({x!r} m) = {v!r} is not finite")
    return v


def shifted_influence_kernel(grid, materials, shift) -> np.ndarray:
    """Influence kernel at offsets shifted by ``shift`` along x, shape (3, 3, 2nx−1, 2ny−1).

    ``K[:, :, kx, ky]`` is the displacement difference [m/Pa] at
    ``((kx − nx + 1) dx + shift, (ky − ny + 1) dy)`` from an element carrying a
    unit traction: the displacement of the previous step seen by the particle
    now at element I (Baeza et al. eq. 2.10, ``u_o``).
    """
    pair = as_material_pair(materials)
    ox, oy = kernel_offsets(grid)
    X, Y = np.meshgrid(ox + shift, oy, indexing="ij")
    return rectangle_influence(X, Y, grid.dx / 2, grid.dy / 2, pair.G, pair.nu, pair.K)


def step_weights(dx, step):
    """Collocation offsets [m] and weights of the element-averaged slip (``scheme="averaged"``).

    With ``m = dx / step`` the slip of element I is the weighted mean of the
    slip at the points ``x_I + k·step``, ``k = 0 … ⌈m⌉ − 1``, weights ``1/m``
    except the last, ``(m − ⌈m⌉ + 1)/m`` (they sum to one). Held steady, the
    displacement differences telescope to ``(u(x_I) − ũ(x_I + dx)) / dx``
    with ``ũ`` the linear interpolation of ``u`` between the two last points:
    Kalker's steady discretisation, exactly when ``m`` is an integer. With
    ``step ≥ dx`` a single point (the element centre).

    Returns
    -------
    offsets, weights : ndarray, shape (K,)
    """
    m = dx / step
    K = max(1, int(math.ceil(m - 1e-9)))
    if K == 1:
        return np.zeros(1), np.ones(1)
    w = np.full(K, 1.0 / m)
    w[-1] = (m - (K - 1)) / m
    return np.arange(K) * step, w


def step_kernels(grid, materials, step, scheme="averaged"):
    """Influence kernels of one time step, each of shape (3, 3, 2nx−1, 2ny−1) [m/Pa].

    ``(now, old)``: the displacement difference at the collocation points of
    element I due to a unit traction on element J now (``now``) and, carried
    one step ``h = step`` upstream, at the previous step (``old``)::

        s_I = w_I + Σ_J (now(I − J) p_J − old(I − J) p_old,J) / h

    ``scheme="centre"``: Baeza et al.'s eq. (2.10) at the element centres,
    ``now = C`` and ``old = C`` at offsets shifted by ``h``
    (:func:`shifted_influence_kernel`). ``scheme="averaged"``: the slip
    averaged over the points of :func:`step_weights`; every kernel is
    evaluated exactly with Love's rectangle formulae (no interpolation of
    tractions or displacements).

    Why the average: held steady, the centre scheme becomes the steady
    problem with kernel ``(C − C_h)/h → −∂C/∂x`` at the element centres,
    whose self-coefficient vanishes as ``h/dx → 0`` (the derivative of the
    displacement of a uniformly loaded rectangle at its centre is zero). That
    steady problem is a centred difference and loses its diagonal dominance:
    the Newton iteration stops converging for ``dx/h ≳ 4`` on 30 elements
    (measured) and the transient run ends off Kalker's steady solution
    (−1.9 % in ξ at 30 elements, V·Δt = 0.05 mm). The averaged scheme ends
    on Kalker's upwind discretisation (:func:`~wheelrail.halfspace.solve_rolling`)
    for any step (exactly for integer ``dx/h``; 0.04 % in the force at
    ``dx/h = 3.7``).
    """
    if scheme == "centre":
        return influence_kernel(grid, materials), shifted_influence_kernel(grid, materials, step)
    if scheme != "averaged":
        raise InputError(f"scheme must be 'averaged' or 'centre', got {scheme!r}")
    offsets, weights = step_weights(grid.dx, step)
    now = sum(w * shifted_influence_kernel(grid, materials, s) for s, w in zip(offsets, weights))
    old = sum(w * shifted_influence_kernel(grid, materials, s + step)
              for s, w in zip(offsets, weights))
    return now, old


def transient_rolling(contact, *, travel, step, mu, Fn=None, creepage=None,
                      Fx=None, friction="exact", epsilon=None, elements=30,
                      margin=1.25, tol=1e-8, maxiter=100, force_tol=1e-7, frames=100,
                      progress=False, scheme="averaged", penetration=None,
                      discretisation="uniform", strips=None) -> TransientResult:
    """Transient (instationary) rolling of a Hertzian contact by time stepping.

    Parameters
    ----------
    contact : HertzContact
        Defines the surfaces (curvatures A, B), the materials and, unless
        ``Fn`` is given, the normal load.
    travel : float
        Rolling distance [m], > 0.
    step : float
        Rolling distance per time step ``V Δt`` [m], > 0 and shorter than the
        contact length 2a.
    mu : float
        Friction coefficient [-], > 0.
    Fn : float or callable, optional
        F3(x) [N] (> 0), a constant or a function of travel x [m]; default the
        contact's load. A non-constant function solves the normal problem at
        every step.
    creepage : sequence of 3 (float or callable), optional
        (ξ [-], η [-], φ [1/m]) as constants or functions of travel [m].
        With ``Fx`` the first entry must be None (ξ is unknown).
    Fx : float or callable, optional
        F1(x) [N] on the wheel (Kalker's convention: positive creepage gives a
        negative force); ξ becomes the unknown of each step.
    friction : {"exact", "regularised"}
        ``"exact"``: Coulomb's law with the adhesion/slip split (Baeza et al., eq. 2.20),
        active-set Newton; ``"regularised"``: the smooth law of eq. (2.21)
        solved by Newton–Raphson (eq. 2.22), dense over the contact elements
        (:mod:`wheelrail.transient.regularised`); its ``n_slip`` counts
        elements with ``|s| > ε``.
    epsilon : float, optional
        Regularisation slip ε [-] (slip velocity / V) of ``"regularised"``, > 0.
    elements : int
        Elements across 2a (and 2b) of the contact at the first step; the
        grid is fixed to the contact and keeps its size.
    margin : float
        Grid half-width in semi-axes (> 1); room for a growing contact.
    tol : float
        Newton tolerance of each step (relative slip residual).
    maxiter : int
        Newton iterations per step.
    force_tol : float
        Tolerance of ``|Fx − F1|`` relative to μ·Fn (force control).
    frames : int
        Number of traction fields stored (evenly spread, plus the last step).
    progress : bool
        Show a rich progress bar.
    scheme : {"averaged", "centre"}
        Collocation of the slip (:func:`step_kernels`): ``"averaged"``
        (default) averages the slip over the element's upstream points so that
        a run held at constant loads ends on Kalker's steady discretisation
        for any step; ``"centre"`` is Baeza et al.'s eq. (2.10) at the element
        centres (accurate only for ``step = dx``).
    penetration : float or callable, optional
        Prescribed penetration δ(x) [m] (> 0) instead of ``Fn``
        (normal control by penetration): the normal problem is solved for the
        penetration at every step.
    discretisation : {"uniform", "strips", "material"}
        ``"uniform"``: the grid of :func:`~wheelrail.normal.bem.hertz_grid`
        moving with the contact (FFT operators). ``"material"``: the same
        grid fixed to the rail (a window that follows the contact in whole
        elements): each particle keeps its element, the carried displacement
        is ``C p_old`` without shift, the rigid slip is taken about the moving
        contact centre, and the normal problem is solved every step for the
        moved gap; held steady it oscillates with period ``dx/h`` steps. ``"strips"``: Paul–Hashemi (Baeza et al., Fig. 2,
        :mod:`wheelrail.transient.strips`): ``strips`` strips along x over the
        Hertz ellipse with ``elements`` elements each, Hertz pressure, dense
        operators; constant normal force and exact friction only.
    strips : int, optional
        Number of strips (default ``elements``).

    Returns
    -------
    TransientResult

    Raises
    ------
    InputError
        A step not in (0, 2a), a load or penetration function that is not
        positive at some step (checked before the run, naming the travel and
        value), ``|F1| ≥ μ F3`` (the wheel would slide), an unknown friction
        law or scheme, both ``Fn`` and ``penetration``.
    ConvergenceError
        A step whose frictional problem or force iteration fails.

    References
    ----------
    Baeza et al. eqs. (2.8)–(2.13), (2.19)–(2.20); Kalker (1990) §5.2.
    """
    if friction == "regularized":
        friction = "regularised"
    if friction == "regularised":
        if epsilon is None:
            raise InputError("friction='regularised' needs epsilon= (regularisation slip, > 0)")
        epsilon = float(as_float_array("epsilon", epsilon))
        if not epsilon > 0:
            raise InputError(f"epsilon must be > 0, got {epsilon!r}")
    elif friction != "exact":
        raise InputError(f"friction must be 'exact' or 'regularised', got {friction!r}")
    pair = as_material_pair(contact.materials)
    mu = float(positive("mu", mu))
    travel = float(positive("travel", travel))
    h = float(positive("step", step))
    elements = integer("elements", elements, 2)
    frames = integer("frames", frames, 1)
    tol = float(positive("tol", tol))
    force_tol = float(positive("force_tol", force_tol))
    a = float(contact.a)
    if not h < 2 * a:
        raise InputError(f"step = {h!r} m must be shorter than the contact length "
                         f"2a = {2 * a!r} m")
    if h > travel:
        raise InputError(f"step = {h!r} m is longer than travel = {travel!r} m")
    if Fn is not None and penetration is not None:
        raise InputError("give Fn= or penetration= (normal control), not both")
    if penetration is not None:
        F3 = _as_function("penetration", penetration)
        normal_name, normal_unit = "penetration", "m"
        F3_const = not callable(penetration)
    else:
        F3 = _as_function("Fn", float(contact.Fn) if Fn is None
                          else Fn)
        normal_name, normal_unit = "Fn", "N"
        F3_const = not callable(Fn)
    if Fx is not None:
        F1 = _as_function("Fx", Fx)
        if creepage is None:
            creepage = (None, 0.0, 0.0)
        if len(creepage) != 3 or creepage[0] is not None:
            raise InputError("with Fx, creepage must be (None, eta, phi): "
                             f"xi is the unknown; got {creepage!r}")
        cr = (None,) + tuple(_as_function(n, c) for n, c in zip(("eta", "phi"), creepage[1:]))
    else:
        F1 = None
        if creepage is None or len(creepage) != 3 or any(c is None for c in creepage):
            raise InputError(f"give creepage=(xi, eta, phi) or Fx=, got "
                             f"creepage={creepage!r}")
        cr = tuple(_as_function(n, c) for n, c in zip(("xi", "eta", "phi"), creepage))

    n = int(math.floor(travel / h + 1e-9)) + 1
    xs = np.arange(n) * h
    # every load function is checked at every step before the run: a load that turns
    # negative (or not finite) is named with its travel instead of failing mid-run
    for name, fun in ((normal_name, F3), ("Fx", F1)) + tuple(
            zip(("xi", "eta", "phi"), cr)):
        if fun is None:
            continue
        vals = np.array([_evaluate(name, fun, float(x)) for x in xs])
        if name == normal_name and not np.all(vals > 0):
            k = int(np.argmax(~(vals > 0)))
            raise InputError(f"{name}(x = {xs[k]!r} m) = {vals[k]!r} {normal_unit} must be > 0 "
                             f"(the load function goes non-positive along the travel)")
        if name == normal_name:
            normal_vals = vals
        if name == "Fx" and penetration is None:
            bad = np.nonzero(~(np.abs(vals) < mu * normal_vals))[0]
            if bad.size:
                k = int(bad[0])
                raise InputError(f"Fx(x = {xs[k]!r} m) = {vals[k]!r} N must be "
                                 f"smaller in magnitude than mu*Fn = "
                                 f"{mu * normal_vals[k]!r} N (full sliding)")

    if scheme not in ("averaged", "centre"):
        raise InputError(f"scheme must be 'averaged' or 'centre', got {scheme!r}")
    if discretisation == "strips":
        if not F3_const or penetration is not None:
            raise InputError("discretisation='strips' (Paul–Hashemi) needs a constant "
                             "Fn (the strips follow the Hertz ellipse)")
        if friction != "exact":
            raise InputError("discretisation='strips' supports friction='exact' only")
        if scheme != "averaged":
            raise InputError("discretisation='strips' uses scheme='averaged'")

        strips = integer("strips", elements if strips is None else strips, 2)
        grid = strip_grid(contact, elements, strips)
        X, Y = grid.X, grid.Y
        dA = np.array(grid.area)
        Nw, Ow = strip_step_operators(grid, pair, h, step_weights)
        nflat = grid.nx * grid.ny
        K_now = preconditioner_kernel(Nw / h, grid)
        conv_now = DenseOperator(Nw[:, :2 * nflat] / h, grid.shape)
        conv_old = DenseOperator(Ow, grid.shape)
        conv_n = DenseOperator(Nw[:, 2 * nflat:], grid.shape) if pair.K else None
        strip_pn = hertz_pressure(contact, grid, _evaluate(normal_name, F3, 0.0))

        class _HertzNormal:
            pressure = strip_pn
            penetration = float(np.asarray(contact.penetration))
    elif discretisation in ("uniform", "material"):
        grid, gap = hertz_grid(contact, elements=elements, margin=margin)
        X, Y = grid.X, grid.Y
        dA = grid.element_area
        if discretisation == "material":
            # grid fixed to the rail (a window moved in whole elements): the particle
            # stays on its element, so the carried displacement is C p_old unshifted
            C = influence_kernel(grid, pair)
            Ch = C
        else:
            C, Ch = step_kernels(grid, pair, h, scheme)
        K_now = np.ascontiguousarray(C[:2, :2] / h)
        conv_now = _BlockConvolution(K_now)
        conv_old = _BlockConvolution(Ch[:2, :])
        conv_n = _BlockConvolution(C[:2, 2:3]) if pair.K else None
    else:
        raise InputError(f"discretisation must be 'uniform', 'strips' or 'material', got "
                         f"{discretisation!r}")
    material = discretisation == "material"
    centre = 0.0  # material grid: contact centre relative to the window centre [m]
    A_, B_ = float(contact.A), float(contact.B)

    hist = {k: np.zeros(n) for k in _SCALARS}
    keep = set(np.unique(np.linspace(0, n - 1, min(frames, n)).round().astype(int)).tolist())
    keep.add(n - 1)
    keep = sorted(keep)
    nxy = grid.shape
    store = {k: np.zeros((len(keep),) + nxy) for k in ("px", "py", "pn")}
    state_store = np.zeros((len(keep),) + nxy, dtype=np.int8)

    def normal(x, initial):
        F = _evaluate(normal_name, F3, x)
        if discretisation == "strips":
            return _HertzNormal
        if material:
            gap_c = A_ * (X - centre) ** 2 + B_ * Y ** 2
            if penetration is not None:
                return solve_normal(grid, gap_c, pair, penetration=F, initial=initial)
            return solve_normal(grid, gap_c, pair, Fn=F, initial=initial)
        if penetration is not None:
            return solve_normal(grid, gap, pair, penetration=F, initial=initial)
        return solve_normal(grid, gap, pair, Fn=F, initial=initial)

    nsol = normal(0.0, None)
    pn = np.array(nsol.pressure)
    p = np.zeros((2,) + nxy)
    total_newton = total_krylov = total_solves = 0

    dense_cache = {}

    def dense_for(mask):
        key = mask.tobytes()
        if key not in dense_cache:
            dense_cache.clear()
            ii, jj = np.nonzero(mask)
            dense_cache[key] = dense_block(K_now, ii, jj)
        return dense_cache[key]

    def record(k, x, pn, p, s, nsol, xi, eta, phi):
        g = mu * pn
        contact_ = pn > 0
        norm = np.hypot(p[0], p[1])
        if friction == "regularised":  # no sharp split: slip where |s| > ε (|p| > g/2)
            slip = contact_ & (np.hypot(s[0], s[1]) > epsilon)
        else:
            slip = contact_ & (norm >= g * (1 - 1e-9)) & (np.hypot(s[0], s[1]) > 0)
        hist["xi"][k], hist["eta"][k], hist["phi"][k] = xi, eta, phi
        hist["Fn"][k] = float((pn * dA).sum())
        hist["Fx"][k] = float((p[0] * dA).sum())
        hist["Fy"][k] = float((p[1] * dA).sum())
        hist["p_max"][k] = float(pn.max())
        hist["penetration"][k] = float(nsol.penetration)
        hist["n_contact"][k] = int(contact_.sum())
        hist["n_slip"][k] = int(slip.sum())
        hist["n_adhesion"][k] = int(contact_.sum() - slip.sum())
        if k in keep:
            j = keep.index(k)
            store["px"][j], store["py"][j], store["pn"][j] = p[0], p[1], pn
            state_store[j] = np.where(slip, 2, np.where(contact_, 1, 0))

    record(0, 0.0, pn, p, np.zeros_like(p), nsol, 0.0 if F1 else _evaluate("xi", cr[0], 0.0),
           _evaluate("eta", cr[1], 0.0), _evaluate("phi", cr[2], 0.0))

    xi_prev, slope = 0.0, None
    fixed = None  # (loads, tractions, xi, slip) of a step that reproduced its input
    skipped = 0
    # the averaged scheme couples each element strongly to its upstream neighbour:
    # precondition with that coupling (the line solve of newton_step)
    upwind = scheme == "averaged"
    bar = None
    if progress:
        from rich.progress import Progress
        bar = Progress(transient=True)
        bar.start()
        task = bar.add_task("transient rolling", total=n - 1)
    try:
        for k in range(1, n):
            x = xs[k]
            if material:
                # the contact moves by h over the rail-fixed elements; the window follows
                # in whole elements (tractions and pressure move back by one index)
                centre += h
                while centre >= 0.5 * grid.dx * (1 - 1e-12):
                    p = np.concatenate((p[:, 1:], np.zeros((2, 1, grid.ny))), axis=1)
                    pn = np.concatenate((pn[1:], np.zeros((1, grid.ny))), axis=0)
                    centre -= grid.dx
            if not F3_const or material:
                nsol = normal(x, pn)
            pn_new = np.array(nsol.pressure)
            g = mu * pn_new
            eta, phi = _evaluate("eta", cr[1], x), _evaluate("phi", cr[2], x)
            control = (_evaluate("xi", cr[0], x) if F1 is None
                       else _evaluate("Fx", F1, x))
            key = (eta, phi, control)
            if (fixed is not None and not material and fixed[0] == key and np.array_equal(fixed[1], p)
                    and np.array_equal(pn, pn_new)):
                # the previous step reproduced its input exactly under the same loads: the
                # run has reached its steady fixed point and every such step repeats it
                xi = fixed[2]
                record(k, x, pn_new, p, fixed[3], nsol, xi, eta, phi)
                skipped += 1
                if bar is not None:
                    bar.advance(task)
                continue
            p_in = p
            carried = conv_old(np.concatenate((p, pn[None])))
            base = -carried / h
            if conv_n is not None:
                base = base + conv_n(pn_new[None]) / h
            base[0] -= phi * Y
            # the spin's rigid slip phi x is collocated _SPIN_SHIFT dx upstream of the element
            # centre, as in the steady solver: held steady the run ends on its solution
            base[1] += eta + phi * (X - centre + _SPIN_SHIFT * grid.dx)

            def solve(xi, p0):
                nonlocal total_newton, total_krylov, total_solves
                b = base.copy()
                b[0] += xi
                if friction == "regularised":
                    mask = g > 0
                    Kd = dense_for(mask)
                    pp = np.zeros((2,) + nxy)
                    qc, sc, its = regularised_step(Kd, b[:, mask], g[mask], epsilon,
                                                   p0[:, mask], tol=tol, maxiter=maxiter)
                    pp[:, mask] = qc
                    ss = b + conv_now(pp)
                    total_newton += its
                    total_solves += 1
                    return pp, ss
                pp, ss, its, res, kry = newton_step(K_now, b, g, conv=conv_now, initial=p0,
                                                    tol=tol, maxiter=maxiter, upwind=upwind)
                total_newton += its
                total_krylov += kry
                total_solves += 1
                if not res <= tol:
                    raise ConvergenceError(f"step {k} (x = {x!r} m, xi = {xi!r}): the "
                                           f"frictional problem did not converge "
                                           f"(residual {res:.2e} > tol={tol:.1e})")
                return pp, ss

            if F1 is None:
                xi = control
                p_new, s_new = solve(xi, p)
            else:
                target = control
                Fn_k = float((pn_new * dA).sum())
                if not abs(target) < mu * Fn_k:
                    raise InputError(f"Fx({x!r} m) = {target!r} N must be smaller "
                                     f"in magnitude than mu*Fn = {mu * Fn_k!r} N (full sliding)")
                xi, p_new, s_new, slope = _xi_for_force(solve, target, xi_prev, slope, p, dA,
                                                        force_tol * mu * Fn_k, k, x)
                xi_prev = xi
            fixed = (key, p_in, xi, s_new) if np.array_equal(p_new, p_in) else None
            p, pn = p_new, pn_new
            record(k, x, pn, p, s_new, nsol, xi, eta, phi)
            if bar is not None:
                bar.advance(task)
    finally:
        if bar is not None:
            bar.stop()
    for d in (hist, store):
        for v in d.values():
            v.setflags(write=False)
    state_store.setflags(write=False)
    frame_x = xs[keep]
    frame_x.setflags(write=False)
    xs.setflags(write=False)
    info = {"step": h, "mu": mu, "elements": elements, "nx": grid.nx, "ny": grid.ny,
            "dx": float(np.max(grid.dx)), "dy": grid.dy, "discretisation": discretisation, "a": a, "b": float(contact.b), "friction": friction,
            "epsilon": float(epsilon) if epsilon is not None else float("nan"),
            "newton": total_newton, "krylov": total_krylov, "solves": total_solves,
            "steady_steps": skipped,
            "control": "force" if F1 is not None else "creepage"}
    return TransientResult(x=xs, history=hist, grid=grid, frame_x=frame_x, px=store["px"],
                           py=store["py"], pn=store["pn"], state=state_store, info=info)


def _xi_for_force(solve, target, xi0, slope, p0, dA, ftol, k, x, maxit=50):
    """ξ with ``Fx(ξ) = target``: secant steps kept inside a bracket (Illinois)."""
    def F(xi, p_init):
        pp, ss = solve(xi, p_init)
        return float((pp[0] * dA).sum()) - target, pp, ss

    fa, pa, sa = F(xi0, p0)
    if abs(fa) <= ftol:
        return xi0, pa, sa, slope
    xa = xi0
    lo = hi = None  # brackets: (xi, f) with f > 0 (lo: xi too small) and f < 0
    if fa > 0:
        lo = (xa, fa)
    else:
        hi = (xa, fa)
    s = slope if (slope is not None and slope < 0) else None
    best = (xa, fa, pa, sa)
    for _ in range(maxit):
        if s is not None:
            xn = best[0] - best[1] / s
        else:
            xn = best[0] + 1e-6 * math.copysign(1.0, best[1])
        if lo is not None and hi is not None and not (lo[0] < xn < hi[0]):
            xn = (lo[0] * hi[1] - hi[0] * lo[1]) / (hi[1] - lo[1])  # regula falsi
            if not (lo[0] < xn < hi[0]):
                xn = 0.5 * (lo[0] + hi[0])
        fn, pn_, sn = F(xn, best[2])
        if xn != best[0] and fn != best[1]:
            s_new = (fn - best[1]) / (xn - best[0])
            s = s_new if s_new < 0 else s
        if abs(fn) <= ftol:
            return xn, pn_, sn, s
        if fn > 0:
            lo = (xn, fn) if lo is None or xn > lo[0] else lo
        else:
            hi = (xn, fn) if hi is None or xn < hi[0] else hi
        if lo is None or hi is None:
            # still unbracketed: move further in the right direction
            if s is None:
                s = -1.0
        best = (xn, fn, pn_, sn) if abs(fn) < abs(best[1]) or True else best
    raise ConvergenceError(f"step {k} (x = {x!r} m): no creepage found giving "
                           f"Fx = {target!r} N in {maxit} iterations")
