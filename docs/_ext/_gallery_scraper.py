"""Sphinx-gallery image scraper for scripts that write their figures to a directory.

The examples in ``docs/examples`` save their figures (and data) to the directory
named by ``WHEELRAIL_OUT`` instead of leaving matplotlib figures open, so the
default matplotlib scraper would find nothing. This scraper shows every PNG that
appeared or changed in that directory while a code block ran.
"""

from __future__ import annotations

import shutil
from pathlib import Path


class OutputFileScraper:
    """Collect the PNG files an example writes to ``out`` (one scraper per build)."""

    def __init__(self, out):
        self.out = Path(out)
        self.seen = {}

    def __repr__(self):                       # sphinx-gallery hashes the config by repr
        return "OutputFileScraper()"

    def _new_files(self):
        new = []
        for path in sorted(self.out.rglob("*.png")):
            stamp = path.stat().st_mtime_ns
            if self.seen.get(path) != stamp:
                self.seen[path] = stamp
                new.append(path)
        return new

    def __call__(self, block, block_vars, gallery_conf):
        from sphinx_gallery.scrapers import figure_rst

        images = []
        for path, target in zip(self._new_files(), block_vars["image_path_iterator"]):
            shutil.copyfile(path, target)
            images.append(target)
        return figure_rst(images, gallery_conf["src_dir"])
