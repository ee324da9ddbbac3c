"""numba's kernel cache follows a change in a kernel of another file.

numba (``cache=True``) keys a cached function on its own source file only: a caller
compiled with a callee of another file kept the old callee after the callee's file
changed (the dynamics used a stale FASTSIM kernel in an editable install until
``__pycache__`` was cleared). ``wheelrail._numba_cache`` salts the cache stamp of every
kernel of a package with a hash of all its numba sources. Here a two-file package in a
temporary directory is compiled, its callee edited, and run again in fresh processes:
without the salt (control) the caller returns the stale value; with it the caller is
recompiled, and an unchanged package is still loaded from the cache.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

CALLEE = "from numba import njit\n\n\n@njit(cache=True)\ndef value():\n    return {}\n"
CALLER = textwrap.dedent("""\
    from numba import njit

    from .callee import value


    @njit(cache=True)
    def twice():
        return 2 * value()
""")
CHILD = textwrap.dedent("""\
    import json, sys
    root, salted = sys.argv[1], sys.argv[2] == "1"
    sys.path.insert(0, root)
    if salted:
        from wheelrail import _numba_cache
        _numba_cache.install(root + "/kpkg")
    from kpkg.caller import twice
    out = twice()
    print(json.dumps({"value": int(out), "hits": sum(twice.stats.cache_hits.values()),
                      "misses": sum(twice.stats.cache_misses.values())}))
""")


def _package(root, value):
    pkg = root / "kpkg"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "callee.py").write_text(CALLEE.format(value))
    (pkg / "caller.py").write_text(CALLER)


def _run(root, salted):
    out = subprocess.run([sys.executable, "-c", CHILD, str(root), "1" if salted else "0"],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_editing_a_callee_recompiles_the_caller(tmp_path):
    control, salted = tmp_path / "control", tmp_path / "salted"
    for root in (control, salted):
        root.mkdir()
        _package(root, 1)
        assert _run(root, root is salted)["value"] == 2
        _package(root, 5)  # the callee's file changes, the caller's does not
    stale = _run(control, False)
    assert stale["value"] == 2, ("numba now recompiles a caller whose callee changed; "
                                 "wheelrail._numba_cache may no longer be needed")
    fresh = _run(salted, True)
    assert fresh["value"] == 10 and fresh["misses"] == 1
    again = _run(salted, True)  # unchanged sources: loaded from the cache
    assert again["value"] == 10 and again["hits"] == 1 and again["misses"] == 0


def test_the_package_kernels_are_salted():
    """Every cached kernel of wheelrail gets the salted stamp (the locator is in place)."""
    from wheelrail import _numba_cache
    from wheelrail.tangential import _fastsim_kernel

    loc = _fastsim_kernel.fastsim_strips_kernel._cache._impl.locator
    assert loc.get_source_stamp()[-1] == _numba_cache.salt(_numba_cache.ROOT)
