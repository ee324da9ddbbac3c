"""``wheelrail fe CASE.toml``: finite-element rolling contact (or static indentation) of a case file.

The case file holds one ``[fe]`` table; every key is a
:class:`wheelrail.fe.RollingCase` field, plus

* ``wheel`` / ``rail`` — a standard profile name (``"S1002"``, ``"60E1"``), a
  profile file path (relative to the case file), or for the wheel
  ``"cylinder"`` / ``"cone"`` (a straight tread 80 mm wide, taper ``wheel_taper``,
  default 1/10), for the rail ``"arc"`` (a head arc of ``rail_head_radius`` [m],
  default 0.3; the Hertzian case of Toumi et al. (2016) is ``wheel = "cone"``, ``rail = "arc"``,
  ``inclination = 0.0996686525`` = arctan(1/10));
* ``E``, ``nu`` — the material (default steel 210 GPa, 0.28);
* elasto-plastic bodies (:class:`wheelrail.fe.J2Plastic`): ``material = "r900a"`` (the R900A
  steel of Toumi, Chollet & Yin 2016: yield 489 MPa, Voce hardening), or ``yield_stress``
  [Pa] with optional ``hardening`` (a modulus [Pa], or ``[[plastic strains], [yield
  stresses]]``), ``hardening_saturation`` [Pa] and ``hardening_rate`` (Voce),
  ``kinematic`` [Pa] and ``kinematic_recovery`` (Prager / Armstrong–Frederick); any of them
  also overrides the R900A values;
* ``toumi2016 = "table3"`` or ``"printed"`` — start from the case of Toumi et al. (2016)
  (:func:`wheelrail.fe.seed000_case`; ``wheel``/``rail`` not needed, other keys override,
  e.g. ``plastic = true``); the old key ``seed000`` still works and is deprecated;
* ``mode`` — ``"roll"`` (default) or ``"indent"``;
* ``transition = "reduced"`` or ``"full"`` — the one- to two-point contact transition of a
  half-wheelset on a flexible track (:func:`wheelrail.fe.seed004_case`; the old key
  ``seed004`` still works and is deprecated; every other key is a
  :class:`wheelrail.fe.TransitionCase` field, e.g. ``angle_of_attack = 0.025``,
  ``mesh_size = 4e-3``, ``travel = 0.1``; ``wheel``/``rail`` optional; ``[fe.track]`` and
  ``[fe.suspension]`` tables give :class:`wheelrail.fe.TrackStructure` and
  :class:`wheelrail.fe.WheelSuspension` fields, e.g. ``lateral_stiffness = 0.0`` for free
  lateral motion, ``roll_stiffness = 1.44e7`` for the wheel's roll on its half-axle).
  Writes
  patches.nc (per-patch histories), history.nc, summary.json, transition.png, restart.npz
  and, with ``wave_time`` > 0, wave.png and wave.npz (``x``, ``t``, ``v`` of the rail line
  ``wave_line`` from ``wave_travel``: :func:`wheelrail.fe.transition.phase_velocity` reads it as a
  dict); with ``field_travel = [FROM, TO]`` (m of
  travel) also contact_fields.nc (pressure, shear, micro-slip, adhesion/slip per wheel
  surface node at every ``field_stride``-th output) and contact_fields_stress.png /
  contact_fields_slip.png (maps of both patches around the first flange patch).

A plastic run also writes fields.nc (equivalent plastic strain, stresses, von Mises per
element) and, with ``passes > 1``, passes.nc; restart files carry the plastic state.

Example::

    [fe]
    wheel = "cylinder"
    rail = "60E1"
    radius = 0.46
    Fn = 7500.0
    creepage = [7e-4, 0.0, 0.0]
    mu = 0.2
    mesh_size = 1.5e-3
    integrator = "explicit"
"""

from __future__ import annotations

from ._output import esc

HELP = "finite-element rolling contact (or static indentation) of an [fe] case file"

