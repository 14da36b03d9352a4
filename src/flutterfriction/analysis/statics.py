"""Planar statics of a rigid body: the equilibrium of known and unknown forces as a linear
system (used for the lever of Fig. 18, independently of its closed-form moment balance)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import ParameterError, check_finite_array


def _cross(r: NDArray, f: NDArray) -> float:
    return float(r[0] * f[1] - r[1] * f[0])


def planar_equilibrium(known: Sequence[tuple[ArrayLike, ArrayLike]],
                       unknown: Sequence[tuple[ArrayLike, ArrayLike]]) -> NDArray:
    """Magnitudes ``x`` of three unknown forces ``x_k d_k`` applied at ``r_k`` that balance the
    known forces ``F_j`` at ``r_j``: sum of forces (x, y) and of moments about the origin zero.

    Parameters
    ----------
    known
        ``(point, force)`` pairs [m], [N].
    unknown
        Three ``(point, direction)`` pairs; the directions need not be unit vectors (the
        magnitude multiplies the direction as given).

    Returns
    -------
    ndarray, shape (3,)
        The magnitudes, from ``numpy.linalg.solve`` of the 3x3 equilibrium matrix.
    """
    if len(unknown) != 3:
        raise ParameterError(f"a planar rigid body has 3 equilibrium equations: give 3 unknown "
                             f"forces, got {len(unknown)}")
    def planar(name: str, x: ArrayLike) -> NDArray:
        return check_finite_array(name, x, (2,), "two finite numbers (x, y)")

    A = np.empty((3, 3))
    for k, (r, d) in enumerate(unknown):
        r, d = planar(f"unknown[{k}] point", r), planar(f"unknown[{k}] direction", d)
        A[:, k] = [d[0], d[1], _cross(r, d)]
    rhs = np.zeros(3)
    for j, (r, f) in enumerate(known):
        r, f = planar(f"known[{j}] point", r), planar(f"known[{j}] force", f)
        rhs -= [f[0], f[1], _cross(r, f)]
    if abs(np.linalg.det(A)) <= 1e-12 * max(1.0, float(np.abs(A).max())) ** 3:
        raise ParameterError("the unknown forces are statically indeterminate or a mechanism "
                             "(singular equilibrium matrix)")
    return np.linalg.solve(A, rhs)
