"""Restart files of a rolling run (NumPy ``.npz``; a leaf module).

A restart file holds the complete state of an integrator at the end of a time
step of the rolling step (the second loading step of Toumi et al. 2016): displacements and velocities in
the body frames, the axle dof and its velocity, the rigid motions (rolling angle
ψ [rad], rail travel s [m], time t [s]), the contact history (tangential forces
and the previous contact positions that define the next slip increment), the
accumulated energies, the history rows written so far and the next step number.
:func:`wheelrail.fe.solve` with ``restart=path`` continues from it and gives the
same numbers as an uninterrupted run that wrote the file (bit for bit: the same
arrays enter the same operations).

A fingerprint of the case (integrator, mesh size, element and node counts, time
step, load, creepage, friction, speed, travel) is stored and checked on reading.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["write_restart", "read_restart", "fingerprint"]

_VERSION = 2


def fingerprint(model, dt: float) -> dict:
    """Quantities a restart must share with the run that wrote it."""
    case = model.case
    return {"integrator": case.integrator, "mesh_size": case.mesh_size,
            "n_elements": model.n_elements, "n_nodes": model.n_nodes, "time_step": float(dt),
            "load": case.Fn, "xi": case.creepage[0], "eta": case.creepage[1], "mu": case.mu,
            "speed": case.speed, "travel": float(model.geometry["travel"]),
            "element": case.element, "mass_scaling": case.mass_scaling,
            "rayleigh_alpha": case.rayleigh[0], "rayleigh_beta": case.rayleigh[1],
            "contact_damping": case.contact_damping, "passes": case.passes,
            "axle_damping": case.axle_damping,
            "material": repr(model.material)}


def write_restart(path, model, dt: float, state: dict) -> None:
    """Write ``state`` (arrays, floats, ints, and one level of nested dicts) atomically.

    Parameters
    ----------
    path : str or Path
        Target ``.npz`` file; written to ``path + ".tmp"`` first and renamed, so that an
        interrupted write never leaves a truncated restart file.
    model : Model
    dt : float
        Time step of the run [s].
    state : dict
        The integrator's state; nested dicts (contact results, energies) are flattened
        with ``"name.key"`` names.
    """
    flat = {"_version": np.array(_VERSION)}
    for k, v in fingerprint(model, dt).items():
        flat[f"_fp.{k}"] = np.array(v)
    for k, v in state.items():
        if isinstance(v, dict):
            for kk, vv in v.items():
                flat[f"{k}.{kk}"] = np.asarray(vv)
        else:
            flat[k] = np.asarray(v)
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp.npz")
    np.savez(tmp, **flat)
    os.replace(tmp, path)


def read_restart(path, model, dt: float) -> dict:
    """Read a restart file written by :func:`write_restart` for the same case.

    Raises
    ------
    InputError
        The file does not exist, is not a restart file, or was written for a different
        case (naming the first differing quantity and both values).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"restart file {str(path)!r} does not exist")
    try:
        data = np.load(path, allow_pickle=False)
        flat = {k: data[k] for k in data.files}
    except Exception as exc:  # noqa: BLE001 - any unreadable file is the same user error
        raise InputError(f"restart file {str(path)!r} is not readable: {exc}") from exc
    if "_version" not in flat:
        raise InputError(f"{str(path)!r} is not a wheelrail FE restart file")
    for k, v in fingerprint(model, dt).items():
        stored = flat.get(f"_fp.{k}")
        stored = None if stored is None else stored.item()
        if stored != v:
            raise InputError(f"restart file {str(path)!r} was written for {k} = {stored!r}, "
                             f"this case has {k} = {v!r}")
    state: dict = {}
    for k, v in flat.items():
        if k.startswith("_"):
            continue
        v = v.item() if v.ndim == 0 else v
        if "." in k:
            a, b = k.split(".", 1)
            state.setdefault(a, {})[b] = v
        else:
            state[k] = v
    return state