#: Time model of an explicit run: wall time on an unloaded machine with cached kernels, on
#: the numba threads of the process (one or two; more are estimated as two): the model's
#: build and output (:data:`BUILD_COST`), then per step a fixed cost (:data:`STEP_COST`) plus
#: a cost per element (:data:`COST_PER_ELEMENT_STEP`).
#:
#: Per element and step: the time loop of the one-region kernel
#: (:func:`wheelrail.fe._explicit.run_steps`: element forces and plasticity, contact, node
#: update, bookkeeping) of Toumi et al.'s case on the 1 mm mesh (47 736 reduced hex8 x 7 533
#: steps), measured on the idle 2-core machine on 2026-11-27 (load 1.0–1.9; ``python
#: benchmarks/bench_fe_plastic.py speed --mesh 1e-3 --travel 0.004``, its "time loop only"
#: line; the whole runs: 163.7 / 214.7 ns on one thread, 106.3 / 127.3 ns on two):
#: 160.7 ns elastic and 212.1 ns plastic on one thread, 102.9 and 123.9 ns on two. Full hex8
#: (8 points): 2.5 times the reduced element (2.3–2.9 measured on the rolling case of
#: tests/fe/test_fe_cli.py at 1.5 and 1 mm, 2 904 and 8 370 elements, one thread, CPU time,
#: load 3.6–4.7, 2026-11-27); its two-thread factor is taken as the reduced one's.
#:
#: Per step: the serial parts that do not grow with the elements (rail surface, contact
#: scatter and sums, axle, one Python call per block of steps): the intercept of the
#: one-thread CPU time per step against the elements, rolling case of tests/fe/test_fe_cli.py
#: at 2, 1.5 and 1 mm (952, 2 904 and 8 370 elements: 0.246, 0.694 and 1.79 ms per step;
#: load 3.6–3.8, 2026-11-27). The time loop before the one-region kernel cost
#: 1.4 ms per step and 230 ns per element.
STEP_COST = 5e-5
COST_PER_ELEMENT_STEP = {"full": 2.5 * 160.7e-9, "reduced": 160.7e-9}
#: Plastic / elastic cost of the per-element part of a step on one thread (J2 return
#: mapping at the integration points): 212.1 / 160.7.
PLASTIC_COST_FACTOR = 212.1 / 160.7
#: Two-thread / one-thread wall time of the per-element part, elastic and plastic:
#: 102.9 / 160.7 and 123.9 / 212.1.
TWO_THREAD_FACTOR = {False: 102.9 / 160.7, True: 123.9 / 212.1}
#: Build of the model and the results (all but the time loop): fixed and per element [s]
#: (1.08 s at 47 736 elements, the 1 mm run above; 0.46 s at 8 370, the 1 mm rolling case of
#: tests/fe/test_fe_cli.py).
BUILD_COST = (0.3, 1.7e-5)
#: First run only: numba compiles the FE kernels, cached afterwards (measured 88 s on an idle
#: 2-core machine, 79 s of it the time loop ``run_steps``, in a fresh numba cache).
COMPILE_SECONDS = 90.0


def _threads() -> int:
    """The numba threads the FE kernels will run on."""
    import numba

    return numba.get_num_threads()


def seconds_estimate(case, n_elements: int, steps: float, plastic: bool,
                     threads: int | None = None) -> float:
    """Estimated wall time [s] of an explicit run of ``steps`` steps on ``n_elements``
    elements on ``threads`` numba threads (default: the process's): model build, steps ×
    (:data:`STEP_COST` + elements × :data:`COST_PER_ELEMENT_STEP` × the plastic and
    two-thread factors) and, when the FE kernels are not cached yet, their compilation."""
    threads = _threads() if threads is None else threads
    per_element = COST_PER_ELEMENT_STEP[case.element] * (PLASTIC_COST_FACTOR if plastic else 1.0)
    if threads >= 2:
        per_element *= TWO_THREAD_FACTOR[bool(plastic)]
    seconds = BUILD_COST[0] + BUILD_COST[1] * n_elements + steps * (STEP_COST + n_elements
                                                                    * per_element)
    return seconds + (COMPILE_SECONDS if not _kernels_cached() else 0.0)


def _kernels_cached() -> bool:
    """Whether the explicit FE loop has a valid numba cache (else the run compiles it)."""
    try:
        from .._numba_cache import is_cached
        from ..fe import _explicit

        # the entry point of the explicit rolling loop (the kernels it calls are compiled
        # into it; inlined helpers have no cache of their own)
        return is_cached(_explicit.run_steps)
    except Exception:  # pragma: no cover - numba internals moved: assume cached
        return True


def _steps_between_writes(text: str) -> int:
    """``--restart-every N``: an integer >= 1 (argparse reports anything else in one line)."""
    import argparse

    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number of steps >= 1, got "
                                         f"{text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number of steps >= 1 (steps between "
                                         f"restart writes; leave it out for a tenth of the "
                                         f"steps), got {n}")
    return n


