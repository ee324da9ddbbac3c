"""Evaluators: what a sweep computes at each point.

An evaluator turns the input columns of one chunk into output columns. It is
the seam where other problems plug into the sweep machinery (the wheel–rail
contact solve of the contact module can be added as one more evaluator).

What an evaluator must provide
------------------------------
``name`` : str
    Registry name (``[sweep] evaluator = "..."``).
``quantities`` : tuple of str
    Input quantities it accepts (fixed values or axes).
``outputs`` : dict
    Output variable name → (dtype, units, description); every output has the
    shape of the sweep.
``check(spec)``
    Raise :class:`~wheelrail.errors.InputError` for a spec it cannot evaluate
    (missing quantity, unknown method or option), naming the value.
``evaluate(spec, columns) -> dict``
    Output arrays of shape (m,) for the m points of ``columns``, plus
    ``status`` (int8 codes of :data:`STATUS_CODES`) and ``message`` (str).
    A failing point must not abort the chunk: it gets status ``failed``, NaN
    outputs and the exception text as its message.
"""

from __future__ import annotations

import numpy as np

from .. import plausibility, profiles, tangential
from ..errors import InputError
from ..geometry import Track, Wheelset, contact_points
from ..hertzian import RADII_KEYS, hertz, hertz_from_radii, hertz_from_semiaxes
from ..materials import Material

__all__ = ["EVALUATORS", "STATUS_CODES", "get_evaluator", "CreepEvaluator"]

#: Per-point status codes stored in the ``status`` variable (0 = not computed yet: the value
#: of a chunk that was never written).
STATUS_CODES = {"pending": 0, "ok": 1, "not_converged": 2, "failed": 3}
MESSAGE_LENGTH = 160  # characters kept of a failure message


def _values(spec, name):
    """The values of ``name`` in ``spec`` (its fixed value or its axis), or None."""
    if name in spec.fixed:
        return [spec.fixed[name]]
    axes = dict(spec.axes)
    return list(axes[name].tolist()) if name in axes else None


def _check_numbers(spec, names, evaluator: str) -> None:
    """Every quantity of ``names`` given in ``spec`` must be a number (not a name)."""
    for name in names:
        values = _values(spec, name)
        if values is None:
            continue
        text = [v for v in values if isinstance(v, str)]
        if text:
            kind = "an axis" if name not in spec.fixed else "a value"
            raise InputError(f"{name} must be numbers for the {evaluator} evaluator, got "
                             f"{kind} with the name {text[0]!r}")


def _check_friction(spec) -> None:
    values = _values(spec, "mu")
    if values is None:
        return
    mu = np.asarray(values, float)
    if (mu <= 0).any():
        raise InputError(f"mu must be > 0 (a friction coefficient), got {mu[mu <= 0][0]:g}")
    plausibility.check_friction(mu)


