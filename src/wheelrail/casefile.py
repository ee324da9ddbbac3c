"""Deprecated name of :mod:`wheelrail.cases.files` (the case-file readers).

The readers of TOML case files now live beside the cases they produce:
``wheelrail.cases.files`` (``load_case``, ``load_contact_case``,
``load_wheelset_case``, ``load_transient_case``, ``case_from_dict``; also
``wr.load_case``). This module re-exports them with a :class:`DeprecationWarning`
and will be removed in the next release.
"""

from __future__ import annotations

import warnings

from .cases.files import (case_from_dict, load_case, load_contact_case, load_transient_case,
                          load_wheelset_case)

__all__ = ["case_from_dict", "load_case", "load_contact_case", "load_transient_case",
           "load_wheelset_case"]

warnings.warn("wheelrail.casefile is now wheelrail.cases.files (the same functions); the old "
              "name will be removed in the next release", DeprecationWarning, stacklevel=2)
