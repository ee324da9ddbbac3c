"""The test setup itself: hypothesis profiles, shared-data policy, and the CI script.

CI must be reproducible: derandomised hypothesis examples, never a local example
database, and a missing ``../shared/data`` is a failure there, not a silent skip.
"""

import os
import re
from pathlib import Path

import pytest
from conftest import in_ci, require_shared  # tests/conftest.py (on sys.path under pytest)
from hypothesis import settings

ROOT = Path(__file__).resolve().parents[2]


def test_ci_profile_is_derandomised_without_database_or_deadline():
    ci = settings.get_profile("ci")
    assert ci.derandomize is True
    assert ci.database is None
    assert ci.deadline is None
    dev = settings.get_profile("dev")
    assert dev.derandomize is False and dev.deadline is None


@pytest.mark.parametrize("value, expected", [("1", True), ("true", True), ("yes", True),
                                             ("", False), ("0", False), ("false", False)])
def test_in_ci_reads_the_environment(monkeypatch, value, expected):
    monkeypatch.setenv("CI", value)
    assert in_ci() is expected
    monkeypatch.delenv("CI")
    assert in_ci() is False


def test_missing_shared_data_skips_outside_ci_and_fails_in_ci(monkeypatch, tmp_path):
    missing = tmp_path / "shared" / "data"
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception, match="not present"):
        require_shared(missing)
    monkeypatch.setenv("CI", "1")
    with pytest.raises(pytest.fail.Exception, match="CI must provide it"):
        require_shared(missing)
    missing.mkdir(parents=True)
    assert require_shared(missing) == missing


def test_ci_script_sets_ci_and_runs_the_readme_test_command():
    """``.ci/run`` exports CI=1 before it runs the README's pytest command, unchanged."""
    script = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```bash\n(.*?)```", readme, re.S)
    (readme_cmd,) = [b.strip() for b in blocks if "pytest" in b]
    pytest_part = readme_cmd[readme_cmd.index(".venv/bin/python -m pytest"):]
    lines = script.splitlines()
    run = [i for i, line in enumerate(lines) if pytest_part in line]
    export = [i for i, line in enumerate(lines) if line.strip() == "export CI=1"]
    assert run and export and export[0] < run[0]
    assert lines[run[0]].endswith(pytest_part)


def test_the_loaded_profile_follows_the_environment():
    """Under ``CI`` (and no ``HYPOTHESIS_PROFILE``) every test runs with the ``ci`` profile."""
    name = os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if in_ci() else "dev")
    profile = settings.get_profile(name)
    assert settings.default.derandomize is profile.derandomize
    assert settings.default.database == profile.database


def test_suite_starts_without_xdist_and_groups_the_fe_tests_with_it():
    """The conftest's FE scheduler is xdist's optional hook: a plain ``pytest`` without xdist
    collects (it failed with 'unknown hook' before), and with xdist the FE tests form one
    unit while the others are scheduled one by one."""
    import subprocess
    import sys

    from conftest import _runs_fe_kernels

    r = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:xdist", "--co", "-q",
                        "tests/unit/test_layers.py"], cwd=ROOT, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    assert _runs_fe_kernels("tests/fe/test_transition.py::test_x")
    assert _runs_fe_kernels("tests/reference/test_fe_hertz.py::test_x")
    assert not _runs_fe_kernels("tests/reference/test_fastsim.py::test_x")
