"""The assembled two-body model: meshes, element data, masses, rigid motions, contact.

Kinematics (small strain, large prescribed rigid motion)
--------------------------------------------------------
Each body carries its elastic displacement ``u`` in its own frame. The rail
frame translates by ``-s(t)`` along ``x``; the wheel frame turns by the rolling
angle ``psi(t)`` about the axle and the axle moves vertically by ``w`` (the
load degree of freedom). A wheel node's global position is

    x = c0 + w e_z + Q(psi) (X + u),   Q = [[cos, 0, sin], [0, 1, 0], [-sin, 0, cos]],

a rail node's ``x = X + u - s e_x - η s e_y``: with a lateral creepage η the rail
also drifts sideways at −η V(t), so that the rigid lateral creepage (wheel velocity
relative to the rail / V) is η — the small-angle equivalent of a yaw angle
α = −η of the wheel (Toumi et al. 2016, eqs. 2-3). This is exact for the elastic response to
small strains under arbitrary rigid rotation (a co-rotational frame per body);
the fictitious (centrifugal, Coriolis) body forces of the turning frame are
neglected (ρ Ω² R ≈ 3 MN/m³ at 50 km/h, i.e. < 0.1 MPa over the kept rim).

The rail's foot plane and the wheel's inner rim (the cut faces of Toumi et al.'s (2016)
Fig. 1) are clamped in their body frames.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..materials import Material
from ..normal.hertz import hertz
from . import _kernels as K
from . import _solid as S
from ._solid import element_chunks
from .elements import ElementData, Hex8
from .materials import as_fe_material
from .mesh import axis_size, graded_axis, rail_body, wheel_body

__all__ = ["Model", "PlasticState", "build_model", "contact_geometry"]

_NO_STATE = np.zeros((0, 1, 14))
_NO_HARDENING = (np.zeros(6), np.zeros(0), np.zeros(0))


class PlasticState:
    """The plastic state of both bodies (mutable; one per run).

    ``committed`` and ``trial`` have shape (n_elements, n_points, 14), wheel elements
    first: plastic strain (6, engineering shear), equivalent plastic strain, back stress
    (6) [Pa] and plastic work density [J/m³] per integration point
    (:mod:`wheelrail.fe._solid`). The kernels read ``committed`` and write ``trial``;
    :meth:`commit` accepts the trial state (swapping the buffers).
    """

    def __init__(self, committed, n_wheel_elements, trial=None):
        self.committed = np.ascontiguousarray(committed, dtype=float)
        self.trial = self.committed.copy() if trial is None else trial
        self.n_wheel = int(n_wheel_elements)
        self.energies = (0.0, 0.0)

    def commit(self):
        """Accept the trial state of the last kernel call."""
        self.committed, self.trial = self.trial, self.committed

    def copy(self):
        return PlasticState(self.committed.copy(), self.n_wheel)

    def body(self, k):
        """Committed state of the wheel (k = 0) or the rail (k = 1) (a view)."""
        return self.committed[:self.n_wheel] if k == 0 else self.committed[self.n_wheel:]

    def equivalent_plastic_strain(self):
        """Mean equivalent plastic strain per element [-]: (wheel (ne_w,), rail (ne_r,))."""
        p = self.committed[:, :, S.P_INDEX].mean(axis=1)
        return [p[:self.n_wheel], p[self.n_wheel:]]


def contact_geometry(case):
    """Initial contact point, rolling radius and Hertz estimate of a case.

    Returns
    -------
    dict
        ``y_c`` lateral position of the contact point [m], ``z_axle`` axle height [m],
        ``r_c`` rolling radius there [m], ``radius_of_y`` callable r(y) [m],
        ``rail`` the inclined rail profile, ``hertz`` a :class:`HertzContact`
        from the local curvatures and the normal load ``load / cos δ`` (δ the contact
        angle, ``delta`` [rad]), or None if they are not Hertzian; ``lateral`` and
        ``normal`` the unit lateral tangent and normal (3,) of the undeformed contact
        plane (global axes).
    """

    rail = case.rail.rotated(case.inclination) if case.inclination else case.rail
    wheel = case.wheel
    lat = case.lateral_position
    lo = max(rail.y_min, wheel.y_min + lat)
    hi = min(rail.y_max, wheel.y_max + lat)
    if hi <= lo:
        raise InputError(f"lateral_position {lat!r} m puts the wheel profile beside the rail "
                         f"(no lateral overlap)")
    ys = np.linspace(lo, hi, 4001)
    gap = wheel(ys - lat) - rail(ys)
    k = int(np.nanargmin(gap))
    if 0 < k < len(ys) - 1:   # parabolic refinement
        g0, g1, g2 = gap[k - 1:k + 2]
        den = g0 - 2 * g1 + g2
        y_c = ys[k] + (0.5 * (g0 - g2) / den if den > 0 else 0.0) * (ys[1] - ys[0])
    else:
        y_c = ys[k]
    s_v = -(wheel(y_c - lat) - rail(y_c))          # vertical shift to touch
    z_axle = case.radius + s_v

    def radius_of_y(y):
        return case.radius - wheel(np.asarray(y) - lat)

    r_c = float(radius_of_y(y_c))
    kw = float(wheel.curvature(y_c - lat))
    kr = float(rail.curvature(y_c))
    # circumferential normal curvature of the wheel (a surface of revolution): cos δ / r,
    # δ the angle of the tread to the axle (the wheel's profile slope; 1/10 cone: -0.5 %)
    A = 0.5 * float(np.cos(np.arctan(wheel.slope(y_c - lat)))) / r_c
    B = 0.5 * (kw - kr)
    mat = as_fe_material(case.material, case.density)
    # the vertical wheel load acts along the contact normal with Fn = load / cos(contact angle)
    delta = float(np.arctan(rail.slope(y_c)))
    hz = hertz(case.Fn / np.cos(delta), A, B, Material(mat.E, mat.nu)) if B > 1e-9 else None
    return {"y_c": float(y_c), "z_axle": float(z_axle), "r_c": r_c, "radius_of_y": radius_of_y,
            "rail": rail, "hertz": hz, "A": A, "B": B, "delta": delta,
            "lateral": np.array([0.0, np.cos(delta), np.sin(delta)]),
            "normal": np.array([0.0, -np.sin(delta), np.cos(delta)]),
            "normal_load": case.Fn / float(np.cos(delta))}


@dataclass(frozen=True, eq=False)
class Model:
    """Meshes and precomputed arrays of a case (built by :func:`build_model`).

    Nodes are numbered wheel first, then rail. ``u`` arrays have shape
    (n_nodes, 3); the generalized vector used by the implicit solvers is
    ``[u.ravel(), w]`` of length ``3 n_nodes + 1``.
    """

    case: object
    wheel: object
    rail: object
    material: object
    element: object
    edata: object               # ElementData of all elements (wheel first, then rail)
    conn: np.ndarray
    chunks: np.ndarray          # element chunks of the parallel force kernel (_solid.element_chunks)
    mass: np.ndarray            # (n_nodes,) lumped, unscaled [kg]
    fixed: np.ndarray           # (n_fixed,) node numbers
    slave: np.ndarray           # wheel surface nodes (flattened)
    slave_area: np.ndarray
    master: np.ndarray          # (nx, ny) rail surface node numbers (global)
    kn: np.ndarray              # (ns,) penalty [Pa/m]
    geometry: dict
    z_axle: float
    g0: float
    x_rail_span: tuple
    scratch: dict = field(default_factory=dict, repr=False)

    @property
    def n_nodes(self) -> int:
        return self.wheel.n_nodes + self.rail.n_nodes

    @property
    def n_elements(self) -> int:
        return self.wheel.n_elements + self.rail.n_elements

    @property
    def nw(self) -> int:
        return self.wheel.n_nodes

    @property
    def edata_w(self):
        """Element data of the wheel (views into :attr:`edata`)."""
        return self.edata[:self.wheel.n_elements]

    @property
    def edata_r(self):
        """Element data of the rail (views into :attr:`edata`)."""
        return self.edata[self.wheel.n_elements:]

    def reference(self) -> np.ndarray:
        return np.concatenate([self.wheel.nodes, self.rail.nodes])

    # -------------------------------------------------------------- kernels
    @property
    def plastic(self) -> bool:
        """True if the material carries a plastic state (:class:`wheelrail.fe.J2Plastic`)."""
        return bool(self.material.plastic)

    def _bodies(self):
        return ((self.wheel, self.edata_w, slice(0, self.nw), 0),
                (self.rail, self.edata_r, slice(self.nw, None), 1))

    def new_state(self):
        """A zero plastic state of both bodies (:class:`PlasticState`), None if elastic."""
        if not self.plastic:
            return None
        return PlasticState(np.zeros((self.n_elements, self.edata.n_points, S.NSTATE)),
                            self.wheel.n_elements)

    def internal_force(self, u, f=None, state=None, *, elastic=False):
        """Internal forces (n_nodes, 3) in the body frames and the internal energy [J].

        Parameters
        ----------
        u : ndarray, shape (n_nodes, 3)
            Displacements in the body frames [m].
        f : ndarray, optional
            Output array (overwritten).
        state : PlasticState, optional
            Required for a plastic material: the return map starts from
            ``state.committed`` and writes ``state.trial`` (the state that belongs to
            ``u``; commit it with ``state.commit()`` when the step is accepted).
        elastic : bool
            The linear elastic response (K u) whatever the material (stiffness-proportional
            damping).

        Returns
        -------
        f, energy : the forces and the elastic strain energy plus the plastic work [J]
        (``state.energies`` holds the two parts).
        """
        if f is None:
            f = np.zeros_like(u)
        plastic = self.plastic and not elastic
        if plastic and state is None:
            raise InputError("a plastic material needs its state (model.new_state())")
        lam, G = self.material.lam, self.material.shear_modulus
        hp, tp, ts = self._hardening
        ed = self.edata
        buf = self._scratch("energy", (self.n_elements, 2))
        st_in = state.committed if plastic else _NO_STATE
        st_out = state.trial if plastic else _NO_STATE
        hg = ed.hx if ed.hx.shape[0] else ed.gamma          # compact hourglass data
        S.element_forces(u, self.conn, self.chunks, ed.dNdx, ed.wdet, hg, ed.khg, lam, G,
                         plastic, hp, tp, ts, st_in, st_out, f, buf)
        e_el = float(buf[:, 0].sum())
        e_pl = float(buf[:, 1].sum())
        if plastic:
            state.energies = (e_el, e_pl)
        return f, e_el + e_pl

    def _scratch(self, name, shape):
        buf = self.scratch.get(name)
        if buf is None or buf.shape != shape:
            buf = self.scratch[name] = np.zeros(shape)
        return buf

    @property
    def _hardening(self):
        if self.plastic:
            return self.material.kernel_parameters()
        return _NO_HARDENING

    def stiffness(self, u=None, state=None):
        """Sparse stiffness (CSR) of size 3 n_nodes + 1 (the last row/column, w, is empty).

        Elastic K, or, for a plastic material with ``u`` and ``state``, the consistent
        elasto-plastic tangent of the return map from ``state.committed`` at ``u``.
        """
        import scipy.sparse as sp

        plastic = self.plastic and state is not None and u is not None
        n = 3 * self.n_nodes + 1
        lam, G = self.material.lam, self.material.shear_modulus
        hp, tp, ts = self._hardening
        mats = []
        for body, ed, sl, k in self._bodies():
            ne = body.n_elements
            off = 0 if k == 0 else self.nw
            rows = np.empty(ne * 576, np.int64)
            cols = np.empty(ne * 576, np.int64)
            vals = np.empty(ne * 576)
            if plastic:
                S.tangent_triplets(u[sl], body.elements, ed.dNdx, ed.wdet, ed.gamma, ed.khg, lam,
                                   G, True, hp, tp, ts, state.body(k), rows, cols, vals)
                rows += 3 * off
                cols += 3 * off
            else:
                K.stiffness_triplets(body.elements + off, ed.dNdx, ed.wdet, lam, G, ed.gamma,
                                     ed.khg, rows, cols, vals)
            mats.append(sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr())
        return (mats[0] + mats[1]).tocsr()

    def stress(self, u, state=None):
        """Element stresses [Pa], Voigt (xx, yy, zz, xy, yz, xz), mean over the integration
        points: (wheel (ne_w, 6), rail (ne_r, 6)), body frames. For a plastic material
        σ = C : (ε − ε_p) with the plastic strain of ``state.committed`` (the state that
        belongs to ``u``)."""
        plastic = self.plastic and state is not None
        lam, G = self.material.lam, self.material.shear_modulus
        out = []
        for body, ed, sl, k in self._bodies():
            sig = np.empty((body.n_elements, 6))
            S.element_stress(u[sl], body.elements, ed.dNdx, ed.wdet, lam, G, plastic,
                             state.body(k) if plastic else _NO_STATE, sig)
            out.append(sig)
        return out

    def von_mises(self, u, state=None):
        """Von Mises stress at the element centres [Pa]: (wheel (ne_w,), rail (ne_r,))."""
        return [S.von_mises(sig) for sig in self.stress(u, state)]

    # -------------------------------------------------------------- kinematics
    @staticmethod
    def rotation(psi: float) -> np.ndarray:
        c, s = np.cos(psi), np.sin(psi)
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])

    def slave_positions(self, u, w, psi):
        """Global positions (ns, 3) of the wheel surface nodes."""
        X = self.wheel.nodes[self.slave] + u[self.slave]
        return X @ self.rotation(psi).T + np.array([0.0, 0.0, self.z_axle + w])

    def master_positions(self, u, s):
        """Global positions (nx, ny, 3) of the rail surface nodes."""
        idx = self.master
        X = self.rail.nodes[idx - self.nw] + u[idx]
        X[..., 0] -= s
        X[..., 1] -= self.lateral_shift(s)
        return X

    def lateral_shift(self, s):
        """Lateral rail drift η s [m] after a rail travel s [m] (lateral creepage η)."""
        return self.case.creepage[1] * s

    def contact(self, u, w, psi, s, xs_prev, xm_prev, ft_old, mu, damping=None, dt=1.0):
        """Evaluate contact; returns a dict of per-slave results and the generalized forces.

        ``damping`` (ns,) [N s/m]: normal contact dashpots (explicit runs), ``dt`` the step.
        """
        xs = self.slave_positions(u, w, psi)
        xm = self.master_positions(u, s)
        ns = xs.shape[0]
        nx, ny = self.master.shape
        out = {
            "fs": np.zeros((ns, 3)), "fm": np.zeros((nx, ny, 3)), "gap": np.empty(ns),
            "pn": np.empty(ns), "ft": np.zeros((ns, 3)), "status": np.zeros(ns, np.int64),
            "cell": np.zeros((ns, 2), np.int64), "rt": np.zeros((ns, 2)),
            "normal": np.zeros((ns, 3)), "slip": np.zeros(ns), "energy": np.zeros(ns),
        }
        h = self.case.mesh_size
        cdamp = self.scratch.setdefault("no_damping", np.zeros(ns)) if damping is None else damping
        K.node_to_surface(
            (xs, xs - xs_prev, self.slave_area, self.kn, self.kn, cdamp),
            (xm, nodal_normals(xm), xm - xm_prev, self.rail.axes[0],
             self.rail.axes[1] - self.lateral_shift(s), s),
            (mu, 5.0 * h, self.g0, 1.0 / dt), ft_old,
            (out["energy"], out["fs"], out["gap"], out["pn"], out["ft"], out["status"],
             out["cell"], out["rt"], out["normal"], out["slip"]), out["fm"])
        out["xs"] = xs
        out["xm"] = xm
        return out

    def generalized_contact_force(self, c, psi):
        """Contact forces in the body frames (n_nodes, 3) and on the axle dof w."""
        f = np.zeros((self.n_nodes, 3))
        f[self.slave] = c["fs"] @ self.rotation(psi)        # Q^T f per row
        np.add.at(f, self.master.ravel(), c["fm"].reshape(-1, 3))
        return f, float(c["fs"][:, 2].sum())


def nodal_normals(xm):
    """Unit normals (nx, ny, 3) of a structured surface from differences along both axes."""
    tx = np.gradient(xm, axis=0)
    ty = np.gradient(xm, axis=1)
    n = np.cross(tx, ty)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def _axes(case, geo, h):
    hz = geo["hertz"]
    if hz is not None:
        a, b = float(hz.a), float(hz.b)
        if h > min(a, b):
            raise InputError(f"mesh_size {h!r} m is larger than the contact patch (Hertz "
                             f"semi-axes a = {a:.3g} m, b = {b:.3g} m); use mesh_size < "
                             f"{min(a, b):.3g} m")
    else:
        a = b = 5 * h
    return a, b



def _mesh_spec(case, rolling):
    """Contact geometry (with the Hertz semi-axes ``a``, ``b`` and the ``travel``) and
    the arguments of :func:`~wheelrail.fe.mesh.graded_axis` of the four axes (``x``,
    ``y``, depth ``d`` and the wheel's ``theta``): what :func:`build_model` meshes and
    :func:`mesh_size_estimate` counts, without allocating a mesh."""
    geo = contact_geometry(case)
    h = case.mesh_size
    a, b = _axes(case, geo, h)
    g = case.grading
    y_c = geo["y_c"]
    hw = case.half_width * b
    fine_y = 1.5 * b + 2 * h
    rail_prof = geo["rail"]
    wheel_lo = case.wheel.y_min + case.lateral_position
    wheel_hi = case.wheel.y_max + case.lateral_position
    y_lo = max(y_c - hw, rail_prof.y_min, wheel_lo)
    y_hi = min(y_c + hw, rail_prof.y_max, wheel_hi)
    depth = case.depth * max(a, b)
    L = case.half_length * a
    if rolling:
        travel = case.travel if case.travel is not None else default_travel(case, a)
        x_lo, x_hi = -2.5 * a - L, travel + 2.5 * a + L
        fx_lo, fx_hi = -2.5 * a, travel + 2.5 * a
    else:
        travel = 0.0
        x_lo, x_hi, fx_lo, fx_hi = -L, L, -2 * a, 2 * a
    R = geo["r_c"]
    if (x_hi - x_lo) / R > np.pi:
        raise InputError(f"travel {travel!r} m needs more than half the wheel circumference")
    spec = {"x": (x_lo, x_hi, fx_lo, fx_hi, h, g),
            "y": (y_lo, y_hi, y_c - fine_y, y_c + fine_y, h, g),
            "d": (0.0, depth, 0.0, 1.5 * a + h, h, g),
            # wheel: material ahead (theta > 0) rolls into contact; arc lengths mirror the rail's
            "theta": (x_lo / R, x_hi / R, fx_lo / R, fx_hi / R, h / R, g)}
    return dict(geo, a=a, b=b, travel=travel), spec


def build_model(case, *, rolling: bool = True) -> Model:
    """Mesh both bodies and precompute element data, masses and penalties.

    Parameters
    ----------
    case : RollingCase
    rolling : bool
        True: the rail and wheel meshes cover the rolled distance (refined all along
        the path); False: a short static mesh (refined ``±2a`` around the contact,
        ``half_length`` semi-axes long) for :func:`wheelrail.fe.indent`.
    """
    geo, spec = _mesh_spec(case, rolling)
    mat = as_fe_material(case.material, case.density)
    elem = Hex8(case.element)
    x_axis, y_axis, d_axis, th_axis = (graded_axis(*spec[k]) for k in ("x", "y", "d", "theta"))
    rail_prof = geo["rail"]
    rail = rail_body(rail_prof, x_axis, y_axis, d_axis)
    wheel = wheel_body(geo["radius_of_y"], th_axis, y_axis, d_axis)
    edata = ElementData.concatenate([elem.precompute(wheel.nodes, wheel.elements, mat),
                                     elem.precompute(rail.nodes, rail.elements, mat)])
    nw = wheel.n_nodes
    conn = np.concatenate([wheel.elements, rail.elements + nw])
    # 32 chunks, up to 64 above 16 384 elements (tasks of >= 512 elements): finer tasks shorten
    # the wait for the last task of a parallel phase of the explicit step
    target = min(max(conn.shape[0] // 512, 32), 64)
    chunks = element_chunks(conn, nw + rail.n_nodes, target)
    mass = np.zeros(nw + rail.n_nodes)
    vol = edata.volume
    np.add.at(mass, conn.ravel(), np.repeat(mat.density * vol / 8.0, 8))
    fixed = np.concatenate([wheel.fixed, rail.fixed + nw])
    slave = wheel.surface_nodes.ravel()
    area = wheel.surface_areas().ravel()
    master = rail.surface_nodes + nw
    kn = case.penalty * mat.E / np.sqrt(area)
    p_ref = float(geo["hertz"].p0) if geo["hertz"] is not None else 1e-3 * mat.E
    g0 = 0.05 * p_ref / float(np.median(kn))
    return Model(case, wheel, rail, mat, elem, edata, conn, chunks, mass, fixed, slave, area,
                 master, kn, geo, geo["z_axle"], g0, spec["x"][:2])


#: Bytes per element of a model and its explicit run state: 3.4 kB measured as the peak
#: resident memory of :func:`build_model` per element (seed000_case at 2 and 1.2 mm, 36 k
#: and 110 k elements, 3434 and 3432 B), plus the run's nodal vectors (about 0.6 kB) and,
#: for J2, the plastic state of 8 integration points (13 doubles each, 0.8 kB).
BYTES_PER_ELEMENT = {"elastic": 4.0e3, "plastic": 4.8e3}


def mesh_size_estimate(case, *, rolling: bool = True) -> dict:
    """Element and node counts and the memory of a model, before anything is allocated.

    Counts the nodes of the four graded axes that :func:`build_model` would mesh (one
    source of the mesh parameters), so a mesh of 10^12 elements is refused by the
    resource guard in microseconds instead of failing in the allocator.

    Returns
    -------
    dict
        ``n_elements``, ``n_nodes``, ``memory`` [bytes] (:data:`BYTES_PER_ELEMENT`),
        ``shape`` (nodes per axis x, y, depth, theta), the rolled ``travel`` [m] and the
        ``depth`` of the kept bodies [m].
    """
    geo, spec = _mesh_spec(case, rolling)
    nx, ny, nd, nt = (axis_size(*spec[k]) for k in ("x", "y", "d", "theta"))
    n_el = (nx - 1) * (ny - 1) * (nd - 1) + (nt - 1) * (ny - 1) * (nd - 1)
    kind = "plastic" if getattr(case.material, "yield_stress", None) is not None else "elastic"
    return {"n_elements": int(n_el), "n_nodes": int((nx + nt) * ny * nd),
            "memory": float(n_el * BYTES_PER_ELEMENT[kind]), "shape": (nx, ny, nd, nt),
            "travel": float(geo["travel"]), "depth": float(spec["d"][1])}


def default_travel(case, a: float) -> float:
    """Rolled distance: the speed ramp plus 8 semi-axes of steady rolling [m]."""
    steady = 8.0 * a
    return steady / (1.0 - case.ramp)
