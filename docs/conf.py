"""Sphinx configuration of the wheelrail documentation.

Build: ``sphinx-build -W --keep-going -b html docs docs/_build/html`` (after
``pip install -e ".[docs]"``). Pages are Markdown (MyST), the API reference is
generated from the numpydoc docstrings, and the gallery runs every script in
``docs/examples/``; the figures an example writes to ``WHEELRAIL_OUT`` are
collected by :func:`_gallery_scraper.scrape_output_files`.
"""

from __future__ import annotations

import os
import sys
import tempfile
import warnings
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import wheelrail  # noqa: E402

project = "wheelrail"
author = "the wheelrail developers"
copyright = "2026, the wheelrail developers"
release = version = wheelrail.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "_docstrings",
    "_methods_page",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "examples", "gallery/**/*.ipynb",
                    "gallery/**/*.py", "gallery/**/*.zip", "gallery/**/*.json",
                    "gallery/**/*.md5", "gallery/**/*.codeobj.json"]
suppress_warnings = [
    "myst.header",     # pages start at '#', sections may skip levels
    "ref.citation",    # numpydoc References are a bibliography, not always cited inline
]

myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 4                # [text](page.md#a-heading) links resolve

# numpydoc reports malformed docstring sections as Python warnings, which sphinx -W does not
# see: make them errors too, so the build stays free of warnings of any kind
warnings.filterwarnings("error", category=UserWarning, module=r"numpydoc\..*")

# numpydoc renders the docstrings; the class member tables would duplicate autodoc's
numpydoc_show_class_members = False
numpydoc_validation_checks = set()
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "none"
autosummary_generate = True

# the gallery: every script of docs/examples runs; files it writes go to a scratch dir
_OUT = Path(tempfile.mkdtemp(prefix="wheelrail-gallery-"))
os.environ["WHEELRAIL_OUT"] = str(_OUT)
os.environ.setdefault("MPLBACKEND", "Agg")

from _gallery_scraper import OutputFileScraper  # noqa: E402

sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"\.py$",          # run every example, not only plot_*.py
    "image_scrapers": (OutputFileScraper(_OUT),),
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "furo"
html_title = f"wheelrail {release}"
html_static_path = []
nitpicky = False