def _travel(text: str) -> float:
    """``--stop-travel M``: a finite length > 0 [m]."""
    import argparse
    import math

    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not (math.isfinite(v) and v > 0):
        raise argparse.ArgumentTypeError(f"must be a travel > 0 in metres, got {text!r}")
    return v


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with an [fe] table")
    p.add_argument("--out", metavar="DIR", default="fe_out",
                   help="output directory (default fe_out): summary.json, history.csv, "
                        "patch.nc, mesh.vtu, patch.png (pressure, shear), history.png, "
                        "von_mises_surface.png, restart.npz; plastic: fields.nc, "
                        "plastic_strain_section.png, plastic_strain_surface.png (passes.nc, "
                        "passes.png)")
    p.add_argument("--mode", choices=("roll", "indent"), default=None,
                   help="override the case's mode")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--estimate-only", action="store_true",
                   help="print the mesh size and the time estimate, then stop")
    p.add_argument("--restart", metavar="FILE", default=None,
                   help="continue a rolling run from this restart file (DIR/restart.npz of "
                        "an earlier run of the same case)")
    p.add_argument("--restart-every", metavar="N", type=_steps_between_writes, default=None,
                   help="write DIR/restart.npz every N rolling steps (default: a tenth of "
                        "the steps)")
    p.add_argument("--stop-travel", metavar="M", type=_travel, default=None,
                   help="transition cases: stop once the wheel has rolled M metres, writing "
                        "DIR/restart.npz there (continue with --restart; the output keys, "
                        "e.g. field_travel, may change in between)")


def _profile(value, kind, base, param=0.0, source="case file"):
    """The ``wheel`` or ``rail`` of an [fe] table: a standard name, a file (relative to the
    case file), or the built-in shapes. A profile of the other body (a rail file given as
    the wheel: its header, comment or extension says so, or it reads only as the other
    body) is refused naming the file and why: wheel and rail swapped?"""
    import warnings

    import numpy as np

    import wheelrail as wr
    from ..errors import CaseFileError, ProfileError
    from ..profiles.io import declared_kind

    if not isinstance(value, str):
        raise CaseFileError(f"{source}: [fe] {kind} must be a profile name or file, got "
                            f"{value!r}")
    if kind == "wheel" and value.lower() in ("cylinder", "cone"):
        y = np.linspace(-0.04, 0.04, 17)
        return wr.Profile(y, param * y if value.lower() == "cone" else 0 * y, kind="wheel",
                          name=value)
    if kind == "rail" and value.lower() == "arc":
        return wr.fe.head_arc_rail(param)
    other = "rail" if kind == "wheel" else "wheel"
    where = f"{source}: [fe] {kind} = {value!r}"
    swapped = f"give it as {other} = {value!r} (wheel and rail swapped?)"
    path = base / value
    if not path.is_file():
        p = wr.profiles.load(value)
        if p.kind != kind:
            raise CaseFileError(f"{where} is a standard {p.kind} profile, not a {kind} "
                                f"profile; {swapped}")
        return p
    said, why = declared_kind(path)
    if said is not None and said != kind:
        raise CaseFileError(f"{where}: {path.name} is a {said} profile ({why}), not a "
                            f"{kind} profile; {swapped}")
    try:
        return wr.profiles.read(path, kind=kind)
    except ProfileError as exc:
        if said is None:  # the file does not say: does it read as the other body?
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    wr.profiles.read(path, kind=other)
            except ProfileError:
                raise exc from None
            raise CaseFileError(f"{where}: {path.name} is not a {kind} profile but reads as "
                                f"a {other} profile ({exc}); {swapped}") from None
        raise


