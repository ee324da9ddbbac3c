"""FE cases estimated before the mesh is allocated.

The campaign: an FE case with ``mesh_size = 1e-6`` failed with ``MemoryError: Unable
to allocate 2.80 TiB``, also with ``--estimate-only``; ``radius = 460`` (mm given as m)
gave an error that blamed ``mesh_size``. Here the element count comes from the mesh
parameters (no allocation), the guard refuses with the estimate, and the radius is
refused by name.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from _helpers import assert_clean_failure, run_cli

import wheelrail as wr
from wheelrail.fe.mesh import axis_size, graded_axis
from wheelrail.fe.model import build_model, mesh_size_estimate


@pytest.mark.parametrize("args", [
    (0.0, 1.0, 0.3, 0.6, 0.01, 1.3, None),
    (-0.05, 0.2, 0.0, 0.1, 1e-3, 1.2, None),
    (0.0, 0.05, 0.0, 0.012, 1e-3, 1.3, 4e-3),
    (0.0, 0.3, 0.1, 0.1, 2e-3, 1.5, None),
    (0.0, 0.02, 0.0, 0.02, 7e-4, 1.3, None),
])
def test_axis_size_counts_the_graded_axis(args):
    """axis_size is the length of graded_axis for the same arguments, without building it."""
    assert axis_size(*args) == len(graded_axis(*args))


@pytest.mark.parametrize("changes", [dict(load="printed", mesh_size=2e-3),
                                     dict(mesh_size=3e-3, plastic=True)])
def test_mesh_estimate_equals_the_built_mesh(changes):
    """The pre-allocation count is the built model's count (the same mesh parameters)."""
    case = wr.fe.seed000_case(**changes)
    est = mesh_size_estimate(case)
    model = build_model(case)
    assert (est["n_elements"], est["n_nodes"]) == (model.n_elements, model.n_nodes)


def test_micrometre_mesh_refused_before_allocation(tmp_path, capsys):
    case = tmp_path / "fe.toml"
    case.write_text('[fe]\ntoumi2016 = "table3"\nmesh_size = 1e-6\n')
    t0 = time.process_time()
    code, _, err = run_cli(["fe", case, "--out", tmp_path / "out"], capsys)
    assert time.process_time() - t0 < 30.0          # no 2.8 TiB allocation attempted
    assert_clean_failure(code, err, "FE mesh", "elements", "1e-06", "memory limit")
    assert not (tmp_path / "out").exists()
    est = mesh_size_estimate(wr.fe.seed000_case(mesh_size=1e-6))
    assert est["n_elements"] > 1e12 and np.isfinite(est["memory"])


def test_radius_in_millimetres_is_named(tmp_path, capsys):
    case = tmp_path / "fe.toml"
    case.write_text('[fe]\ntoumi2016 = "table3"\nradius = 460\n')
    code, _, err = run_cli(["fe", case, "--out", tmp_path / "out"], capsys)
    assert_clean_failure(code, err, "radius", "460", "mm")
    assert "mesh_size" not in err[-1]
