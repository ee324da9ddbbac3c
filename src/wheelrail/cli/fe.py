"""``wheelrail fe CASE.toml``: finite-element rolling contact (or static indentation) of a case file.

The case file holds one ``[fe]`` table; every key is a
:class:`wheelrail.fe.RollingCase` field, plus

* ``wheel`` / ``rail`` — a standard profile name (``"S1002"``, ``"60E1"``), a
  profile file path (relative to the case file), or for the wheel
  ``"cylinder"`` / ``"cone"`` (a straight tread 80 mm wide, taper ``wheel_taper``,
  default 1/10), for the rail ``"arc"`` (a head arc of ``rail_head_radius`` [m],
  default 0.3; seed 000's Hertzian case is ``wheel = "cone"``, ``rail = "arc"``,
  ``inclination = 0.0996686525`` = arctan(1/10));
* ``E``, ``nu`` — the material (default steel 210 GPa, 0.28);
* ``mode`` — ``"roll"`` (default) or ``"indent"``.

Example::

    [fe]
    wheel = "cylinder"
    rail = "60E1"
    radius = 0.46
    load = 7500.0
    creepage = [7e-4, 0.0, 0.0]
    mu = 0.2
    mesh_size = 1.5e-3
    integrator = "explicit"
"""

from __future__ import annotations

from ._output import esc

HELP = "finite-element rolling contact (or static indentation) of an [fe] case file"

#: Measured cost per element and step [s] of the whole explicit loop, used for the time
#: estimate (one core, load ≈ 2.5 on the 2-core machine; benchmarks/bench_fe.py).
COST_PER_ELEMENT_STEP = {"full": 3.5e-7, "reduced": 1.3e-7}


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file with an [fe] table")
    p.add_argument("--out", metavar="DIR", default="fe_out",
                   help="output directory (default fe_out): summary.json, history.csv, "
                        "patch.nc, mesh.vtu, patch.png, history.png, restart.npz")
    p.add_argument("--mode", choices=("roll", "indent"), default=None,
                   help="override the case's mode")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--estimate-only", action="store_true",
                   help="print the mesh size and the time estimate, then stop")
    p.add_argument("--restart", metavar="FILE", default=None,
                   help="continue a rolling run from this restart file (DIR/restart.npz of "
                        "an earlier run of the same case)")
    p.add_argument("--restart-every", metavar="N", type=int, default=None,
                   help="write DIR/restart.npz every N rolling steps (default: a tenth of "
                        "the steps)")


def _profile(value, kind, base, param=0.0):
    import numpy as np

    import wheelrail as wr
    from ..errors import CaseFileError

    if not isinstance(value, str):
        raise CaseFileError(f"[fe] {kind} must be a profile name or file, got {value!r}")
    if kind == "wheel" and value.lower() in ("cylinder", "cone"):
        y = np.linspace(-0.04, 0.04, 17)
        return wr.Profile(y, param * y if value.lower() == "cone" else 0 * y, kind="wheel",
                          name=value)
    if kind == "rail" and value.lower() == "arc":
        return wr.fe.head_arc_rail(param)
    path = base / value
    if path.is_file():
        return wr.profiles.read(path, kind=kind)
    return wr.profiles.load(value)


def case_from_toml(path):
    """A :class:`RollingCase` and the mode from the ``[fe]`` table of a TOML file."""
    import sys
    from pathlib import Path

    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib

    import wheelrail as wr
    from ..errors import CaseFileError
    from ..fe import RollingCase

    from .._toml import read_input

    path = Path(path)
    try:
        doc = tomllib.loads(read_input(path).decode("utf-8", errors="replace"))
    except tomllib.TOMLDecodeError as exc:
        raise CaseFileError(f"{path}: {exc}") from exc
    if "fe" not in doc:
        raise CaseFileError(f"{path}: no [fe] table")
    t = dict(doc["fe"])
    mode = t.pop("mode", "roll")
    if mode not in ("roll", "indent"):
        raise CaseFileError(f"{path}: [fe] mode must be 'roll' or 'indent', got {mode!r}")
    taper = float(t.pop("wheel_taper", 0.1))
    head = float(t.pop("rail_head_radius", 0.3))
    for key in ("wheel", "rail"):
        if key not in t:
            raise CaseFileError(f"{path}: [fe] needs '{key}'")
    t["wheel"] = _profile(t["wheel"], "wheel", path.parent, taper)
    t["rail"] = _profile(t["rail"], "rail", path.parent, head)
    E, nu = t.pop("E", 2.1e11), t.pop("nu", 0.28)
    t["material"] = wr.Material(E=E, nu=nu)
    for key in ("creepage", "rayleigh"):
        if key in t:
            t[key] = tuple(t[key])
    try:
        return RollingCase(**t), mode
    except TypeError as exc:
        raise CaseFileError(f"{path}: [fe] {exc}") from exc


def estimate(case, model) -> tuple[int, float]:
    """Steps and estimated wall time [s] of an explicit run."""
    import numpy as np

    from ..fe.rolling import _speed_profile, stable_time_step

    dt = case.courant * stable_time_step(model)
    _, t_end = _speed_profile(case, model.geometry["travel"])
    depth = model.wheel.axes[2][-1]
    omega1 = np.pi * model.material.wave_speed / (2 * depth) / np.sqrt(case.mass_scaling)
    steps = int(np.ceil(t_end / dt)) + int(np.ceil(12 * 2 * np.pi / omega1 / dt))
    return steps, steps * model.n_elements * COST_PER_ELEMENT_STEP[case.element]


def run(args, console) -> int:
    import json
    from pathlib import Path

    from ..fe import build_model, indent, solve, write_vtu

    case, mode = case_from_toml(args.case)
    mode = args.mode or mode
    out = Path(args.out)
    model = build_model(case, rolling=(mode == "roll"))
    console.print(f"[bold]FE {mode}[/]: {model.n_elements} hex8 elements ({case.element}), "
                  f"{model.n_nodes} nodes, mesh {case.mesh_size * 1e3:g} mm, "
                  f"integrator {case.integrator if mode == 'roll' else 'static'}")
    if mode == "roll" and case.integrator == "explicit":
        steps, seconds = estimate(case, model)
        console.print(f"estimate: {steps} explicit steps, about {seconds / 60:.1f} min on one core")
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
        summary.update(Fx=r.Fx, Fy=r.Fy, p_max=r.p_max, a=r.a, b=r.b,
                       **{k: float(v) for k, v in r.info.items()})
        if args.restart:
            console.print(f"continued from {esc(args.restart)} (step {r.info['restarted_at_step']})")
        r.dataset.to_dataframe().to_csv(out / "history.csv")
        patch, u, mu = r.patch, r.u, case.mu
        model = r.model
    patch.to_netcdf(out / "patch.nc")
    write_vtu(out / "mesh.vtu", model, u)
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    if not args.no_figures:
        from ..fe.plots import plot_history, plot_patch

        plot_patch(patch, mu, path=out / "patch.png")
        if mode == "roll":
            plot_history(r.dataset, path=out / "history.png")
    for k in ("Fx", "Fy", "p_max", "a", "b"):
        if k in summary:
            scale, unit = {"p_max": (1e-6, "MPa"), "a": (1e3, "mm"), "b": (1e3, "mm")}.get(
                k, (1.0, "N"))
            console.print(f"  {k:6s} = {summary[k] * scale:10.4g} {unit}")
    console.print(f"written to {esc(out)}/")
    return 0