def case_from_toml(path):
    """A :class:`RollingCase` and the mode from the ``[fe]`` table of a TOML file."""
    import sys
    from pathlib import Path

    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib

    from ..errors import CaseFileError
    from ..fe import RollingCase

    from .._toml import Reader, read_input

    path = Path(path)
    try:
        doc = tomllib.loads(read_input(path).decode("utf-8", errors="replace"))
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{path}: {exc}") from exc
    if "fe" not in doc:
        raise CaseFileError(f"{path}: no [fe] table")
    r = Reader(str(path))
    t = dict(doc["fe"])
    mode = t.pop("mode", "roll")
    if mode not in ("roll", "indent"):
        raise CaseFileError(f"{path}: [fe] mode must be 'roll' or 'indent', got {mode!r}")
    seed4 = _case_key(t, "transition", "seed004", path)
    if seed4 is not None:
        from ..fe import TrackStructure, TransitionCase, WheelSuspension, seed004_case

        r.unknown("fe", t, ("mode", "transition", *_init_fields(TransitionCase)))
        for key, kind in (("wheel", "wheel"), ("rail", "rail")):
            if key in t:
                t[key] = _profile(t[key], kind, path.parent, source=path)
        # [fe.track] and [fe.suspension] tables: TrackStructure / WheelSuspension fields
        for key, cls in (("track", TrackStructure), ("suspension", WheelSuspension)):
            if isinstance(t.get(key), dict):
                r.unknown(f"fe.{key}", t[key], _init_fields(cls))
                with _named(path, f"fe.{key}", cls, t[key]):
                    t[key] = cls(**t[key])
        with _named(path, "fe"):
            return seed004_case(size=seed4, **t), "transition"
    seed = _case_key(t, "toumi2016", "seed000", path)
    fn = _case_key(t, "Fn", "load", path)
    if fn is not None:
        t["Fn"] = fn
    r.unknown("fe", t, ("mode", "toumi2016", "transition", *_init_fields(RollingCase),
                        *_FE_EXTRA_KEYS, *_PLASTIC_KEYS,
                        *(("plastic",) if seed is not None else ())))
    taper = float(t.pop("wheel_taper", 0.1))
    head = float(t.pop("rail_head_radius", 0.3))
    if seed is None:
        for key in ("wheel", "rail"):
            if key not in t:
                raise CaseFileError(f"{path}: [fe] needs '{key}'")
    for key, kind, param in (("wheel", "wheel", taper), ("rail", "rail", head)):
        if key in t:
            t[key] = _profile(t[key], kind, path.parent, param, source=path)
    with _named(path, "fe"):
        material = _material(t, path, case_default=seed is not None)
    if material is not None:
        t["material"] = material
    for key in ("creepage", "rayleigh"):
        if key in t:
            t[key] = tuple(t[key])
    with _named(path, "fe"):
        if seed is not None:
            from ..fe import seed000_case

            return seed000_case(load=seed, **t), mode
        return RollingCase(**t), mode


#: Keys of an [fe] table of a rolling case besides the RollingCase fields.
_FE_EXTRA_KEYS = ("wheel_taper", "rail_head_radius", "E", "nu")


def _init_fields(cls) -> tuple:
    """The keyword arguments of a case dataclass (its fields but ``meta``)."""
    import dataclasses

    return tuple(f.name for f in dataclasses.fields(cls) if f.init and f.name != "meta")


class _named:
    """Context: an :class:`InputError` (or a TypeError / ValueError of a value of the wrong
    type) raised while a case is made from a table becomes a :class:`CaseFileError` naming
    the file and the table; with ``cls`` and ``values`` (a sub-table made into ``cls``) also
    the key whose value alone is refused."""

    def __init__(self, path, table, cls=None, values=None):
        self.where, self.cls, self.values = f"{path}: [{table}]", cls, values or {}

    def __enter__(self):
        return self

    def _culprit(self) -> str:
        for k, v in self.values.items():
            try:
                self.cls(**{k: v})
            except Exception:  # noqa: BLE001 - any failure of the value alone names it
                return f" {k} = {v!r}:"
        return ""

    def __exit__(self, typ, exc, tb):
        from ..errors import CaseFileError, InputError

        if exc is None or isinstance(exc, CaseFileError):
            return False
        if isinstance(exc, (InputError, TypeError, ValueError)):
            key = self._culprit() if self.cls is not None else ""
            raise CaseFileError(f"{self.where}{key} {exc}") from None
        return False


_PLASTIC_KEYS = ("yield_stress", "hardening", "hardening_saturation", "hardening_rate",
                 "kinematic", "kinematic_recovery")


def _case_key(t, key, old, path):
    """Pop a named-case key of an [fe] table, accepting its deprecated old name."""
    import warnings

    from .._toml import RenamedKeyWarning
    from ..errors import CaseFileError

    if old in t:
        if key in t:
            raise CaseFileError(f"{path}: [fe] gives both {key!r} and its old name {old!r}")
        warnings.warn(f"{path}: [fe] key {old!r} is deprecated, use {key!r}",
                      RenamedKeyWarning, stacklevel=3)
        return t.pop(old)
    return t.pop(key, None)


