"""The one entry for every FE case (:func:`solve`): a wheel rolling over a rail with the
explicit or implicit integrator chosen by the case (:mod:`wheelrail.fe.explicit`,
:mod:`wheelrail.fe.implicit`; the shared parts are in :mod:`wheelrail.fe.rolling`), its
static indentation (:mod:`wheelrail.fe.static`), or the one- to two-point contact
transition (:mod:`wheelrail.fe.transition`)."""

from __future__ import annotations

import numbers

from ..errors import InputError
from .case import RollingCase
from .explicit import solve_explicit
from .implicit import solve_implicit_hht, solve_implicit_qs
from .rolling import _warn_saturation
from .static import indent
from .transition import TransitionCase, run_transition

__all__ = ["solve"]


def solve(case, *, mode: str = "roll", progress: bool = True, output_every: int | None = None,
          restart=None, restart_file=None, restart_every: int | None = None,
          stop_travel=None):
    """Solve an FE case: roll the wheel over the rail (the two loading steps of Toumi et al.
    2016), indent it, or roll a half-wheelset into two-point contact.

    Parameters
    ----------
    case : RollingCase or TransitionCase
        A :class:`~wheelrail.fe.RollingCase` with an elastic (:class:`wheelrail.Material`,
        :class:`wheelrail.fe.LinearElastic`) or elasto-plastic
        (:class:`wheelrail.fe.J2Plastic`) material (``passes`` rolls the same section
        several times); or a :class:`~wheelrail.fe.TransitionCase`, run by
        :func:`~wheelrail.fe.transition.run_transition` (``progress``, ``restart``,
        ``restart_file``, ``restart_every`` and ``stop_travel`` are passed on).
    mode : {"roll", "indent"}
        A rolling case: roll it (default) or only its static normal contact
        (:func:`~wheelrail.fe.indent`, an :class:`~wheelrail.fe.IndentResult`).
    progress : bool
        Show a rich progress bar (a transition case: the estimate and progress lines).
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
        Steps between restart writes, >= 1 (default: a tenth of the rolling steps).

    stop_travel : float, optional
        A transition case: stop after this travel [m] (restart file written there).

    Returns
    -------
    RollingResult, IndentResult or TransitionResult

    Warns
    -----
    UserWarning
        The creepage is past the saturation estimate (:func:`saturation_creepage`): the
        patch slides entirely and the force is μ F_n whatever the creepage; or an implicit
        ``time_step`` above h/(2V) (spurious slip, Toumi et al. 2016, §3).
    """
    if restart_every is not None and (isinstance(restart_every, bool) or not isinstance(
            restart_every, numbers.Integral) or restart_every < 1):
        raise InputError(f"restart_every must be an integer >= 1 (steps between restart "
                         f"writes; None: a tenth of the rolling steps), got {restart_every!r}")
    if isinstance(case, TransitionCase):
        if mode != "roll":
            raise InputError(f"mode {mode!r}: a transition case only rolls")
        return run_transition(case, progress=progress, restart=restart,
                              restart_file=restart_file, restart_every=restart_every or 0,
                              stop_travel=stop_travel)
    if not isinstance(case, RollingCase):
        raise InputError(f"case must be a wheelrail.fe.RollingCase or TransitionCase, got "
                         f"{type(case).__name__}")
    if stop_travel is not None:
        raise InputError("stop_travel is for transition cases")
    if mode == "indent":
        return indent(case)
    if mode != "roll":
        raise InputError(f"mode must be 'roll' or 'indent', got {mode!r}")
    _warn_saturation(case)
    io = {"restart": restart, "file": restart_file, "every": restart_every}
    if case.integrator == "explicit":
        return solve_explicit(case, progress, output_every, io)

    if case.integrator == "implicit-qs":
        return solve_implicit_qs(case, progress, io)
    return solve_implicit_hht(case, progress, io)
