"""A small least-recently-used store for kernels and their transforms (private).

Influence kernels and their FFTs depend only on the element size, the
element counts and the combined material constants, not on where the grid
lies. Consecutive solves on same-sized grids (a wheel-rail load iteration,
a sweep, the steps of a time stepper) reuse them. Stored arrays are
read-only.
"""

from __future__ import annotations

from collections import OrderedDict

_SIZE = 24
_store: OrderedDict = OrderedDict()


def memo(key, build):
    """``build()`` once per ``key``; the ``_SIZE`` most recently used results are kept."""
    try:
        value = _store.pop(key)
    except KeyError:
        value = build()
    _store[key] = value
    while len(_store) > _SIZE:
        _store.popitem(last=False)
    return value


def grid_key(grid, pair) -> tuple:
    """What a translation-invariant kernel of ``grid`` depends on."""
    return (grid.nx, grid.ny, grid.dx, grid.dy, pair.G, pair.nu, pair.K)


def clear() -> None:
    """Forget everything (tests)."""
    _store.clear()