class CreepEvaluator:
    """Creep forces of a Hertzian contact (:func:`wheelrail.creep_forces`) at each point.

    Inputs: ``xi, eta`` [-], ``phi`` [1/m], ``mu`` [-], ``Fn`` [N]; the
    contact as curvatures ``A, B`` [1/m], semi-axes ``a, b`` [m] or principal
    radii [m] (:data:`wheelrail.hertzian.RADII_KEYS`); material ``E`` [Pa],
    ``nu`` [-] (default steel, the same for wheel and rail); ``method`` (a
    name, default ``"fastsim"``). With a ``method`` axis, ``options`` maps each
    method name to its options.
    """

    name = "creep"
    quantities = ("method", "xi", "eta", "phi", "mu", "Fn", "A", "B", "a", "b", *RADII_KEYS,
                  "E", "nu")
    outputs = {
        "Fx": ("f8", "N", "longitudinal creep force on the wheel"),
        "Fy": ("f8", "N", "lateral creep force on the wheel"),
        "Mz": ("f8", "N m", "spin moment on the wheel"),
        "Fn": ("f8", "N", "normal force"),
        "a": ("f8", "m", "semi-axis of the contact ellipse along x"),
        "b": ("f8", "m", "semi-axis of the contact ellipse along y"),
        "p0": ("f8", "Pa", "maximum Hertzian pressure"),
    }

    def output_names(self, spec) -> list[str]:
        """Outputs stored for ``spec``: those that are not already an axis (e.g. ``a``, ``b``)."""
        axes = {n for n, _ in spec.axes}
        return [k for k in self.outputs if k not in axes]

    # ------------------------------------------------------------------ checks
    def _names(self, spec):
        return set(spec.fixed) | {n for n, _ in spec.axes}

    def methods(self, spec) -> list[str]:
        """Registry names of the methods of the sweep."""
        if "method" in spec.fixed:
            given = [spec.fixed["method"]]
        else:
            given = dict(spec.axes).get("method", np.array(["fastsim"], dtype=object)).tolist()
        out = []
        for m in given:
            if not isinstance(m, str):
                raise InputError(f"unknown creep-force method {m!r}; choose one of "
                                 + ", ".join(tangential.registry()))
            out.append(tangential.get_class(m, argname="creep-force").name)
        return out

    def options_for(self, spec, method: str) -> dict:
        """Options of ``method`` (flat options, or ``options[method]`` with a method axis)."""
        opts = dict(spec.options)
        if "method" in spec.fixed or "method" not in dict(spec.axes):
            return opts
        for k, v in opts.items():
            if not isinstance(v, dict) and not hasattr(v, "items"):
                raise InputError(f"with a method axis, options must be given per method "
                                 f"([sweep.options.<method>]), got option {k!r} = {v!r}")
        return {k: v for name, o in opts.items() if tangential.get_class(name).name == method
                for k, v in dict(o).items()}

    def check(self, spec) -> None:
        names = self._names(spec)
        unknown = names - set(self.quantities)
        if unknown:
            raise InputError(f"unknown quantity {sorted(unknown)[0]!r}; the creep evaluator "
                             f"takes {', '.join(self.quantities)}")
        for k in ("mu", "Fn"):
            if k not in names:
                raise InputError(f"{k!r} is required (a value or an axis)")
        groups = {"A, B": {"A", "B"} & names, "a, b": {"a", "b"} & names,
                  "radii": set(RADII_KEYS) & names}
        used = [g for g, s in groups.items() if s]
        if len(used) != 1:
            raise InputError("give the contact as exactly one of: A and B (1/m); a and b (m); "
                             f"radii ({', '.join(RADII_KEYS)}) (m); got {sorted(names & set().union(*groups.values())) or 'none'}")
        if used[0] in ("A, B", "a, b") and len(groups[used[0]]) != 2:
            raise InputError(f"give both {used[0]} (got only {sorted(groups[used[0]])})")
        if used[0] == "radii" and "wheel_rolling_radius" not in names:
            raise InputError("wheel_rolling_radius is required with radii")
        _check_numbers(spec, [q for q in self.quantities if q != "method"], "creep")
        _check_friction(spec)
        for m in self.methods(spec):
            tangential.get(m, self.options_for(spec, m))

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, spec, cols: dict) -> dict:
        """Outputs for the points of ``cols`` (see the module docstring)."""
        m = len(next(iter(cols.values())))
        out = {k: np.full(m, np.nan) for k in self.outputs}
        out["status"] = np.full(m, STATUS_CODES["ok"], dtype=np.int8)
        out["message"] = np.full(m, "", dtype=f"<U{MESSAGE_LENGTH}")
        method = cols.get("method", np.full(m, self.methods(spec)[0], dtype=object))
        E = cols.get("E", np.full(m, 2.1e11))
        nu = cols.get("nu", np.full(m, 0.28))
        keys = list(zip(method.tolist(), np.asarray(E).tolist(), np.asarray(nu).tolist()))
        for key in dict.fromkeys(keys):
            idx = np.array([i for i, k in enumerate(keys) if k == key])
            try:
                self._solve(spec, cols, idx, key, out)
            except Exception:  # noqa: BLE001 - one failing point must not fail its neighbours
                for i in idx:
                    try:
                        self._solve(spec, cols, np.array([i]), key, out)
                    except Exception as exc:  # noqa: BLE001 - recorded per point
                        out["status"][i] = STATUS_CODES["failed"]
                        text = f"{type(exc).__name__}: {' '.join(str(exc).split())}"
                        out["message"][i] = text[:MESSAGE_LENGTH]
                        for k in self.outputs:
                            out[k][i] = np.nan
        keep = set(self.output_names(spec)) | {"status", "message"}
        return {k: v for k, v in out.items() if k in keep}

    def _contact(self, cols, idx, material):
        load = cols["Fn"][idx].astype(float)
        if "A" in cols:
            return hertz(load, cols["A"][idx].astype(float), cols["B"][idx].astype(float),
                         material)
        if "a" in cols:
            return hertz_from_semiaxes(cols["a"][idx].astype(float),
                                       cols["b"][idx].astype(float), load, material)
        radii = {k: cols[k][idx].astype(float) for k in RADII_KEYS if k in cols}
        return hertz_from_radii(load, material=material, **radii)

    def _solve(self, spec, cols, idx, key, out) -> None:
        method, E, nu = key
        contact = self._contact(cols, idx, Material(E, nu))
        opts = self.options_for(spec, method)
        decl = tangential.get_class(method).option_declarations()
        if "on_fail" in decl:
            opts.setdefault("on_fail", "status")  # a non-converged point is recorded, not raised
        if "progress" in decl:
            opts.setdefault("progress", False)    # the sweep shows its own progress
        impl = tangential.get(method, opts)
        creep = np.stack([cols.get(k, np.zeros(len(cols["mu"])))[idx].astype(float)
                          for k in ("xi", "eta", "phi")], axis=1)
        r = impl.forces(contact, creep, cols["mu"][idx].astype(float))
        for k, v in (("Fx", r.Fx), ("Fy", r.Fy), ("Mz", r.Mz), ("Fn", contact.Fn),
                     ("a", contact.a), ("b", contact.b), ("p0", contact.p0)):
            out[k][idx] = np.asarray(v, float).reshape(-1)
        conv = (r.info or {}).get("converged")
        if conv is not None:
            bad = ~np.asarray(conv, bool).reshape(-1)
        else:
            bad = np.full(len(idx), r.status.value == "not_converged")
        out["status"][idx] = np.where(bad, STATUS_CODES["not_converged"], STATUS_CODES["ok"])
        out["message"][idx] = np.where(bad, "not converged (last iterate stored)", "")


