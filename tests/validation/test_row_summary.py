"""A validation row that summarises several points reports the worst one.

A row such as "area, a/b in (0.2, 1, 5)" compares a method with its reference at several
points and is held to its tolerance by the *largest* error: one point outside the tolerance
fails the row, whatever the others. The expected numbers below are written out by hand.
"""

import math

import pytest

from wheelrail import validation
from wheelrail.validation._core import max_row   # the row builder (private; one import)

KW = dict(source="Johnson1985", tolerance_source="test")


def test_relative_errors_the_worst_point_is_reported_and_fails_the_row():
    # relative errors 0.01, 0.30, 0.002: the row is the second point, and it fails
    row = max_row("hertz", "closed form", "p0, 3 contacts", [1.01, 1.30, 0.998], [1.0, 1.0, 1.0],
                  0.05, **KW)
    assert row.value == pytest.approx(1.30) and row.reference_value == pytest.approx(1.0)
    assert row.error == pytest.approx(0.30)
    assert row.measure == "max-rel"
    assert not row.passed and row.status == "failed"


def test_scaled_absolute_errors_the_worst_point_is_reported():
    # |v − r| / scale = 0.5/10, 4/10, 1/10: the second point, 0.4 > 0.2
    row = max_row("exact", "CONTACT", "Fx / (mu Fn)", [10.5, -4.0, 3.0], [10.0, 0.0, 2.0], 0.2,
                  scale=10.0, **KW)
    assert (row.value, row.reference_value) == (-4.0, 0.0)
    assert row.error == pytest.approx(0.4)
    assert row.measure == "max-abs" and not row.passed


def test_all_points_inside_pass_with_the_largest_error():
    row = max_row("hertz", "closed form", "a", [1.001, 0.997, 1.002], [1.0, 1.0, 1.0], 0.01, **KW)
    assert row.passed and row.status == "passed"
    assert row.error == pytest.approx(0.003) and row.value == pytest.approx(0.997)


def test_a_failed_summary_row_fails_the_report():
    bad = max_row("hertz", "closed form", "p0", [1.0, 2.0], [1.0, 1.0], 0.1, **KW)
    report = validation.ValidationReport(rows=(bad,), quick=True, total_time=0.0)
    assert not report.passed and report.counts()["failed"] == 1
    assert math.isfinite(bad.error)
