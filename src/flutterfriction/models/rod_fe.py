"""Finite elements for the linearised Beck/Pflüger rod (eq. 107): the independent twin of the
exact characteristic function. scikit-fem, cubic Hermite beam elements on [0, 1], clamped at 0.

Weak form of ``v'''' + eta v_dot'''' + p v'' + gamma v_dot + v_ddot = 0`` with a tip mass
``tan(alpha)`` and, at the loaded end, ``v'' = 0`` and (follower load)
``(1 + eta d/dt) v''' = tan(alpha) v_ddot`` (eq. 111) or (dead load) ``v''' + p v' = ...``
(eq. 121): multiplying by a test function ``w`` and integrating by parts,

    M v_ddot + C v_dot + (K_B + p (K_f - K_G)) v = 0,

with ``M = (v, w) + tan(alpha) v(1) w(1)``, ``K_B = (v'', w'')``, ``K_G = (v', w')``,
``C = eta K_B + gamma (v, w)`` and ``K_f = w(1) v'(1)``: the follower load's boundary term, the
only unsymmetric matrix (absent for a dead load, §2.8).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from flutterfriction.errors import ParameterError
from flutterfriction.models.rod import RodGroups

Matrix = NDArray[np.float64]


@dataclass(frozen=True)
class RodFE:
    """Assembled dimensionless matrices (free dofs only)."""

    M: Matrix
    C: Matrix
    K_B: Matrix
    K_G: Matrix
    K_f: Matrix
    n_elements: int

    def load_matrix(self, follower: bool = True) -> Matrix:
        """d K / d p: ``K_f - K_G`` for a follower load, ``-K_G`` for a dead load."""
        return self.K_f - self.K_G if follower else -self.K_G


@functools.lru_cache(maxsize=64)
def _unit_matrices(n_elements: int) -> tuple[Matrix, Matrix, Matrix, int, int]:
    from skfem import Basis, BilinearForm, ElementLineHermite, MeshLine, asm

    mesh = MeshLine(np.linspace(0.0, 1.0, n_elements + 1))
    basis = Basis(mesh, ElementLineHermite(), intorder=6)

    @BilinearForm
    def mass(u, v, _):
        return u * v

    @BilinearForm
    def bending(u, v, _):
        return u.hess[0, 0] * v.hess[0, 0]

    @BilinearForm
    def geometric(u, v, _):
        return u.grad[0] * v.grad[0]

    clamped = basis.get_dofs(lambda x: np.isclose(x[0], 0.0)).all()
    free = np.setdiff1d(np.arange(basis.N), clamped)
    tip = basis.get_dofs(lambda x: np.isclose(x[0], 1.0)).nodal
    tip_u = int(np.searchsorted(free, tip["u"][0]))
    tip_ux = int(np.searchsorted(free, tip["u_x"][0]))
    sub = np.ix_(free, free)
    return (asm(mass, basis).toarray()[sub], asm(bending, basis).toarray()[sub],
            asm(geometric, basis).toarray()[sub], tip_u, tip_ux)


def assemble(g: RodGroups, n_elements: int) -> RodFE:
    """Matrices of the rod ``g`` on ``n_elements`` equal elements."""
    if isinstance(n_elements, bool) or not isinstance(n_elements, int | np.integer) \
            or n_elements < 1:
        raise ParameterError(f"n_elements must be an integer >= 1, got {n_elements!r}")
    M0, K_B, K_G, iu, iux = _unit_matrices(int(n_elements))
    M = M0.copy()
    M[iu, iu] += g.tan_alpha
    K_f = np.zeros_like(K_B)
    K_f[iu, iux] = 1.0  # row: test function w(1); column: v'(1)
    C = g.eta * K_B + g.gamma * M0
    return RodFE(M=M, C=C, K_B=K_B.copy(), K_G=K_G.copy(), K_f=K_f, n_elements=int(n_elements))
