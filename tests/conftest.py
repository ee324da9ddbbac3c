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
