"""Sphinx extension: read wheelrail's plain-text mathematics in docstrings as text.

The docstrings are written for ``help()`` as much as for the web: ``|F_t| <= mu Fn``
means an absolute value, and ``*`` a product. reStructuredText reads ``|...|`` as
a substitution reference and a lone ``*`` as the start of emphasis. This hook
escapes both outside inline literals and roles, before numpydoc and autodoc
parse the docstring, so the text renders as written.
"""

from __future__ import annotations

import re

_LITERAL = re.compile(r"(``.+?``|:[a-z:]+:`[^`]*`|`[^`]*`_?)")
_ABS = re.compile(r"(?<![\\|\w])\|(?=[^\s|])([^|\n]*?[^\s|\\])\|(?![\w|])")
# a product (a*b, 2 * x) or an unpacking ((nz, *S)); never a bullet or **strong**/*emphasis*
_STAR = re.compile(r"(?<=[\w)\]}.])\*(?=[\w(\[{.])|(?<=\S\s)\*(?=\s)"
                   r"|(?<=[\s(,\[])\*(?=\w)(?![^*\n]*\*)")


def _escape(text: str) -> str:
    parts = _LITERAL.split(text)
    for i in range(0, len(parts), 2):                 # even parts: outside literals/roles
        part = _ABS.sub(r"\\|\1\\|", parts[i])
        parts[i] = _STAR.sub(r"\\*", part)
    return "".join(parts)


def escape_plain_math(app, what, name, obj, options, lines):
    in_literal_block = False
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped.endswith("::"):
            lines[i] = _escape(line)
            in_literal_block = True
            continue
        if in_literal_block:
            if stripped and not line.startswith((" ", "\t")):
                in_literal_block = False
            else:
                continue
        if stripped.startswith("| ") or stripped.startswith(">>>"):   # line block, doctest
            continue
        lines[i] = _escape(line)


def setup(app):
    app.connect("autodoc-process-docstring", escape_plain_math, priority=100)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