def _material(t, path, case_default=False):
    """The material of an [fe] table (popping its keys); None keeps the case default.

    With ``case_default`` (a named case) and no material keys the named case's own
    material is kept (None), so its ``plastic`` option still applies.
    """
    import wheelrail as wr
    from ..errors import CaseFileError
    from ..fe import J2Plastic, Voce, r900a

    name = t.pop("material", None)
    E, nu = t.pop("E", None), t.pop("nu", None)
    plastic = {k: t.pop(k) for k in _PLASTIC_KEYS if k in t}
    if name is not None and str(name).lower() != "r900a":
        raise CaseFileError(f"{path}: [fe] material must be 'r900a' (or give E, nu, "
                            f"yield_stress ...), got {name!r}")
    if name is None and not plastic:
        if E is None and nu is None and not case_default:
            return wr.Material(E=2.1e11, nu=0.28)
        if E is None and nu is None:
            return None
        return wr.Material(E=2.1e11 if E is None else E, nu=0.28 if nu is None else nu)
    base = r900a() if name is not None else None
    args = dict(E=E if E is not None else (base.E if base else 2.1e11),
                nu=nu if nu is not None else (base.nu if base else 0.28),
                yield_stress=plastic.get("yield_stress", base.yield_stress if base else None),
                hardening=base.hardening if base else 0.0)
    if args["yield_stress"] is None:
        raise CaseFileError(f"{path}: [fe] plastic keys need yield_stress (or material = "
                            f"'r900a')")
    if "hardening_saturation" in plastic or "hardening_rate" in plastic:
        args["hardening"] = Voce(plastic.get("hardening_saturation", 0.0),
                                 plastic.get("hardening_rate", 0.0))
    if "hardening" in plastic:
        h = plastic["hardening"]
        args["hardening"] = tuple(h) if isinstance(h, list) else h
    for k in ("kinematic", "kinematic_recovery"):
        if k in plastic:
            args[k] = plastic[k]
    return J2Plastic(**args)


def estimate(case, model) -> tuple[int, float]:
    """Steps and estimated time [s] of an explicit run of a built model
    (:func:`seconds_estimate`)."""
    import numpy as np

    from ..fe.explicit import relaxation_steps, time_step
    from ..fe.rolling import speed_profile

    dt, _ = time_step(case, model)
    _, t_end = speed_profile(case, model.geometry["travel"])
    n1, _ = relaxation_steps(case, model, dt)
    steps = case.passes * (int(np.ceil(t_end / dt)) + n1)
    return steps, seconds_estimate(case, model.n_elements, steps, model.plastic)


def _steps_before_build(case, size) -> float:
    """Explicit steps of a run, before the mesh is built: the stable step is the smaller of
    the element limit h / c and the contact-spring limit √(m / k) of a surface node
    (m = ρ h³ / 2 scaled, k = penalty E h; damping factor of the contact dashpots), within
    20 % of the built model's (:func:`wheelrail.fe.rolling.stable_time_step`); plus the
    dynamic relaxation (12 periods of the kept bodies' thickness mode)."""
    import numpy as np

    from ..fe.materials import as_fe_material
    from ..fe.rolling import contact_damping_factor, speed_profile

    mat = as_fe_material(case.material, case.density)
    h = case.mesh_size
    c = mat.wave_speed / np.sqrt(case.mass_scaling)
    dt_c = np.sqrt(mat.density * case.mass_scaling * h * h / (2.0 * case.penalty * mat.E))
    dt = case.time_step or case.courant * min(h / c, dt_c * contact_damping_factor(
        case.contact_damping))
    _, t_end = speed_profile(case, size["travel"])
    omega1 = np.pi * c / (2.0 * size["depth"])
    return case.passes * float(np.ceil(t_end / dt) + np.ceil(12 * 2 * np.pi / omega1 / dt))


