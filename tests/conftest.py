"""Shared fixtures, the hypothesis profiles, and access to ``../shared`` (profiles, benchmarks).

Hypothesis profiles
-------------------
``ci``
    Derandomised (the examples of a test are a function of the test alone), no example
    database (a failure found once on some machine is never replayed from a local file),
    no deadline and no ``too_slow`` health check (the CI machine is shared). Loaded when
    the ``CI`` environment variable is set (``.ci/run`` sets ``CI=1``) or
    ``HYPOTHESIS_PROFILE=ci``.
``dev``
    Random examples and the local example database (a failure found is replayed until it
    is fixed), no deadline and no ``too_slow`` health check. Loaded otherwise.

``HYPOTHESIS_PROFILE`` names the profile explicitly and wins over ``CI``.

One xdist worker for the finite-element tests
---------------------------------------------
The FE tests (``tests/fe/``, ``tests/reference/test_fe_*.py``) share numba kernels whose
first compile takes minutes (the explicit time loop alone about 90 s). With ``-n 2`` and
xdist's default scheduling both workers compiled them at the same time. Under that default
(``--dist load``) the scheduler here sends them to one worker as one unit, which compiles
them once while the other worker runs the rest of the suite one test at a time.
(``--dist loadgroup`` with ``xdist_group`` marks would say the same, but with pytest 9 the
group suffix xdist puts on the test ids does not reach the scheduler.)

Shared data
-----------
``../shared/data`` (a sibling of the checkout) holds measured profiles and benchmark
inputs. A test that needs it skips where a user's checkout lacks it, but *fails* in CI
(``CI`` set), where a missing directory is a broken setup, not an optional extra.
"""

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

import wheelrail as wr

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"
SHARED_DATA = SHARED / "data"
PROFILES = SHARED_DATA / "profiles"


def in_ci() -> bool:
    """True when the ``CI`` environment variable is set (to anything but '', 0, false, no)."""
    return os.environ.get("CI", "").strip().lower() not in ("", "0", "false", "no")


# time-based checks (deadline, the too_slow health check) are off in both: the machines are
# shared, and a test must not fail because a neighbour was busy
settings.register_profile("ci", derandomize=True, database=None, deadline=None,
                          print_blob=True, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", derandomize=False, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if in_ci() else "dev"))


def require_shared(path) -> Path:
    """``path`` under ``../shared`` if it exists; else skip the test, or fail it in CI.

    Parameters
    ----------
    path : path-like
        A file or directory the test needs.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    if path.exists():
        return path
    what = (f"{path} is not present (../shared/data: measured profiles and benchmark "
            "inputs beside the checkout)")
    if in_ci():
        pytest.fail(f"{what}; CI must provide it (tests that need it skip only outside CI, "
                    "where the environment variable CI is unset)", pytrace=False)
    pytest.skip(what)


def _runs_fe_kernels(nodeid: str) -> bool:
    return nodeid.startswith(("tests/fe/", "tests/reference/test_fe_"))


@pytest.hookimpl(optionalhook=True)     # xdist's hook: without xdist it is not called
def pytest_xdist_make_scheduler(config, log):
    """xdist's load scheduling with the FE tests as one unit (see the module docstring)."""
    if config.getoption("dist") != "load":
        return None                                   # another mode asked for: xdist's own
    from xdist.scheduler import LoadScopeScheduling

    class FEOnOneWorker(LoadScopeScheduling):
        def _split_scope(self, nodeid):
            return "fe" if _runs_fe_kernels(nodeid) else nodeid

    return FEOnOneWorker(config, log)


@pytest.fixture
def steel():
    return wr.Material(E=2.1e11, nu=0.28)


@pytest.fixture
def shared_profiles():
    """``../shared/data/profiles`` (skips outside CI if absent, fails in CI)."""
    return require_shared(PROFILES)


@pytest.fixture
def shared_data():
    """``../shared/data`` (skips outside CI if absent, fails in CI)."""
    return require_shared(SHARED_DATA)


@pytest.fixture(scope="module")
def hertz_patch16():
    """Grid and BEM pressure of the Hertz contact (10 kN, A = 1, B = 2 1/m, steel), 16 elements."""
    from wheelrail.normal.bem import hertz_grid, solve_normal

    hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    grid, gap = hertz_grid(hc, elements=16, margin=1.1)
    normal = solve_normal(grid, gap, wr.STEEL, Fn=1e4)
    return grid, normal.pressure


@pytest.fixture(scope="session")
def baeza_31():
    """``(hc, dx)`` of Baeza et al. §3.1 on the reduced transient grid (tests/_transient_31.py)."""
    from _transient_31 import contact

    return contact()
