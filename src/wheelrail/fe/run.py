"""Rolling of a wheel over a rail (the entry :func:`solve`): the explicit or implicit
integrator chosen by the case (:mod:`wheelrail.fe.explicit`, :mod:`wheelrail.fe.implicit`;
the shared parts are in :mod:`wheelrail.fe.rolling`)."""

from __future__ import annotations

from .explicit import solve_explicit
from .implicit import solve_implicit_hht, solve_implicit_qs
from .rolling import RollingResult, _warn_saturation

__all__ = ["solve"]


def solve(case, *, progress: bool = True, output_every: int | None = None,
          restart=None, restart_file=None, restart_every: int | None = None) -> RollingResult:
    """Roll the wheel over the rail: the two loading steps of Toumi et al. (2016).

    Parameters
    ----------
    case : RollingCase
        Elastic (:class:`wheelrail.Material`, :class:`wheelrail.fe.LinearElastic`) or
        elasto-plastic (:class:`wheelrail.fe.J2Plastic`) material; ``passes`` rolls the
        same section several times.
    progress : bool
        Show a rich progress bar.
    output_every : int, optional
        Explicit: record the histories every this many steps (default: about 400 rows per
        pass); the steady statistics use every step.
    restart : str or Path, optional
        Continue from this restart file (written by a run of the same case).
    restart_file : str or Path, optional
        Write the state of the rolling step (plastic state included) to this ``.npz``
        file every ``restart_every`` steps (and at the end), see
        :mod:`wheelrail.fe.restart`; ``{step}`` in the name is replaced by the step number
        (one file per write), otherwise the file is overwritten with the latest state.
    restart_every : int, optional
        Steps between restart writes (default: a tenth of the rolling steps).

    Returns
    -------
    RollingResult

    Warns
    -----
    UserWarning
        The creepage is past the saturation estimate (:func:`saturation_creepage`): the
        patch slides entirely and the force is μ F_n whatever the creepage; or an implicit
        ``time_step`` above h/(2V) (spurious slip, Toumi et al. 2016, §3).
    """
    _warn_saturation(case)
    io = {"restart": restart, "file": restart_file, "every": restart_every}
    if case.integrator == "explicit":
        return solve_explicit(case, progress, output_every, io)

    if case.integrator == "implicit-qs":
        return solve_implicit_qs(case, progress, io)
    return solve_implicit_hht(case, progress, io)
