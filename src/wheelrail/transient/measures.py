"""Measures of a transient run used to state Baeza et al.'s findings (pure functions).

* :func:`leading_edge_slip` — slip at the leading edge of the contact with
  adhesion behind it (Baeza et al. §3.2, Fig. 10: impossible in steady rolling
  with pure longitudinal creepage);
* :func:`same_sign_fraction` — fraction of the travel where ξ and F1 have the
  same sign (Baeza et al. §3.3, Fig. 11: impossible in steady rolling);
* :func:`reverse_traction` — elements whose longitudinal traction opposes the
  total force (Baeza et al. §3.3, Fig. 12, "reverse slip").

References
----------
L. Baeza, F.J. Fuenmayor, J. Carballeira, A. Roda, Influence of the wheel–rail contact instationary process on contact parameters, §3.2–3.3.
"""

from __future__ import annotations

import numpy as np

__all__ = ["leading_edge_slip", "same_sign_fraction", "reverse_traction"]


def leading_edge_slip(state):
    """Rows with slip at the leading edge and adhesion behind it; deepest such zone.

    Parameters
    ----------
    state : array_like of int, shape (nx, ny)
        0 out of contact, 1 adhesion, 2 slip (``TransientResult.state[k]``);
        x (axis 0) is the rolling direction, the leading edge at the largest x.

    Returns
    -------
    rows : int
        Grid rows (fixed y) whose leading contact element slips while an
        adhesion element lies behind the slipping run.
    depth : int
        Largest number of consecutive slipping elements from the leading
        edge over those rows [elements].
    """
    rows = depth = 0
    for col in np.asarray(state).T:
        idx = np.nonzero(col)[0]
        if idx.size < 2:
            continue
        d = 0
        for i in idx[::-1]:
            if col[i] != 2:
                break
            d += 1
        if 0 < d < idx.size and np.any(col[idx[: idx.size - d]] == 1):
            rows += 1
            depth = max(depth, d)
    return rows, depth


def same_sign_fraction(xi, force):
    """Fraction of the samples where ξ and the force F1 have the same (nonzero) sign.

    With Kalker's convention a steady rolling contact always has opposite
    signs (positive creepage, negative force on the wheel).

    Parameters
    ----------
    xi, force : array_like, shape (n,)
        Longitudinal creepage [-] and force on the wheel [N] at the same travels.
    """
    xi = np.asarray(xi, float)
    force = np.asarray(force, float)
    return float(np.mean(np.sign(xi) * np.sign(force) > 0))


def reverse_traction(px, pn, Fx):
    """Elements in contact whose traction px opposes the total force Fx, and the extreme.

    Parameters
    ----------
    px, pn : array_like, shape (nx, ny)
        Longitudinal traction and pressure [Pa].
    Fx : float
        Total longitudinal force [N].

    Returns
    -------
    count : int
        Elements with ``pn > 0`` and ``px·Fx < 0``.
    extreme : float
        The most reverse traction ``min(px·sign(Fx))`` [Pa] (≤ 0 when any).
    """
    px = np.asarray(px, float)
    s = np.sign(Fx) if Fx != 0 else 1.0
    inside = np.asarray(pn) > 0
    rev = inside & (px * s < 0)
    return int(rev.sum()), float(min(0.0, (px * s)[inside].min())) if inside.any() else 0.0
