"""Sphinx extension: ``methods.md``, generated from the method registries at build time.

Every normal method and creep-force law with its options (unit, default, allowed
values, meaning) and references, from the option declarations
(:func:`wheelrail.options.describe`): the page cannot drift from the code.
"""

from __future__ import annotations

from pathlib import Path

HEADER = """# Methods and their options

Generated from the method registries (`wr.normal_methods()`,
`wr.tangential_methods()`) and the option declarations of each class when the
documentation is built. A method is chosen by name (its defaults) or as a
configured object; options given to `wr.solve` go to the one method that
declares them:

```python
wr.solve(problem, creepage, mu, normal=wr.normal.Bem(element_size=2e-4),
         tangential=wr.tangential.Exact(elements=40))
wr.solve(problem, creepage, mu, normal="bem", tangential="exact", element_size=2e-4,
         elements=40)                                   # the same
```

Case files take the same options in `[method.<name>]` tables, and refuse the
same values.
"""


def page() -> str:
    import wheelrail as wr
    from wheelrail.options import describe

    parts = [HEADER, "## Normal methods\n"]
    parts += [describe(c) for c in wr.normal_methods().values()]
    parts += ["## Creep-force laws (tangential methods)\n"]
    parts += [describe(c) for c in wr.tangential_methods().values()]
    return "\n".join(parts)


def _write(app):
    out = Path(app.srcdir) / "methods.md"
    text = page()
    if not out.exists() or out.read_text(encoding="utf-8") != text:
        out.write_text(text, encoding="utf-8")


def setup(app):
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True}