def _check_size(case, mode) -> None:
    """Refuse, before anything is allocated, a mesh past the memory limit or an explicit run
    past the time limit (:func:`seconds_estimate` with the steps of
    :func:`_steps_before_build`)."""
    from .. import _resources
    from ..fe.model import mesh_size_estimate

    size = mesh_size_estimate(case, rolling=(mode == "roll"))
    n = size["n_elements"]
    seconds = 0.0
    if mode == "roll" and case.integrator == "explicit":
        plastic = getattr(case.material, "yield_stress", None) is not None
        steps = _steps_before_build(case, size)
        seconds = seconds_estimate(case, n, steps, plastic)
        detail = f"about {steps:.3g} explicit steps; measured cost per element and step"
    else:
        detail = "elements counted from the mesh parameters"
    _resources.check(f"FE mesh of {n:.3g} elements ({case.mesh_size:g} m)", seconds,
                     size["memory"], detail)


def _surface_figures(r, model, out) -> None:
    """von_mises_surface.png (and, plastic, plastic_strain_surface.png): the rail's running
    surface from above and a longitudinal section, in the manner of Toumi et al. (2016) Fig. 9
    (:func:`wheelrail.fe.plots.plot_surface`; the elastic stresses if the run is elastic)."""
    from ..fe.plots import plot_surface
    from ..fe.rolling import stress_fields

    fields = r.fields if r.fields is not None else stress_fields(model, r.u)
    g = model.geometry
    sy = getattr(model.material, "yield_stress", None)
    plot_surface(fields, "rail_von_mises", y_section=g["y_c"], depth_max=4 * g["a"],
                 yield_stress=sy, path=out / "von_mises_surface.png")
    if r.fields is not None:
        plot_surface(fields, "rail_equivalent_plastic_strain", y_section=g["y_c"],
                     depth_max=4 * g["a"], path=out / "plastic_strain_surface.png")


def run(args, console) -> int:
    import json
    from pathlib import Path

    from ..fe import indent, solve, write_vtu
    from ..fe.model import build_model

    case, mode = case_from_toml(args.case)
    if mode == "transition":
        return _run_transition(case, args, console)
    if args.stop_travel is not None:
        from ..errors import CaseFileError

        raise CaseFileError(f"--stop-travel {args.stop_travel!r} is for transition cases "
                            f"(a 'transition' key in the [fe] table); {args.case} is not one")
    mode = args.mode or mode
    out = Path(args.out)
    _check_size(case, mode)
    model = build_model(case, rolling=(mode == "roll"))
    console.print(f"[bold]FE {mode}[/]: {model.n_elements} hex8 elements ({case.element}), "
                  f"{model.n_nodes} nodes, mesh {case.mesh_size * 1e3:g} mm, "
                  f"integrator {case.integrator if mode == 'roll' else 'static'}")
    if mode == "roll" and case.integrator == "explicit":
        from .. import _resources
        from ..fe.model import mesh_size_estimate

        steps, seconds = estimate(case, model)
        nthr = _threads()
        console.print(f"estimate: {steps} explicit steps, about {_resources._duration(seconds)} "
                      f"on {nthr} thread{'s' if nthr > 1 else ''}"
                      + ("" if _kernels_cached()
                         else " (including compiling the FE kernels, once)"))
        _resources.check(f"FE run of {model.n_elements} elements x {steps} steps", seconds,
                         mesh_size_estimate(case)["memory"], "measured cost per element and step")
    if args.estimate_only:
        return 0
    out.mkdir(parents=True, exist_ok=True)
    summary = {"mode": mode, "n_elements": model.n_elements, "mesh_size": case.mesh_size}
    hz = model.geometry["hertz"]
    if hz is not None:
        summary["hertz"] = {"p_max": float(hz.p0), "a": float(hz.a), "b": float(hz.b)}
    if mode == "indent":
        r = indent(case)
        summary.update(p_max=r.p_max, a=r.a, b=r.b, Fn=r.Fn, approach=r.approach)
        patch, u, mu = r.patch, r.u, case.mu or 0.3
        model = r.model
    else:
        r = solve(case, progress=True, restart=args.restart, restart_file=out / "restart.npz",
                  restart_every=args.restart_every)
        summary.update(Fx=r.Fx, Fy=r.Fy, Fy_contact=r.Fy_contact, p_max=r.p_max, a=r.a, b=r.b,
                       tau_max=float(r.patch.shear.max()),
                       **{k: float(v) for k, v in r.info.items()})
        summary["steady"] = {k: (list(v) if isinstance(v, tuple) else v)
                             for k, v in r.steady.items()}
        if r.fields is not None:
            r.fields.to_netcdf(out / "fields.nc")
            summary["equivalent_plastic_strain_max"] = float(
                r.fields.rail_equivalent_plastic_strain.max())
            summary["von_mises_max"] = float(r.fields.rail_von_mises.max())
        if r.passes is not None:
            r.passes.to_netcdf(out / "passes.nc")
        if args.restart:
            console.print(f"continued from {esc(args.restart)} (step {r.info['restarted_at_step']})")
        r.dataset.to_dataframe().to_csv(out / "history.csv")
        patch, u, mu = r.patch, r.u, case.mu
        model = r.model
    patch.to_netcdf(out / "patch.nc")
    write_vtu(out / "mesh.vtu", model, u, state=r.state)
    if mode == "indent" and r.fields is not None:
        r.fields.to_netcdf(out / "fields.nc")
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    if not args.no_figures:
        from ..fe.plots import plot_history, plot_patch

        plot_patch(patch, mu, path=out / "patch.png")
        if mode == "roll":
            plot_history(r.dataset, path=out / "history.png")
        if r.fields is not None:
            from ..fe.plots import plot_section

            plot_section(r.fields, "rail_equivalent_plastic_strain", y=model.geometry["y_c"],
                         path=out / "plastic_strain_section.png",
                         depth_max=3 * model.geometry["a"])
        if mode == "roll":
            _surface_figures(r, model, out)
        if mode == "roll" and r.passes is not None:
            from ..fe.plots import plot_passes

            plot_passes(r.passes, path=out / "passes.png")
    for k in ("Fx", "Fy", "p_max", "a", "b"):
        if k in summary:
            scale, unit = {"p_max": (1e-6, "MPa"), "a": (1e3, "mm"), "b": (1e3, "mm")}.get(
                k, (1.0, "N"))
            console.print(f"  {k:6s} = {summary[k] * scale:10.4g} {unit}")
    console.print(f"written to {esc(out)}/")
    return 0


