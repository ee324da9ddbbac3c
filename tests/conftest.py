"""Shared fixtures. ``SHARED`` points at ../shared (profiles, seeds) when it is present."""

from pathlib import Path

import pytest

import wheelrail as wr

ROOT = Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared"
PROFILES = SHARED / "data" / "profiles"


@pytest.fixture
def steel():
    return wr.Material(E=2.1e11, nu=0.28)


@pytest.fixture
def shared_profiles():
    if not PROFILES.is_dir():
        pytest.skip("../shared/data/profiles is not present")
    return PROFILES


@pytest.fixture(scope="module")
def hertz_patch16():
    """Grid and BEM pressure of the Hertz contact (10 kN, A = 1, B = 2 1/m, steel), 16 elements."""
    from wheelrail.normal.bem import hertz_grid, solve_normal

    hc = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)
    grid, gap = hertz_grid(hc, elements=16, margin=1.1)
    normal = solve_normal(grid, gap, wr.STEEL, Fn=1e4)
    return grid, normal.pressure
