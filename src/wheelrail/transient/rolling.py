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
in ξ for Baeza et al. §3.1 at 30 elements). The default ``scheme="transport"``
takes the previous displacement at the particle's departure point ``x + h`` from the
cubic through the four element centres around it (a semi-Lagrangian step, exact
transport up to an interpolation error O(dx⁴) per step). ``scheme="interpolated"``
keeps the current displacement at the centre and
takes the previous one at ``x + h`` by linear interpolation between element
centres (as Vollebregt's CONTACT shifts its displacement field by a rolled
distance that is not a whole number of elements); held steady the run ends
on Kalker's discretisation for any ``h ≤ dx`` (:func:`step_kernels`), and in
adhesion the traction field is carried by upwind interpolation, which damps
and never amplifies. ``scheme="averaged"`` (the slip relation averaged over
the points ``x_I + k h``, :func:`step_weights`) also ends on Kalker's
discretisation, exactly for integer ``dx/h``, but at a non-integer ratio its
collocation points straddle the element boundary and the transient shows a
false slip phase (Baeza et al. §3.1, 60 elements, ``dx/h = 1.84``).

Normal force varying along the travel: the normal problem is solved at every
step on the same grid (Polonsky–Keer, warm started); elements leaving the
contact get zero traction (bound ``μ pn = 0``), elements entering start
without traction but with the displacement carried from the previous step,
which keeps the tractions physical (Baeza et al., Fig. 1).

Prescribed tangential force F1(x): the longitudinal creepage ξ is one more
unknown of each step's Newton iteration, with the equation ``Fx = F1``
(:func:`~wheelrail.tangential.exact.newton_force_step`), started from the
tractions and ξ extrapolated linearly from the two previous steps; where that
iteration fails a safeguarded secant iteration on ``Fx(ξ) = F1`` around the
step (Fx decreases monotonically with ξ).

References
----------
.. [1] L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the
   wheel–rail contact instationary process on contact parameters (Baeza et al.),
   eqs. (2.5)–(2.13), (2.19)–(2.20), §3.1.
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.2 (transient discretisation, steady state as its limit).
.. [3] E.A.H. Vollebregt, CONTACT user guide and examples (github.com/eve70a/CONTACT,
   examples/catt_to_cart), the transient example the default scheme is checked against.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validation import as_float_array, integer, positive
from ..errors import InputError
from ..halfspace.influence import influence_kernel
from ..materials import as_material_pair
from ..normal.bem import hertz_grid
from ..tangential.exact._kernels import _SPIN_SHIFT
from ._fft import FastBlockConvolution as _BlockConvolution
from ._schemes import (  # noqa: F401  (the schemes' public names, here since they began here)
    SCHEMES,
    shifted_influence_kernel,
    step_kernels,
    step_points,
    step_weights,
    transport_weights,
)
from ._stepping import SCALARS as _SCALARS
from ._stepping import HertzNormal, RollingProblem, as_function, evaluate, run
from .strips import (
    DenseOperator,
    hertz_pressure,
    preconditioner_kernel,
    strip_grid,
    strip_step_operators,
)

__all__ = ["TransientResult", "transient_rolling"]

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