_GEOM_SIDE = {"contact_angle": ("rad", "contact angle of the primary point"),
              "rolling_radius": ("m", "rolling radius of the primary point"),
              "A": ("1/m", "longitudinal combined curvature at the primary point"),
              "B": ("1/m", "lateral combined curvature at the primary point"),
              "wheel_y": ("m", "lateral position of the primary point on the wheel profile")}


class GeometryEvaluator:
    """Rigid contact geometry of a wheelset on a track (:func:`wheelrail.contact_points`).

    Inputs: ``y`` lateral shift [m] and ``yaw`` [rad] (default 0); profiles
    ``wheel`` and ``rail`` (a standard name such as ``"S1002"``/``"60E1"`` or a
    profile file path; names make them an axis); ``gauge`` [m] (1.435),
    ``inclination`` [-] (1/40), ``nominal_radius`` [m] (0.46), ``flange_back``
    [m] (1.360). Options: ``tolerance``, ``step`` [m] of the contact search.

    Outputs: ``delta_r`` [m], ``roll`` [rad], ``z`` [m] and, for the primary
    (rigid) contact point of each side, ``contact_angle_<side>`` [rad],
    ``rolling_radius_<side>`` [m], ``A_<side>``, ``B_<side>`` [1/m] (Hertz
    curvatures: where a wheel–rail creep-force solve plugs in),
    ``wheel_y_<side>`` [m] and ``n_contact_<side>`` (points within the tolerance).
    """

    name = "geometry"
    quantities = ("wheel", "rail", "y", "yaw", "gauge", "inclination", "nominal_radius",
                  "flange_back")
    _DEFAULTS = {"wheel": "S1002", "rail": "60E1", "yaw": 0.0, "gauge": 1.435,
                 "inclination": 1.0 / 40.0, "nominal_radius": 0.46, "flange_back": 1.360}
    outputs = {
        "delta_r": ("f8", "m", "rolling radius difference right - left"),
        "roll": ("f8", "rad", "roll angle of the wheelset"),
        "z": ("f8", "m", "height of the axle centre"),
        **{f"{k}_{side}": ("f8", u, f"{d}, {side}") for side in ("left", "right")
           for k, (u, d) in _GEOM_SIDE.items()},
        **{f"n_contact_{side}": ("f8", "1", f"contact points within the tolerance, {side}")
           for side in ("left", "right")},
    }
    options = {"tolerance": 1e-4, "step": 2e-4}

    def output_names(self, spec) -> list[str]:
        return list(self.outputs)

    def methods(self, spec) -> list[str]:
        return ["contact_points"]

    def options_for(self, spec, method) -> dict:
        return {**self.options, **dict(spec.options)}

    def check(self, spec) -> None:
        names = set(spec.fixed) | {n for n, _ in spec.axes}
        unknown = names - set(self.quantities)
        if unknown:
            raise InputError(f"unknown quantity {sorted(unknown)[0]!r}; the geometry evaluator "
                             f"takes {', '.join(self.quantities)}")
        if "y" not in names:
            raise InputError("'y' (lateral shift, m) is required (a value or an axis)")
        extra = set(spec.options) - set(self.options)
        if extra:
            raise InputError(f"the geometry evaluator does not accept option(s) "
                             f"{', '.join(sorted(extra))}; allowed: tolerance, step")
        _check_numbers(spec, [q for q in self.quantities if q not in ("wheel", "rail")],
                       "geometry")
        for k in ("wheel", "rail"):
            values = [spec.fixed[k]] if k in spec.fixed else dict(spec.axes).get(k, [])
            for v in list(values):
                if not isinstance(v, str):
                    raise InputError(f"{k} must be a profile name or file, got {v!r}")
                self._profile(v)  # unknown names fail now, not in every point

    @staticmethod
    def _profile(name):
        from pathlib import Path


        return profiles.read(name) if Path(name).is_file() else profiles.load(name)

    def evaluate(self, spec, cols: dict) -> dict:
        m = len(next(iter(cols.values())))
        out = {k: np.full(m, np.nan) for k in self.outputs}
        out["status"] = np.full(m, STATUS_CODES["ok"], dtype=np.int8)
        out["message"] = np.full(m, "", dtype=f"<U{MESSAGE_LENGTH}")
        val = {k: cols.get(k, np.full(m, v, dtype=object if isinstance(v, str) else float))
               for k, v in self._DEFAULTS.items()}
        opts = self.options_for(spec, None)
        cache = {}
        for i in range(m):
            try:
                key = tuple(val[k][i] for k in ("wheel", "rail", "gauge", "inclination",
                                                 "nominal_radius", "flange_back"))
                if key not in cache:
                    cache[key] = (Wheelset(self._profile(key[0]), nominal_radius=float(key[4]),
                                           flange_back=float(key[5])),
                                  Track(self._profile(key[1]), gauge=float(key[2]),
                                        inclination=float(key[3])))
                ws, tr = cache[key]
                cp = contact_points(ws, tr, float(cols["y"][i]), float(val["yaw"][i]), **opts)
                out["delta_r"][i], out["roll"][i], out["z"][i] = cp.delta_r, cp.roll, cp.z
                for side in ("left", "right"):
                    sc = cp.side(side)
                    j = sc.primary
                    for k in _GEOM_SIDE:
                        out[f"{k}_{side}"][i] = getattr(sc, k)[j]
                    out[f"n_contact_{side}"][i] = sc.n
            except Exception as exc:  # noqa: BLE001 - recorded per point
                out["status"][i] = STATUS_CODES["failed"]
                out["message"][i] = f"{type(exc).__name__}: {' '.join(str(exc).split())}"[
                    :MESSAGE_LENGTH]
        return out


#: Registry of evaluators: name -> instance.
EVALUATORS = {"creep": CreepEvaluator(), "geometry": GeometryEvaluator()}


def get_evaluator(name):
    """The evaluator registered as ``name``."""
    if not isinstance(name, str) or name not in EVALUATORS:
        raise InputError(f"unknown sweep evaluator {name!r}; choose one of "
                         + ", ".join(EVALUATORS))
    return EVALUATORS[name]
