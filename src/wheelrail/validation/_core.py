"""Result objects and the registry of validation checks."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Callable

from ..citations import BIBLIOGRAPHY, bibtex, citation_keys

__all__ = ["CheckResult", "ValidationReport", "Check", "CHECKS", "register", "rel_row", "abs_row",
           "band_row", "max_row", "skipped_row"]

#: Row statuses.
PASSED, FAILED, KNOWN, SKIPPED = "passed", "failed", "known-failure", "skipped"

#: Kinds of reference, in report order; the first three are validation.
REFERENCE_KINDS = ("closed form", "published", "other code", "consistency", "convergence")
VALIDATION_KINDS = REFERENCE_KINDS[:3]
#: wheelrail methods that evaluate a closed form (Hertz's and Carter's theories): a row whose
#: reference comes from one of them can be validation; from any other method it is consistency.
CLOSED_FORM_METHODS = ("hertz", "carter")


#: A tolerance more than this many times the measured error must say why.
LOOSE_MARGIN = 5.0


@dataclass(frozen=True)
class CheckResult:
    """One row of the validation report: a method against an independent reference.

    Attributes
    ----------
    method : str
        The wheelrail method checked (a name of :func:`wheelrail.normal_methods`,
        :func:`wheelrail.tangential_methods`, or ``"transient"``, ``"fe"``,
        ``"geometry"``, ``"halfspace"``).
    reference : str
        The independent reference (closed form, published table, other code).
    quantity : str
        What is compared, with the case (units in the text).
    value, reference_value : float
        The method's value and the reference's (SI units or dimensionless as
        ``quantity`` says); for a fitted order the observed and expected order.
    error : float
        The error measure compared with ``tolerance`` (``measure`` says which).
    tolerance : float or tuple of float
        Largest accepted ``error``, or ``(low, high)`` bounds of ``value`` for
        fitted orders and bias bands.
    passed : bool
        Whether the row is within its tolerance.
    time : float
        Wall time [s] of the check that produced the row (rows of one check
        share it).
    figure : str or None
        A base64 PNG shown in the HTML report.
    source : str
        Citation key(s) of the reference (:data:`wheelrail.citations.BIBLIOGRAPHY`),
        comma separated.
    check : str
        Registry name of the check.
    measure : {"rel", "abs", "band", "max-rel", "max-abs"}
        How ``error`` is defined: relative error ``|value/reference − 1|``,
        absolute error in the unit stated in ``quantity``, ``value`` inside the
        ``tolerance`` band, or the maximum of either over a set of points.
    tolerance_source : str
        Where the tolerance comes from (the test holding it, paper, equation).
    status : {"passed", "failed", "known-failure", "skipped"}
        ``known-failure``: a defect recorded in ``note`` (reported, not hidden).
    note : str
        Further explanation (known defect, skip reason, grid sizes).
    reference_method : str
        The wheelrail method that computed the reference value, if any (e.g.
        ``"exact"`` for creep curves, ``"hertz"`` for Hertz's closed form); empty
        for closed forms written in the check, published tables and other codes.
        For ``kind == "reference"`` it is never ``method`` (no self-comparison).
    kind : {"reference", "convergence"}
        ``convergence``: a fitted order or a limit of the method's own grid
        sequence (a convergence study, not a comparison with a reference).
    reference_kind : {"closed form", "published", "other code", "consistency", "convergence"}
        What the reference is (:data:`REFERENCE_KINDS`): a closed form, a published
        table or figure value, a published run of another code, or — not counted
        as validation — wheelrail against itself (another of its methods, a
        solver sharing its core, the same formula or table on both sides) or a
        convergence study of its own grids.
    """

    method: str
    reference: str
    quantity: str
    value: float
    reference_value: float
    error: float
    tolerance: float | tuple
    passed: bool
    time: float
    figure: str | None = None
    source: str = ""
    check: str = ""
    measure: str = "rel"
    tolerance_source: str = ""
    status: str = ""
    note: str = ""
    reference_method: str = ""
    kind: str = "reference"
    reference_kind: str = ""

    @property
    def margin(self) -> float:
        """``tolerance / error`` of a scalar tolerance (inf for a zero error, nan for bands and
        skipped rows). Above :data:`LOOSE_MARGIN` the ``tolerance_source`` must say why
        (``"why: ..."``)."""
        if isinstance(self.tolerance, tuple) or not math.isfinite(self.error) \
                or not math.isfinite(self.tolerance):
            return math.nan
        return math.inf if self.error == 0 else self.tolerance / abs(self.error)

    @property
    def is_validation(self) -> bool:
        """Whether the row compares with an independent reference (counted as validation)."""
        return self.reference_kind in VALIDATION_KINDS

    def to_dict(self) -> dict:
        """All fields as JSON-ready values (the figure replaced by whether there is one)."""
        out = {}
        for k in self.__dataclass_fields__:
            v = getattr(self, k)
            if k == "figure":
                out["has_figure"] = v is not None
                continue
            if isinstance(v, tuple):
                v = [x if math.isfinite(x) else None for x in v]
            elif isinstance(v, float) and not math.isfinite(v):
                v = None
            out[k] = v
        return out


@dataclass(frozen=True)
class ValidationReport:
    """Result of :func:`wheelrail.validation.run` (frozen).

    Attributes
    ----------
    rows : tuple of CheckResult
    quick : bool
        Whether the quick (small grids) variant was run.
    total_time : float
        Wall time of the run [s].
    environment : dict
        Version, platform, Python, CPU count and the load average before and
        after the run.
    errors : dict
        Checks that raised: name -> message (their rows are ``failed``).
    """

    rows: tuple
    quick: bool
    total_time: float
    environment: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        """True when no row failed (known failures and skipped rows are listed, not counted)."""
        return all(r.status != FAILED for r in self.rows) and not self.errors

    def counts(self) -> dict:
        """Number of rows per status."""
        out = {s: 0 for s in (PASSED, FAILED, KNOWN, SKIPPED)}
        for r in self.rows:
            out[r.status] += 1
        return out

    def kind_counts(self) -> dict:
        """Number of rows per reference kind (:data:`REFERENCE_KINDS`)."""
        out = {k: 0 for k in REFERENCE_KINDS}
        for r in self.rows:
            out[r.reference_kind] = out.get(r.reference_kind, 0) + 1
        return out

    def methods(self) -> list[str]:
        """Methods that appear in at least one row, in order of appearance."""
        seen: list[str] = []
        for r in self.rows:
            if r.method not in seen:
                seen.append(r.method)
        return seen

    def citation_keys(self) -> list[str]:
        """Citation keys of the rows' references and of the validated methods."""

        keys: list[str] = []
        for r in self.rows:
            for k in (s.strip() for s in r.source.split(",")):
                if k in BIBLIOGRAPHY and k not in keys:
                    keys.append(k)
        for k in citation_keys(*self.methods()):
            if k not in keys:
                keys.append(k)
        return keys

    def bibtex(self) -> str:
        """BibTeX of :meth:`citation_keys`."""

        return "\n\n".join(bibtex(k) for k in self.citation_keys()) + "\n"


@dataclass(frozen=True)
class Check:
    """A registered check: ``func(quick) -> list[CheckResult]``."""

    name: str
    func: Callable
    methods: tuple
    title: str
    full_only: bool = False
    heavy: str = ""
    reference_kind: str = ""


#: Registry: name -> :class:`Check`, in report order.
CHECKS: dict[str, Check] = {}


def register(name, methods, title, full_only=False, heavy="", reference_kind=""):
    """Decorator adding a check function to :data:`CHECKS`.

    ``heavy`` (a reason) marks checks the test suite skips to stay fast;
    ``reference_kind`` (:data:`REFERENCE_KINDS`) is the kind of the check's rows
    unless a row says otherwise (convergence rows are always "convergence").
    """
    if reference_kind not in REFERENCE_KINDS:
        raise ValueError(f"check {name!r}: reference_kind must be one of {REFERENCE_KINDS}, "
                         f"got {reference_kind!r}")

    def deco(func):
        CHECKS[name] = Check(name, func, tuple(methods), title, full_only, heavy, reference_kind)
        return func
    return deco


def _status(ok, known):
    if ok:
        return PASSED
    return KNOWN if known else FAILED


def _row(method, reference, quantity, value, ref, error, tol, ok, *, source, tolerance_source,
         measure, known="", note="", figure=None, reference_method="", kind="reference",
         reference_kind=""):
    value = float(value)
    ref = float(ref) if ref is not None else math.nan
    error = float(error)
    ok = bool(ok) and math.isfinite(value)
    note = (known + (" " + note if note else "")) if (known and not ok) else note
    return CheckResult(method=method, reference=reference, quantity=quantity, value=value,
                       reference_value=ref, error=error, tolerance=tol, passed=ok,
                       time=math.nan, figure=figure, source=source, measure=measure,
                       tolerance_source=tolerance_source, status=_status(ok, known), note=note,
                       reference_method=reference_method, kind=kind,
                       reference_kind=reference_kind)


def rel_row(method, reference, quantity, value, ref, tol, **kw):
    """Row with the relative error |value/ref − 1| ≤ tol."""
    err = abs(float(value) / float(ref) - 1.0)
    return _row(method, reference, quantity, value, ref, err, float(tol), err <= tol,
                measure="rel", **kw)


def abs_row(method, reference, quantity, value, ref, tol, scale=1.0, **kw):
    """Row with the absolute error |value − ref| / scale ≤ tol."""
    err = abs(float(value) - float(ref)) / float(scale)
    return _row(method, reference, quantity, value, ref, err, float(tol), err <= tol,
                measure="abs", **kw)


def max_row(method, reference, quantity, values, refs, tol, scale=None, **kw):
    """Row with the largest relative (or, with ``scale``, scaled absolute) error of several."""
    import numpy as np

    v, r = np.asarray(values, float).ravel(), np.asarray(refs, float).ravel()
    if scale is None:
        e = np.abs(v / r - 1.0)
        measure = "max-rel"
    else:
        e = np.abs(v - r) / np.broadcast_to(np.asarray(scale, float).ravel(), v.shape)
        measure = "max-abs"
    i = int(np.argmax(e))
    return _row(method, reference, quantity, v[i], r[i], e[i], float(tol), e[i] <= tol,
                measure=measure, **kw)


def band_row(method, reference, quantity, value, expected, low, high, **kw):
    """Row passing when ``low < value < high`` (fitted orders, documented bias bands)."""
    value = float(value)
    err = 0.0 if low < value < high else min(abs(value - low), abs(value - high))
    return _row(method, reference, quantity, value, expected, err, (float(low), float(high)),
                low < value < high, measure="band", **kw)


def skipped_row(method, reference, quantity, reason, source=""):
    """A row that could not be run here (missing data), with the reason."""
    return CheckResult(method=method, reference=reference, quantity=quantity, value=math.nan,
                       reference_value=math.nan, error=math.nan, tolerance=math.nan,
                       passed=False, time=0.0, source=source, measure="rel", status=SKIPPED,
                       note=reason)


def run_check(check: Check, quick: bool) -> tuple[list[CheckResult], str | None]:
    """Run one check; rows carry its name and wall time. An exception gives a failed row."""
    t0 = time.perf_counter()
    try:
        rows = list(check.func(quick))
        err = None
    except Exception as exc:  # noqa: BLE001 - reported as a failed row, the run goes on
        err = f"{type(exc).__name__}: {exc}"
        rows = [CheckResult(method=check.methods[0], reference=check.title, quantity="(check raised)",
                            value=math.nan, reference_value=math.nan, error=math.nan,
                            tolerance=math.nan, passed=False, time=math.nan, status=FAILED,
                            note=err)]
    dt = time.perf_counter() - t0

    def kind_of(r):
        if r.kind == "convergence":
            return "convergence"
        if r.reference_method and r.reference_method not in CLOSED_FORM_METHODS:
            return "consistency"       # the reference value is another wheelrail computation
        return r.reference_kind or check.reference_kind

    return [replace(r, check=check.name, time=dt if r.status != SKIPPED else r.time,
                    reference_kind=kind_of(r)) for r in rows], err