def transient_rolling(contact, *, travel, step, mu, Fn=None, creepage=None,
                      Fx=None, friction="exact", epsilon=None, elements=30,
                      margin=1.25, tol=1e-8, maxiter=100, force_tol=1e-7, frames=100,
                      progress=False, scheme="transport", penetration=None,
                      discretisation="uniform", strips=None, settle=1e-4) -> TransientResult:
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
    scheme : {"transport", "interpolated", "upwind2", "averaged", "centre"}
        Collocation of the slip (:func:`step_points`, :func:`step_kernels`):
        ``"transport"`` (default) takes the previous displacement at the
        departure point ``x + h`` of the particle from the cubic through the four
        element centres around it (a semi-Lagrangian step: the transient is carried
        without the damping of linear interpolation at steps shorter than an
        element; the exact shift, Kalker's scheme, at ``h = dx``);
        ``"interpolated"`` takes the previous displacement at
        ``x + h`` by linear interpolation between element centres, so that a
        run held at constant loads ends on Kalker's steady discretisation for
        any step up to ``dx`` and the traction is carried without amplification;
        ``"upwind2"`` takes the convective derivative by the second-order
        upwind difference at the new time (implicit) and the time derivative
        at the element centre: held steady it ends on the second-order
        upwind rolling kernel (grid error first order in ``dx`` with Kalker's
        kernel, much smaller with this one; docs/transient.md);
        ``"averaged"`` averages the slip over the element's upstream points
        (a false slip phase at non-integer ``dx/h``); ``"centre"`` is Baeza
        et al.'s eq. (2.10) at the element centres (accurate only for
        ``step = dx``).
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
    settle : float
        On the uniform grid with exact friction: once the
        loads stay constant to the end of the travel and a step changes the
        tractions by less than ``0.1·settle·μ·max pn``, the steady fixed point of the
        step (Kalker's steady rolling on the same grid, solved directly) is
        computed; if it lies within ``settle·μ·max pn`` of the current tractions
        the run continues from it, and every later step, reproducing its input,
        is recorded without solving. ``0`` steps through the whole travel.

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
    friction, epsilon = _friction_law(friction, epsilon)
    pair = as_material_pair(contact.materials)
    mu = float(positive("mu", mu))
    travel = float(positive("travel", travel))
    h = float(positive("step", step))
    elements = integer("elements", elements, 2)
    frames = integer("frames", frames, 1)
    tol = float(positive("tol", tol))
    force_tol = float(positive("force_tol", force_tol))
    settle = float(as_float_array("settle", settle))
    if not settle >= 0:
        raise InputError(f"settle must be >= 0, got {settle!r}")
    a = float(contact.a)
    if not h < 2 * a:
        raise InputError(f"step = {h!r} m must be shorter than the contact length "
                         f"2a = {2 * a!r} m")
    if h > travel:
        raise InputError(f"step = {h!r} m is longer than travel = {travel!r} m")
    normal_name, normal_unit, F3, F3_const, F1, cr = _load_functions(contact, Fn, penetration,
                                                                     Fx, creepage)
    n = int(math.floor(travel / h + 1e-9)) + 1
    xs = np.arange(n) * h
    load_at, steady_from = _loads_along(xs, mu, ((normal_name, F3), ("Fx", F1)) + tuple(
        zip(("xi", "eta", "phi"), cr)), normal_name, normal_unit, penetration is None)
    if scheme not in SCHEMES:
        raise InputError(f"scheme must be one of {SCHEMES}, got {scheme!r}")
    if discretisation == "strips":
        ops = _strip_operators(contact, pair, h, scheme, friction, elements, strips,
                               F3_const and penetration is None, evaluate(normal_name, F3, 0.0))
    elif discretisation in ("uniform", "material"):
        ops = _grid_operators(contact, pair, h, scheme, elements, margin, discretisation)
    else:
        raise InputError(f"discretisation must be 'uniform', 'strips' or 'material', got "
                         f"{discretisation!r}")
    keep = set(np.unique(np.linspace(0, n - 1, min(frames, n)).round().astype(int)).tolist())
    keep.add(n - 1)
    problem = RollingProblem(
        pair=pair, mu=mu, h=h, friction=friction, epsilon=epsilon, tol=tol, maxiter=maxiter,
        force_tol=force_tol, settle=settle, scheme=scheme, discretisation=discretisation,
        elements=elements, a=a, b=float(contact.b), A=float(contact.A), B=float(contact.B),
        progress=progress, normal_name=normal_name, F3=F3, F3_const=F3_const,
        by_penetration=penetration is not None, F1=F1, creepage=cr, xs=xs, load_at=load_at,
        steady_from=steady_from, keep=sorted(keep), **ops,
        **_scheme_settings(ops["grid"], h, scheme, discretisation, friction, settle))
    return TransientResult(**run(problem))


def _friction_law(friction, epsilon):
    """``(friction, epsilon)`` checked: ``"exact"``, or ``"regularised"`` with ε > 0."""
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
    return friction, epsilon


def _load_functions(contact, Fn, penetration, Fx, creepage):
    """``(normal_name, normal_unit, F3, F3_const, F1, (xi, eta, phi))`` as functions of
    travel (``F1`` and, under force control, ``xi`` None)."""
    if Fn is not None and penetration is not None:
        raise InputError("give Fn= or penetration= (normal control), not both")
    if penetration is not None:
        F3 = as_function("penetration", penetration)
        normal_name, normal_unit = "penetration", "m"
        F3_const = not callable(penetration)
    else:
        F3 = as_function("Fn", float(contact.Fn) if Fn is None
                         else Fn)
        normal_name, normal_unit = "Fn", "N"
        F3_const = not callable(Fn)
    if Fx is not None:
        F1 = as_function("Fx", Fx)
        if creepage is None:
            creepage = (None, 0.0, 0.0)
        if len(creepage) != 3 or creepage[0] is not None:
            raise InputError("with Fx, creepage must be (None, eta, phi): "
                             f"xi is the unknown; got {creepage!r}")
        cr = (None,) + tuple(as_function(n, c) for n, c in zip(("eta", "phi"), creepage[1:]))
    else:
        F1 = None
        if creepage is None or len(creepage) != 3 or any(c is None for c in creepage):
            raise InputError(f"give creepage=(xi, eta, phi) or Fx=, got "
                             f"creepage={creepage!r}")
        cr = tuple(as_function(n, c) for n, c in zip(("xi", "eta", "phi"), creepage))
    return normal_name, normal_unit, F3, F3_const, F1, cr


def _loads_along(xs, mu, functions, normal_name, normal_unit, check_force):
    """``(load_at, steady_from)``: each load function's values at every travel ``xs``
    (evaluated once) and whether the loads stay equal from step k to the end.

    Every load function is checked at every step before the run: a load that turns
    negative (or not finite) is named with its travel instead of failing mid-run.
    """
    steady_from = np.ones(len(xs), dtype=bool)
    load_at = {}
    for name, fun in functions:
        if fun is None:
            continue
        vals = np.array([evaluate(name, fun, float(x)) for x in xs])
        load_at[name] = vals
        same = np.append(vals[1:] == vals[:-1], True)
        steady_from &= np.flip(np.logical_and.accumulate(np.flip(same)))
        if name == normal_name and not np.all(vals > 0):
            k = int(np.argmax(~(vals > 0)))
            raise InputError(f"{name}(x = {xs[k]!r} m) = {vals[k]!r} {normal_unit} must be > 0 "
                             f"(the load function goes non-positive along the travel)")
        if name == normal_name:
            normal_vals = vals
        if name == "Fx" and check_force:
            bad = np.nonzero(~(np.abs(vals) < mu * normal_vals))[0]
            if bad.size:
                k = int(bad[0])
                raise InputError(f"Fx(x = {xs[k]!r} m) = {vals[k]!r} N must be "
                                 f"smaller in magnitude than mu*Fn = "
                                 f"{mu * normal_vals[k]!r} N (full sliding)")
    return load_at, steady_from


def _strip_operators(contact, pair, h, scheme, friction, elements, strips, constant_force,
                     F3_0):
    """The Paul–Hashemi strips (Baeza et al., Fig. 2): grid, dense step operators and the
    Hertz pressure of the constant normal force ``F3_0`` [N]."""
    if not constant_force:
        raise InputError("discretisation='strips' (Paul–Hashemi) needs a constant "
                         "Fn (the strips follow the Hertz ellipse)")
    if friction != "exact":
        raise InputError("discretisation='strips' supports friction='exact' only")
    if scheme in ("centre", "upwind2"):
        raise InputError(f"discretisation='strips' uses scheme='interpolated' or "
                         f"'averaged', got {scheme!r}")
    strips = integer("strips", elements if strips is None else strips, 2)
    grid = strip_grid(contact, elements, strips)
    Nw, Ow = strip_step_operators(grid, pair, h, lambda d, st: step_points(d, st, scheme))
    nflat = grid.nx * grid.ny
    return dict(grid=grid, gap=None, dA=np.array(grid.area),
                K_now=preconditioner_kernel(Nw / h, grid),
                conv_now=DenseOperator(Nw[:, :2 * nflat] / h, grid.shape),
                conv_old=DenseOperator(Ow, grid.shape),
                conv_n=DenseOperator(Nw[:, 2 * nflat:], grid.shape) if pair.K else None,
                strip_normal=HertzNormal(pressure=hertz_pressure(contact, grid, F3_0),
                                         penetration=float(np.asarray(contact.penetration))))


def _grid_operators(contact, pair, h, scheme, elements, margin, discretisation):
    """The grid of :func:`~wheelrail.normal.bem.hertz_grid` (moving with the contact, or
    fixed to the rail: ``"material"``), its gap and the FFT operators of one step."""
    grid, gap = hertz_grid(contact, elements=elements, margin=margin)
    if discretisation == "material":
        # grid fixed to the rail (a window moved in whole elements): the particle
        # stays on its element, so the carried displacement is C p_old unshifted
        C = influence_kernel(grid, pair)
        Ch = C
    else:
        C, Ch = step_kernels(grid, pair, h, scheme)
    K_now = np.ascontiguousarray(C[:2, :2] / h)
    return dict(grid=grid, gap=gap, dA=grid.element_area, K_now=K_now,
                conv_now=_BlockConvolution(K_now), conv_old=_BlockConvolution(Ch[:2, :]),
                conv_n=_BlockConvolution(C[:2, 2:3]) if pair.K else None, strip_normal=None)


def _scheme_settings(grid, h, scheme, discretisation, friction, settle):
    """Preconditioning, spin collocation, carried displacement and steady jump of a scheme."""
    # precondition with the upstream neighbour (the line solve of newton_step): the
    # averaged scheme couples each element strongly to it, and for the influence kernel
    # C of the other schemes the one-sided sweep needs fewer Krylov steps than the
    # element alone (measured on Baeza et al. §3.1)
    # (for "upwind2" the line recursion with the upstream neighbour alone is unstable in
    # the steady limit, whose kernel also couples to the second element upstream: the
    # element alone is used)
    out = dict(upwind=scheme != "upwind2")
    # where the spin's rigid slip is collocated: upstream of the centre for Kalker's
    # first-order difference (as the steady solver), at the centre for "upwind2"
    # (the transport scheme: Kalker's shift at h = dx, the centre as h -> 0)
    out["spin_shift"] = (0.0 if scheme == "upwind2" else
                         _SPIN_SHIFT * min(1.0, h / float(np.max(grid.dx)))
                         if scheme == "transport" else _SPIN_SHIFT)
    # interpolated scheme on the moving grid: the carried displacement is the previous
    # step's displacement field (its slip minus its rigid part) interpolated upstream,
    # no convolution needed
    out["carry_u"] = scheme in ("interpolated", "transport") and discretisation == "uniform"
    if out["carry_u"]:
        # the previous displacement at x + h from the element centres x + o_k dx, weights w_k
        _, _, up_s, up_w = step_points(grid.dx, h, scheme)
        out["up_o"] = np.rint(up_s / grid.dx).astype(int)
        out["up_w"] = up_w
    # the steady fixed point of the step (Kalker's steady rolling with the interpolated
    # scheme), tried once the tractions change little per step under constant loads; if
    # its Newton iteration fails (the centre scheme at large dx/h) the run steps on
    out["jump"] = settle > 0 and discretisation == "uniform" and friction == "exact"
    return out
