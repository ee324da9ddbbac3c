"""numba's on-disk cache of the package's kernels, invalidated when any kernel source changes
(private).

numba (``@njit(cache=True)``) keys a cached function on the content of *its own* source
file. A kernel that calls a kernel of another file has the callee compiled into it; when
only the callee's file changes, numba still loads the caller's stale machine code (seen in
an editable install: the dynamics used an old FASTSIM kernel until ``__pycache__`` was
cleared). Here every cached function of a registered package (this one, :func:`install`)
gets a *salted* source stamp: numba's own stamp of its file plus a hash of every source
file of the package that imports numba. Any change to any kernel source then misses the cache
of every kernel of the package and recompiles it once; the cache files stay where numba
puts them (``__pycache__``, ``NUMBA_CACHE_DIR`` or the user-wide cache directory).

The salting locator is put first in numba's list of cache locators when numba is imported
(an import hook, so that ``import wheelrail`` does not import numba) or at once if numba
is already imported; it answers only for files under a registered package, so other
packages' cached functions are untouched. The salt is computed once per process, when the
first kernel of the package is decorated (about 15 ms for the 20-odd files that import numba).
"""

from __future__ import annotations

import hashlib
import importlib.abc
import os
import re
import sys

__all__ = ["install", "salt", "ROOT"]

#: The package directory (every cached kernel below it is salted).
ROOT = os.path.dirname(os.path.abspath(__file__))

_roots: dict = {}  # package directory -> salt (None until computed)
_hook = {"finder": None, "registered": False}


_IMPORTS_NUMBA = re.compile(rb"^[ \t]*(from[ \t]+numba[ \t.]|import[ \t]+numba)", re.MULTILINE)


def salt(root: str) -> str:
    """Hash of the sources of every ``.py`` file under ``root`` that imports numba."""
    h = hashlib.sha256()
    for d, dirs, files in os.walk(root):
        dirs[:] = sorted(x for x in dirs if x != "__pycache__" and not x.startswith("."))
        for name in sorted(files):
            if not name.endswith(".py"):
                continue
            path = os.path.join(d, name)
            try:
                with open(path, "rb") as fh:
                    data = fh.read()
            except OSError:  # pragma: no cover - a file removed while walking
                continue
            if _IMPORTS_NUMBA.search(data):
                h.update(os.path.relpath(path, root).encode() + b"\0" + data + b"\0")
    return h.hexdigest()[:16]


def _salt_of(py_file: str):
    path = os.path.abspath(py_file)
    for root in _roots:
        if path.startswith(root + os.sep):
            if _roots[root] is None:
                _roots[root] = salt(root)
            return _roots[root]
    return None


def _register() -> None:
    """Put the salting locator first in numba's cache locators (once)."""
    if _hook["registered"]:
        return
    _hook["registered"] = True
    try:
        from numba.core import caching

        impl = getattr(caching, "CacheImpl", None) or caching._CacheImpl
        base = getattr(caching, "CacheLocator", None) or caching._CacheLocator
        locators = impl._locator_classes
    except (ImportError, AttributeError) as exc:  # pragma: no cover - numba internals moved
        import warnings

        warnings.warn(f"wheelrail cannot salt numba's kernel cache ({exc}); after changing a "
                      f"kernel source, delete the __pycache__ directories", RuntimeWarning,
                      stacklevel=2)
        return
    inner = list(locators)

    class SaltedLocator(base):
        """numba's locator of a package file, with the package's kernel-source hash
        in the source stamp (see the module docstring)."""

        def __init__(self, locator, value):
            self._inner, self._salt = locator, value

        def ensure_cache_path(self):
            self._inner.ensure_cache_path()

        def get_cache_path(self):
            return self._inner.get_cache_path()

        def get_source_stamp(self):
            return (self._inner.get_source_stamp(), "wheelrail-kernels", self._salt)

        def get_disambiguator(self):
            return self._inner.get_disambiguator()

        @classmethod
        def from_function(cls, py_func, py_file):
            value = _salt_of(py_file)
            if value is None:
                return None
            for c in inner:
                loc = c.from_function(py_func, py_file)
                if loc is not None:
                    return cls(loc, value)
            return None

    locators.insert(0, SaltedLocator)


class _NumbaImportHook(importlib.abc.MetaPathFinder):
    """Registers the locator right after ``numba`` is imported (then removes itself)."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname != "numba":
            return None
        for finder in sys.meta_path:
            if finder is self or not hasattr(finder, "find_spec"):
                continue
            spec = finder.find_spec(fullname, path, target)
            if spec is not None:
                break
        else:
            return None
        loader = spec.loader
        original = getattr(loader, "exec_module", None)
        if original is None:  # pragma: no cover - a legacy loader
            return spec

        def exec_module(module):  # numba's own loader, then the locator
            try:
                original(module)
            finally:
                try:
                    del loader.exec_module
                except AttributeError:  # pragma: no cover
                    pass
            _remove_hook()
            _register()

        loader.exec_module = exec_module  # this loader instance loads numba only
        return spec


def _remove_hook() -> None:
    finder = _hook["finder"]
    if finder is not None and finder in sys.meta_path:
        sys.meta_path.remove(finder)
    _hook["finder"] = None


def install(root: str = ROOT) -> None:
    """Salt the numba cache of every cached kernel under the package directory ``root``.

    Called for this package when it is imported; other packages (and the tests, on a
    temporary package) may call it for theirs. Must run before the package's kernels
    are decorated (they are imported lazily, after ``wheelrail``).
    """
    _roots.setdefault(os.path.abspath(root), None)
    if "numba" in sys.modules and hasattr(sys.modules["numba"], "njit"):
        _register()
    elif _hook["finder"] is None and not _hook["registered"]:
        _hook["finder"] = _NumbaImportHook()
        sys.meta_path.insert(0, _hook["finder"])


def is_cached(dispatcher) -> bool:
    """Whether a ``cache=True`` numba function has a cache entry valid for the current sources
    (its first call then loads instead of compiling). False if it has none."""
    cache = getattr(dispatcher, "_cache", None)
    index = getattr(getattr(cache, "_cache_file", None), "_load_index", None)
    if index is None:
        return False
    try:
        return bool(index())
    except Exception:  # an unreadable or foreign index: numba recompiles
        return False
