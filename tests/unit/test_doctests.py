"""The Examples sections of the docstrings run and give what they print (pinned as tests)."""

from __future__ import annotations

import doctest
import importlib
import pathlib

import pytest

import wheelrail

ROOT = pathlib.Path(wheelrail.__file__).parent
MODULES = sorted(
    ".".join(p.relative_to(ROOT.parent).with_suffix("").parts).removesuffix(".__init__")
    for p in ROOT.rglob("*.py") if ">>> " in p.read_text(encoding="utf-8"))


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
                             verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples of {name} failed"


def test_some_modules_have_examples():
    assert len(MODULES) >= 10
