"""The ``[fe]`` example of docs/cli.md reads as written: its keys are RollingCase fields
(``Fn``, not the deprecated ``load``), with no warning."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_cli_md_fe_example_is_a_valid_case_file(tmp_path):
    from wheelrail.cli.fe import case_from_toml

    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    section = text[text.index("## `wheelrail fe CASE.toml`"):]
    block = re.search(r"```toml\n(.*?)```", section, re.S).group(1)
    assert block.lstrip().startswith("[fe]")
    path = tmp_path / "fe.toml"
    path.write_text(block, encoding="utf-8")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        case, mode = case_from_toml(path)
    assert mode == "roll" and case.Fn == 7500.0 and case.mesh_size == 2e-3


def test_the_old_load_key_still_reads_with_a_deprecation_warning(tmp_path):
    import pytest

    from wheelrail.cli.fe import case_from_toml

    path = tmp_path / "old.toml"
    path.write_text('[fe]\nwheel = "cylinder"\nrail = "60E1"\nradius = 0.46\nload = 7500.0\n',
                    encoding="utf-8")
    with pytest.warns(DeprecationWarning, match="'load' is deprecated, use 'Fn'"):
        case, _ = case_from_toml(path)
    assert case.Fn == 7500.0