def _run_transition(case, args, console) -> int:
    """``wheelrail fe`` for a transition case (``transition`` in the [fe] table)."""
    import json
    from pathlib import Path

    from .. import _resources
    from ..fe import run_transition
    from ..fe.transition import build_transition_model

    out = Path(args.out)
    model = build_transition_model(case)
    est = run_transition(case, model=model, estimate_only=True)
    console.print(f"[bold]FE transition[/]: {model.n_elements} hex8 elements, {model.n_nodes} "
                  f"nodes, mesh {case.mesh_size * 1e3:g} mm, angle of attack "
                  f"{case.angle_of_attack * 1e3:g} mrad, travel {case.travel * 1e3:g} mm")
    console.print(f"estimate: {est['steps']} explicit steps of {est['time_step'] * 1e9:.0f} ns, "
                  f"about {_resources._duration(est['estimate_s'])} of CPU")
    _resources.check(f"FE transition run of {model.n_elements} elements x {est['steps']} steps",
                     est["estimate_s"], 400.0 * model.n_nodes + 2000.0 * model.n_elements,
                     "measured cost per element and step")
    if args.estimate_only:
        return 0
    out.mkdir(parents=True, exist_ok=True)
    r = run_transition(case, model=model, progress=True, restart=args.restart,
                       restart_file=out / "restart.npz",
                       restart_every=args.restart_every or 0,
                       stop_travel=args.stop_travel)
    r.patches.to_netcdf(out / "patches.nc")
    r.history.to_netcdf(out / "history.nc")
    if r.contact_fields is not None:
        r.contact_fields.to_netcdf(out / "contact_fields.nc")
    if r.info.get("wave") is not None:
        import numpy as np

        np.savez_compressed(out / "wave.npz", **{k: np.asarray(v) for k, v in
                                                 r.info["wave"].items() if k != "vz"})
    info = {k: v for k, v in r.info.items() if k not in ("fields", "wave")}
    summary = {"mode": "transition", "n_elements": model.n_elements,
               **{k: float(v) for k, v in info.items() if v is not None}}
    fit = None
    if r.info.get("wave") is not None:
        from ..fe.transition.analysis import wave_speed

        try:
            fit = wave_speed(r.info["wave"])
            summary["wave_speed"] = fit["speed"]
        except Exception as exc:  # noqa: BLE001 - a failed fit is reported, not fatal
            console.print(f"wave speed: {esc(str(exc))}")
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    if not args.no_figures:
        from ..fe.plots import plot_transition, plot_wave

        plot_transition(r.patches, r.history, path=out / "transition.png",
                        title=f"angle of attack {case.angle_of_attack * 1e3:g} mrad")
        if r.info.get("wave") is not None:
            plot_wave(r.info["wave"], fit, path=out / "wave.png")
        if r.contact_fields is not None:
            from ..fe.plots import plot_contact_fields

            for kind in ("stress", "slip"):
                plot_contact_fields(r.contact_fields, kind=kind,
                                    path=out / f"contact_fields_{kind}.png")
    if r.info["stopped_at"] is not None:
        console.print(f"  stopped at {r.patches['travel'].values[-1] * 1e3:.1f} mm (step "
                      f"{r.info['stopped_at']} of {r.info['steps']}); continue with "
                      f"--restart {esc(out / 'restart.npz')}")
    onset = r.info["onset_travel"]
    console.print(f"  onset of two-point contact: "
                  f"{'none' if onset != onset else f'{onset * 1e3:.1f} mm'}; "
                  f"{r.info['cpu_s']:.0f} s CPU, {r.info['ns_per_element_step']:.0f} ns per "
                  f"element and step")
    console.print(f"written to {esc(out)}/")
    return 0


