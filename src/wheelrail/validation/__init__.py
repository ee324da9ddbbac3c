"""Validation report: every method of wheelrail against independent references.

:func:`run` executes the registered checks (:data:`CHECKS`) — closed forms
(Hertz, Carter, Cattaneo–Mindlin, Boussinesq/Cerruti, cone-on-circle
tangency), Kalker's published creep coefficients, published tables and figures, the
published output of the CONTACT program (Manchester benchmark A-2.2, the
FASTSIM example of its user guide) and convergence studies with fitted
orders — and returns a frozen :class:`ValidationReport` of
:class:`CheckResult` rows. :func:`write_report` writes it as a self-contained
HTML page (figures embedded as base64 PNG), JSON with every number, a
Markdown summary (``report.md``) and BibTeX of the references.

Every row compares a method with a reference that does not come from the
same method (no self-comparison) and states the tolerance it is held to and
where that tolerance comes from (the test that holds it, the paper, or the
accuracy target it is held to). Rows of known, reported defects have the status
``known-failure``; they are listed, not hidden.

The command line is ``wheelrail validate [--quick] [--out DIR]``.

Examples
--------
>>> from wheelrail import validation
>>> report = validation.run(quick=True, progress=False)       # doctest: +SKIP
>>> validation.write_report(report, "validation-report")      # doctest: +SKIP
"""

from __future__ import annotations

import importlib
import os
import platform
import sys
import time
import warnings

from .. import __version__
from ..errors import InputError
from ._core import CHECKS, Check, CheckResult, ValidationReport, run_check, skipped_row
from ._report import markdown, write_html, write_json, write_markdown, write_report

__all__ = ["run", "CheckResult", "ValidationReport", "CHECKS", "Check", "write_report",
           "write_html", "write_json", "write_markdown", "markdown", "load_checks"]

_CHECK_MODULES = ("checks_normal", "checks_tangential", "checks_other")


def load_checks() -> dict:
    """Import the check modules (registering their checks) and return :data:`CHECKS`."""
    for m in _CHECK_MODULES:
        importlib.import_module(f"{__name__}.{m}")
    return CHECKS


def _load():
    try:
        return tuple(round(v, 2) for v in os.getloadavg())
    except OSError:           # pragma: no cover - not on every platform
        return None


def _environment():
    import numpy as np


    return {"wheelrail": __version__, "python": sys.version.split()[0], "numpy": np.__version__,
            "platform": platform.platform(), "cpus": os.cpu_count(),
            "date_utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime())}


def run(quick: bool = True, progress: bool = True, only=None, skip_heavy: bool = False,
        console=None) -> ValidationReport:
    """Run the validation checks and collect their rows.

    Parameters
    ----------
    quick : bool
        Small grids and fewer cases (about half a minute on one core); the
        full run adds finer grids, more cases and the checks marked full-only.
    progress : bool
        Show a rich progress bar (on ``console`` or stderr).
    only : sequence of str, optional
        Names of :data:`CHECKS` to run (default: all).
    skip_heavy : bool
        Skip the checks marked heavy (finite elements, the Manchester
        benchmark needing data outside the package); they appear as
        ``skipped`` rows with the reason. Used by the test suite.
    console : rich.console.Console, optional

    Returns
    -------
    ValidationReport
        Rows in registry order, the total wall time [s] and the environment
        (versions, CPU count, load average before and after the run).

    Raises
    ------
    InputError
        An unknown check name in ``only``.
    """

    checks = load_checks()
    if only is not None:
        unknown = [n for n in only if n not in checks]
        if unknown:
            raise InputError(f"unknown validation check(s) {unknown}; choose from "
                             + ", ".join(checks))
        selected = [checks[n] for n in only]
    else:
        selected = [c for c in checks.values() if not (quick and c.full_only)]
    env = _environment()
    env["load_before"] = _load()
    t0 = time.perf_counter()
    rows, errors = [], {}
    bar = None
    if progress:
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

        bar = Progress(TextColumn("[bold]validate[/bold] {task.description:<32}"), BarColumn(),
                       TextColumn("{task.completed}/{task.total}"), TimeElapsedColumn(),
                       console=console, transient=False)
        bar.start()
        task = bar.add_task("", total=len(selected))
    try:
        for check in selected:
            if bar is not None:
                bar.update(task, description=check.name)
            if skip_heavy and check.heavy:
                rows.append(_skipped(check, f"skipped by request (heavy: {check.heavy})"))
            else:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")     # plausibility/quadrature notes of cases
                    got, err = run_check(check, quick)
                rows.extend(got)
                if err is not None:
                    errors[check.name] = err
            if bar is not None:
                bar.advance(task)
    finally:
        if bar is not None:
            bar.stop()
    total = time.perf_counter() - t0
    env["load_after"] = _load()
    return ValidationReport(rows=tuple(rows), quick=bool(quick), total_time=total,
                            environment=env, errors=errors)


def _skipped(check: Check, reason: str) -> CheckResult:
    from dataclasses import replace

    return replace(skipped_row(check.methods[0], check.title, "(not run)", reason),
                   check=check.name, reference_kind=check.reference_kind)
