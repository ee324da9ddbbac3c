"""Rolling: the two loading steps of Toumi, Chollet & Yin (2016) with an explicit or implicit integrator.

Step 1 establishes the normal contact under the load; step 2 rolls: the rail
is pulled back with speed V(t) rising by a smooth step over the first
``ramp`` fraction of the travel, and the wheel turns with

    dψ/dt = V(t) (1 − ξ) / r_c,

so that the rigid longitudinal creepage (v_wheel − v_rail)/V is ξ
(Toumi et al. 2016, eq. 1, in Kalker's sign convention). The lateral creepage η is
imposed by a lateral rail drift −η V(t) (:meth:`wheelrail.fe.model.Model.lateral_shift`).

Integrators (:mod:`.explicit`, :mod:`.implicit`):

* ``"explicit"`` — central differences, lumped mass × ``mass_scaling``, contact dashpots
  (``contact_damping``), the step 1 by dynamic relaxation; parallel kernels;
* ``"implicit-qs"`` — a static Newton solve per time step (backward-Euler slip);
* ``"implicit-hht"`` — HHT-α (Hilber, Hughes & Taylor 1977), Newton per step.

Elastic or elasto-plastic (:class:`wheelrail.fe.J2Plastic`): the plastic state of every
integration point is carried through both steps, written to restart files, and
reported (:attr:`RollingResult.equivalent_plastic_strain`,
:attr:`RollingResult.residual_stress`). ``passes > 1`` rolls the same wheel segment
over the same rail section again (repeated passes: shakedown or ratcheting).

Steady state
------------
Every result reports its steady window (travel from the end of the speed ramp plus
four semi-axes, at most the last quarter, to the end) and the mean and scatter
(standard deviation) of the forces over it, from every time step (explicit) or every
step (implicit): :attr:`RollingResult.steady`.

References
----------
.. [1] M. Toumi, H. Chollet, H. Yin, "Finite element analysis of the frictional
   wheel-rail rolling contact using explicit and implicit methods", Wear 366-367
   (2016) 157-166, §2-3, eq. (1).
.. [2] H.M. Hilber, T.J.R. Hughes, R.L. Taylor, "Improved numerical dissipation for
   time integration algorithms in structural dynamics", Earthquake Eng. Struct.
   Dyn. 5 (1977) 283-292.
.. [3] T. Belytschko, W.K. Liu, B. Moran, *Nonlinear Finite Elements for
   Continua and Structures*, Wiley 2000, §6.2 (central differences, stable step,
   energy balance).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..tangential.linear import kalker_coefficients
from ._solid import von_mises
from .materials import as_fe_material
from .model import contact_geometry
from .restart import write_restart

__all__ = ["RollingResult", "stable_time_step", "saturation_creepage",
           "steady_window", "plastic_fields", "stress_fields"]

#: History columns of a rolling run (rows of the output dataset).
COLUMNS = ("time", "travel", "Fx", "Fy", "Fz", "Fn", "kinetic", "internal", "contact",
           "friction", "damping", "external", "contact_work", "plastic_work")


@dataclass(frozen=True, eq=False)
class RollingResult:
    """Result of :func:`solve`.

    Attributes
    ----------
    dataset : xarray.Dataset
        Histories over ``travel`` [m] (the last pass): Fx, Fy, Fz [N] (contact force on
        the wheel, global axes: x rolling, y the profiles' lateral axis, z up), Fn [N]
        (sum of the normal nodal forces), Fy_contact and Fn_contact [N] (the force on
        the wheel along the lateral tangent and the normal of the undeformed contact
        plane, tilted by the contact angle δ), kinetic, internal (elastic strain energy
        plus plastic work), contact (penalty), friction (dissipated), damping
        (dissipated), external (load work), contact_work and plastic_work energies [J]
        and energy_error = kinetic + internal + damping − external − contact_work [J],
        counted from the start of the rolling step.
    patch : xarray.Dataset
        Contact nodes at the end (see :func:`wheelrail.fe.patch_dataset.patch_from_contact`).
    Fx, Fy : float
        Steady longitudinal and lateral (global y) force on the wheel [N]: the means over
        the steady window (:attr:`steady`); :attr:`Fy_contact` is the lateral force in
        the tilted contact plane.
    p_max, a, b : float
        Peak pressure [Pa] and equivalent semi-axes [m] of the final patch.
    model : Model
    u : ndarray, shape (n_nodes, 3)
        Final displacements in the body frames [m].
    info : dict
        Time step, steps, solver counters; explicit runs: ``loop_wall``, ``loop_cpu``
        the wall and CPU seconds of the time loop (without the model build and output).
    steady : dict
        ``window`` (start, end) of travel [m], ``n`` samples, and for Fx, Fy, Fz, Fn,
        Fy_contact, Fn_contact: ``<name>`` the mean [N], ``<name>_std`` the standard
        deviation [N] and ``<name>_scatter`` = std / |mean| [-].
    state : PlasticState or None
        The final plastic state (plastic materials).
    fields : xarray.Dataset or None
        Element fields at the end (plastic materials): equivalent plastic strain,
        stress (the residual stress away from the contact) and von Mises stress of the
        rail over (x, y, depth) and of the wheel over (wheel_x, wheel_y, wheel_depth)
        (see :func:`plastic_fields`).
    passes : xarray.Dataset or None
        Per pass (``passes > 1``): steady forces and the depth profiles of the residual
        stress and equivalent plastic strain under the middle of the rolled section.
    """

    dataset: object
    patch: object
    Fx: float
    Fy: float
    p_max: float
    a: float
    b: float
    model: object
    u: np.ndarray
    info: dict
    steady: dict = field(default_factory=dict)
    state: object = None
    fields: object = None
    passes: object = None

    @property
    def Fy_contact(self) -> float:
        """Steady lateral force in the contact plane [N] (the creep force to compare with a
        half-space solution when the contact is inclined; equals ``Fy`` at δ = 0)."""
        return self.steady["Fy_contact"]

    @property
    def equivalent_plastic_strain(self):
        """Equivalent plastic strain per element [-]: an xarray.Dataset with ``rail`` (x, y,
        depth) and ``wheel`` (wheel_x, wheel_y, wheel_depth); None for an elastic run."""
        if self.fields is None:
            return None
        return self.fields[["rail_equivalent_plastic_strain", "wheel_equivalent_plastic_strain"]
                           ].rename(rail_equivalent_plastic_strain="rail",
                                    wheel_equivalent_plastic_strain="wheel")

    @property
    def residual_stress(self):
        """Stress per element at the end [Pa] (Voigt components xx, yy, zz, xy, yz, xz, body
        frames): an xarray.Dataset with ``rail`` and ``wheel``; residual where the contact
        has passed (rail x < final contact − 3 a). None for an elastic run."""
        if self.fields is None:
            return None
        return self.fields[["rail_stress", "wheel_stress"]].rename(rail_stress="rail",
                                                                   wheel_stress="wheel")

    def __repr__(self):
        return (f"RollingResult(Fx={self.Fx:.1f} N, Fy={self.Fy:.1f} N, p_max="
                f"{self.p_max / 1e6:.1f} MPa, a={self.a * 1e3:.3f} mm, b={self.b * 1e3:.3f} mm, "
                f"Fx scatter {self.steady.get('Fx_scatter', float('nan')):.1%})")


def _smoothstep(tau):
    if isinstance(tau, (float, int)):       # scalar fast path (called every explicit step)
        tau = min(max(float(tau), 0.0), 1.0)
    else:
        tau = np.clip(tau, 0.0, 1.0)
    return tau ** 3 * (10 - 15 * tau + 6 * tau ** 2)


def contact_damping_factor(zeta: float) -> float:
    """Reduction of the stable central-difference step of an oscillator with damping ratio
    ζ (velocity at the half step): √(1 + ζ²) − ζ (Belytschko et al. 2000, eq. 6.2.40)."""
    return float(np.sqrt(1.0 + zeta * zeta) - zeta)


def stable_time_step(model) -> float:
    """Largest stable central-difference step [s] (before the safety factor), mass scaling included.

    The smaller of the element limit L_e / c (L_e = volume / largest face area, c the
    dilatational wave speed of the scaled density) and the limit √(m / k) of a surface
    node on the contact spring k = k_n A (halved for the master node in series), the latter
    reduced by :func:`contact_damping_factor` of the contact dashpots.
    """
    c = model.material.wave_speed / np.sqrt(model.case.mass_scaling)
    L = float(model.edata.length.min())
    dt_el = L / c
    ms = model.mass[model.slave] * model.case.mass_scaling
    kc = model.kn * model.slave_area
    # only slaves of the refined lateral band can touch the rail
    y = model.wheel.nodes[model.slave, 1]
    band = np.abs(y - model.geometry["y_c"]) <= 1.5 * model.geometry["b"] + 2 * model.case.mesh_size
    dt_c = float(np.sqrt(ms[band] / kc[band]).min())      # slave and master springs in series
    if model.case.integrator == "explicit":
        dt_c *= contact_damping_factor(model.case.contact_damping)
    return float(min(dt_el, dt_c))


def contact_dashpots(model, zeta: float) -> np.ndarray:
    """Normal contact dashpots c = 2 ζ √(k m/2) [N s/m] per slave: ζ of critical damping of
    the slave's (scaled) mass on its linear penalty spring k = k_n A, the master mass in
    series taken equal."""
    ms = model.mass[model.slave] * model.case.mass_scaling
    kc = model.kn * model.slave_area
    return 2.0 * zeta * np.sqrt(kc * 0.5 * ms)


def speed_profile(case, travel):
    """Rail speed V(t) [m/s] (smooth step over the ramp distance) and the end time [s]."""
    V = case.speed
    d_ramp = case.ramp * travel
    # time to cover the ramp with V(t) = V S(t / t_r): ∫ = V t_r / 2 for the quintic step
    t_r = 2 * d_ramp / V if d_ramp > 0 else 0.0
    t_end = t_r + (travel - d_ramp) / V

    def speed(t):
        return V * (_smoothstep(t / t_r) if t_r > 0 else 1.0)

    return speed, t_end


_speed_profile = speed_profile      # older name (benchmarks, CLI)


def steady_window(case, model) -> tuple[float, float]:
    """Travel interval [m] over which the rolling forces are steady (averaged).

    From the end of the speed ramp plus four Hertz semi-axes a (the creep force builds up
    over about 2a of rolling after the speed is reached; plastic wakes need a few more),
    but at most the last quarter of the travel, to the end of the travel.
    """
    travel = float(model.geometry["travel"])
    a = float(model.geometry["a"])
    start = min(case.ramp * travel + 4.0 * a, 0.75 * travel)
    return float(start), travel


def steady_statistics(travel, forces: dict, window) -> dict:
    """Means, standard deviations and scatter (std/|mean|) of force samples in ``window``."""
    travel = np.asarray(travel)
    sel = (travel >= window[0] - 1e-15) & (travel <= window[1] + 1e-15)
    if not sel.any():
        sel = np.zeros(travel.size, bool)
        sel[-1] = True
    out = {"window": (float(window[0]), float(window[1])), "n": int(sel.sum())}
    for name, v in forces.items():
        x = np.asarray(v)[sel]
        m = float(np.mean(x))
        sd = float(np.std(x))
        out[name] = m
        out[f"{name}_std"] = sd
        out[f"{name}_scatter"] = sd / abs(m) if m != 0 else float("inf")
    return out


def contact_plane_forces(model, Fy, Fz):
    """Forces along the lateral tangent and the normal of the undeformed contact plane."""
    t, nv = model.geometry["lateral"], model.geometry["normal"]
    Fy, Fz = np.asarray(Fy), np.asarray(Fz)
    return Fy * t[1] + Fz * t[2], Fy * nv[1] + Fz * nv[2]


def saturation_creepage(case) -> float | None:
    """Creepage magnitude [-] beyond which the whole patch slides (saturation estimate).

    Johnson's and Vermeulen's cubic saturation law reaches μ F_n at three times the
    creepage where Kalker's linear force does: √((C11 ξ)² + (C22 η)²) G c² = 3 μ F_n,
    c = √(ab), with Kalker's coefficients of the Hertz contact of the case (None if the
    case is not Hertzian or the creepage is zero).

    References
    ----------
    .. [1] J.J. Kalker, *Three-Dimensional Elastic Bodies in Rolling Contact*, Kluwer 1990,
       §2.3 (linear theory).
    .. [2] P.J. Vermeulen, K.L. Johnson, "Contact of nonspherical elastic bodies
       transmitting tangential forces", J. Appl. Mech. 31 (1964) 338-340 (cubic law).
    """

    geo = contact_geometry(case)
    hz = geo["hertz"]
    if hz is None:
        return None

    mat = as_fe_material(case.material, case.density)
    c11, c22, _, _ = (float(v) for v in kalker_coefficients(float(hz.a / hz.b), mat.nu))
    xi, eta = case.creepage[0], case.creepage[1]
    n = float(np.hypot(xi, eta))
    if n == 0:
        return None
    stiff = float(np.hypot(c11 * xi / n, c22 * eta / n))
    return float(3.0 * case.mu * geo["normal_load"] / (mat.shear_modulus * hz.a * hz.b * stiff))


def _warn_saturation(case):
    import warnings

    sat = saturation_creepage(case) if case.mu > 0 else None
    if sat is None:
        return
    xi, eta = case.creepage[0], case.creepage[1]
    n = float(np.hypot(xi, eta))
    if n > sat:
        warnings.warn(f"creepage (xi, eta) = ({xi!r}, {eta!r}) is past saturation (cubic "
                      f"law on the linear theory: full sliding beyond |creepage| = "
                      f"{sat:.3g}): the patch slides entirely and the creep force is mu Fn "
                      f"whatever the creepage",
                      UserWarning, stacklevel=3)


def progress_bar(progress, total, label):
    if not progress:
        return None
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    p = Progress(TextColumn(label), BarColumn(), TextColumn("{task.percentage:>3.0f}%"),
                 TimeElapsedColumn(), TimeRemainingColumn(), transient=True)
    p.start()
    p.add_task(label, total=total)
    return p


def history_dataset(rows, case, model, extra):
    """The output histories (rows of :data:`COLUMNS`) as an xarray.Dataset over travel."""
    import xarray as xr

    rows = np.asarray(rows, dtype=float).reshape(-1, len(COLUMNS))
    data = {n: ("travel", rows[:, k]) for k, n in enumerate(COLUMNS) if n != "travel"}
    ds = xr.Dataset(data, coords={"travel": rows[:, 1]})
    units = {"time": "s", "Fx": "N", "Fy": "N", "Fz": "N", "Fn": "N"}
    for n in COLUMNS[6:]:
        units[n] = "J"
    for n, un in units.items():
        ds[n].attrs["units"] = un
    ds.travel.attrs["units"] = "m"
    ds["energy_error"] = ds.kinetic + ds.internal + ds.damping - ds.external - ds.contact_work
    ds["energy_error"].attrs["units"] = "J"
    # forces in the (undeformed) contact plane: differ from Fy, Fz on an inclined contact
    fy_c, fn_c = contact_plane_forces(model, ds.Fy.values, ds.Fz.values)
    ds["Fy_contact"] = ("travel", fy_c)
    ds["Fn_contact"] = ("travel", fn_c)
    for name in ("Fy_contact", "Fn_contact"):
        ds[name].attrs["units"] = "N"
    attrs = {"integrator": case.integrator, "creepage_xi": case.xi,
             "creepage_eta": case.creepage[1], "mu": case.mu, "load": case.Fn,
             "speed": case.speed, "n_elements": model.n_elements, "mesh_size": case.mesh_size,
             "material": type(model.material).__name__}
    for k, v in extra.items():
        if isinstance(v, (int, float, str, np.integer, np.floating)):
            attrs[k] = v
    ds.attrs.update(attrs)
    return ds


def restart_writer(io, model, dt, n_steps):
    """A callable ``maybe_write(k_done, state_fn)`` writing every ``every`` steps and at the end."""

    path = io["file"]
    every = io["every"] or max(1, n_steps // 10)

    def maybe_write(k_done, state_fn, force=False):
        if path is None:
            return False
        if k_done % every == 0 or k_done == n_steps or force:
            write_restart(str(path).format(step=k_done), model, dt, state_fn())
            return True
        return False

    maybe_write.every = every if path is not None else 0     # steps between writes (0: none)
    return maybe_write


def contact_state(c):
    return {k: v for k, v in c.items() if isinstance(v, np.ndarray)}


def plastic_fields(model, u, state):
    """Element fields of a plastic run (an xarray.Dataset; None if elastic).

    ``rail_equivalent_plastic_strain`` (x, y, depth) [-], ``rail_stress`` (x, y, depth,
    component) [Pa], ``rail_von_mises`` [Pa], and the same for the wheel over
    (wheel_x, wheel_y, wheel_depth): element centres, x the rail's reference abscissa
    (the contact started at x = 0 and moved to x = travel), wheel_x = R θ the arc length
    of the wheel's material angle, y lateral, depth below the running surface [m].
    Stresses in the body frames (Voigt xx, yy, zz, xy, yz, xz).
    """
    if state is None:
        return None
    return stress_fields(model, u, state)


def stress_fields(model, u, state=None):
    """The fields of :func:`plastic_fields` for any run: with ``state`` None (an elastic run)
    the stresses of ``u`` and a zero plastic strain."""
    import xarray as xr

    sig_w, sig_r = model.stress(u, state)
    if state is None:
        p_w, p_r = np.zeros(model.wheel.n_elements), np.zeros(model.rail.n_elements)
    else:
        p_w, p_r = state.equivalent_plastic_strain()
    data, coords = {}, {"component": ["xx", "yy", "zz", "xy", "yz", "xz"]}
    R = model.geometry["r_c"]
    for body, sig, p, pre, scale in ((model.rail, sig_r, p_r, "", 1.0),
                                     (model.wheel, sig_w, p_w, "wheel_", R)):
        ax = [0.5 * (a[1:] + a[:-1]) for a in body.axes]
        shape = tuple(len(a) for a in ax)
        dims = (f"{pre}x", f"{pre}y", f"{pre}depth")
        coords[dims[0]] = (dims[0], ax[0] * scale, {"units": "m"})
        coords[dims[1]] = (dims[1], ax[1], {"units": "m"})
        coords[dims[2]] = (dims[2], ax[2], {"units": "m"})
        name = body.name
        data[f"{name}_equivalent_plastic_strain"] = (dims, p.reshape(shape), {"units": "1"})
        data[f"{name}_stress"] = (dims + ("component",), sig.reshape(shape + (6,)),
                                  {"units": "Pa"})
        data[f"{name}_von_mises"] = (dims, von_mises(sig).reshape(shape), {"units": "Pa"})
    return xr.Dataset(data, coords=coords)


def depth_profiles(fields, x_range, y=0.0):
    """Rail depth profiles of the fields, averaged over x in ``x_range`` at the element row
    nearest to ``y``: an xarray.Dataset over depth (stress components, von Mises and the
    equivalent plastic strain)."""
    sub = fields.sel(y=y, method="nearest")
    sub = sub.sel(x=slice(*x_range))
    out = sub[["rail_stress", "rail_von_mises", "rail_equivalent_plastic_strain"]].mean("x")
    return out.rename(rail_stress="residual_stress", rail_von_mises="von_mises",
                      rail_equivalent_plastic_strain="equivalent_plastic_strain")