def demo_step(ctx):
    """Demo step: elasto-plastic rolling on a small mesh (R900A-type hardening, yield at
    p0/3: cylinder on the 60E1 crown, 7.5 kN, ξ = 0.7 ‰), elastic run beside it. The
    1.5 mm mesh puts four nodes across the 6 × 4.6 mm Hertz patch in each direction (2 mm:
    three along the rolling direction) at 3 s more CPU time."""
    import numpy as np

    import wheelrail as wr
    from ..fe import J2Plastic, RollingCase, solve
    from ..fe.materials import R900A_HARDENING
    from ..fe.plots import plot_patch_comparison, plot_section

    flat = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    kw = dict(wheel=flat, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0, mu=0.2,
              creepage=(7e-4, 0.0, 0.0), mesh_size=1.5e-3, element="reduced", mass_scaling=400,
              depth=4, half_width=3, half_length=3, travel=0.008)
    el = solve(RollingCase(**kw), progress=False)
    mat = J2Plastic(2.1e11, 0.28, 517.6e6 / 3.0, hardening=R900A_HARDENING)
    pl = solve(RollingCase(material=mat, **kw), progress=False)
    what = (f"cylinder R 0.46 m on 60E1, 7.5 kN, ξ = 0.7 ‰, μ = 0.2; "
            f"{kw['mesh_size'] * 1e3:g} mm mesh ({pl.model.n_elements} elements), "
            f"yield stress {mat.yield_stress / 1e6:.1f} MPa (p0 / 3), Voce hardening")
    plot_patch_comparison(el.patch, pl.patch, 0.2, title=f"FE rolling patch: {what}",
                          path=ctx.file("fe_patch_elastic_plastic.png",
                                        "FE rolling patch, elastic vs elasto-plastic"))
    plot_section(pl.fields, "rail_equivalent_plastic_strain", y=0.0, depth_max=0.01,
                 title=f"equivalent plastic strain, rail section: {what}",
                 path=ctx.file("fe_plastic_strain.png",
                               "FE equivalent plastic strain, rail section"))
    pl.fields.to_netcdf(ctx.file("fe_plastic_fields.nc", "FE plastic fields (NetCDF)"))
    ctx.results["fe_plastic"] = {
        "elastic": {"Fx": el.Fx, "p_max": el.p_max, "Fx_scatter": el.steady["Fx_scatter"]},
        "plastic": {"Fx": pl.Fx, "p_max": pl.p_max, "Fx_scatter": pl.steady["Fx_scatter"],
                    "equivalent_plastic_strain_max":
                        float(pl.fields.rail_equivalent_plastic_strain.max())},
        "n_elements": pl.model.n_elements, "mesh_size": kw["mesh_size"],
        "yield_stress": mat.yield_stress}
    return (f"{kw['mesh_size'] * 1e3:g} mm mesh, {pl.model.n_elements} elements, yield "
            f"{mat.yield_stress / 1e6:.1f} MPa: Fx {el.Fx:.0f} -> {pl.Fx:.0f} N, p_max "
            f"{el.p_max / 1e6:.0f} -> {pl.p_max / 1e6:.0f} MPa, max plastic strain "
            f"{float(pl.fields.rail_equivalent_plastic_strain.max()):.2%}")
