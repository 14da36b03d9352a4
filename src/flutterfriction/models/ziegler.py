"""The Ziegler double pendulum of chapter §2.1 (Fig. 2).

Two rigid massless rods AB (length ``l1``) and BC (length ``l2``), elastic hinges at A and B
(rotational stiffnesses ``k1``, ``k2``, optional viscosities ``c1``, ``c2``), point masses ``m1`` at
D (distance ``d`` from A on AB), ``m3`` at E (distance ``h`` from B on BC) and ``m2`` at the free
end C. At C act a tangential follower force ``P`` (parallel to BC) and a dead force ``H``
(parallel to e1), both positive when compressive. The Lagrangean parameters are the rod
rotations ``alpha1``, ``alpha2``. All quantities are SI.

Errata relevant here (see ``workflow/reference.yaml``): eq. (1) prints the e2-component of
D - A as ``d sin(alpha2)``; it is ``d sin(alpha1)`` (eqs. 3, 4 and 10 follow from the latter).
Eq. (11) prints the (1,1) entry of the geometric matrix as ``-l1 (P - H)``; the linearisation of
eq. (10) gives ``-l1 (P + H)``, as eq. (13) has it.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import ParameterError, check_nonnegative, check_positive, check_real

Matrix = NDArray[np.float64]


@dataclass(frozen=True)
class PendulumGroups:
    """Dimensionless groups of eq. (17).

    ``rho1 = m1/m2``, ``rho2 = m3/m2``, ``y1 = d/l1``, ``y2 = h/l2``, ``lam = l1/l2``
    (lambda in the chapter) and ``k = k1/k2``. The loads enter as ``eta = H l1/k2`` (eq. 17) and
    ``gamma = P l1/k2`` (eq. 32), the frequency as ``omega^2 = m2 l2^2 Omega^2/k2`` (eq. 17).
    """

    rho1: float
    rho2: float
    y1: float
    y2: float
    lam: float
    k: float


@dataclass(frozen=True)
class ZieglerPendulum:
    """Ziegler double pendulum (chapter §2.1, Fig. 2), SI units.

    Parameters
    ----------
    l1, l2 : float
        Lengths of rods AB and BC [m], > 0.
    d : float
        Position of ``m1`` on AB, measured from A [m], 0 < d <= l1.
    h : float
        Position of ``m3`` on BC, measured from B [m], 0 <= h <= l2.
    m1, m2 : float
        Masses at D and at the loaded end C [kg], > 0.
    m3 : float
        Mass at E [kg], >= 0.
    k1, k2 : float
        Rotational stiffnesses of the hinges at A and B [N m/rad], > 0.
    c1, c2 : float
        Rotational viscosities of the hinges at A and B [N m s/rad], >= 0 (eq. 26).
    """

    l1: float
    l2: float
    d: float
    h: float
    m1: float
    m2: float
    m3: float
    k1: float
    k2: float
    c1: float = 0.0
    c2: float = 0.0

    def __post_init__(self) -> None:
        units = {"l1": "m", "l2": "m", "d": "m", "h": "m", "m1": "kg", "m2": "kg", "m3": "kg",
                 "k1": "N m/rad", "k2": "N m/rad", "c1": "N m s/rad", "c2": "N m s/rad"}
        nonneg = {"h", "m3", "c1", "c2"}
        for f in fields(self):
            check = check_nonnegative if f.name in nonneg else check_positive
            object.__setattr__(self, f.name, check(f.name, getattr(self, f.name), units[f.name]))
        if self.d > self.l1:
            raise ParameterError(
                f"d must lie on rod AB, 0 < d <= l1 = {self.l1!r} m, got d = {self.d!r} m")
        if self.h > self.l2:
            raise ParameterError(
                f"h must lie on rod BC, 0 <= h <= l2 = {self.l2!r} m, got h = {self.h!r} m")

    # ------------------------------------------------------------------ construction helpers
    @classmethod
    def from_mapping(cls, params: dict[str, Any]) -> ZieglerPendulum:
        """Build from a mapping (e.g. a config section); unknown keys are rejected by name."""
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(params) - names)
        if unknown:
            raise ParameterError(
                f"unknown pendulum parameter(s) {unknown}; allowed: {sorted(names)}")
        missing = sorted(f.name for f in fields(cls)
                         if f.name not in params and f.name not in {"c1", "c2"})
        if missing:
            raise ParameterError(f"missing pendulum parameter(s) {missing}")
        return cls(**params)

    def with_(self, **changes: float) -> ZieglerPendulum:
        """A copy with some parameters changed (validated again)."""
        return replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        return {f.name: getattr(self, f.name) for f in fields(self)}

    # ------------------------------------------------------------------ dimensionless groups
    def groups(self) -> PendulumGroups:
        """The dimensionless groups of eq. (17)."""
        return PendulumGroups(rho1=self.m1 / self.m2, rho2=self.m3 / self.m2,
                              y1=self.d / self.l1, y2=self.h / self.l2,
                              lam=self.l1 / self.l2, k=self.k1 / self.k2)

    @property
    def load_unit(self) -> float:
        """``k2/l1`` [N]: P = gamma k2/l1 (eq. 32) and H = eta k2/l1 (eq. 17)."""
        return self.k2 / self.l1

    @property
    def frequency_unit(self) -> float:
        """``sqrt(k2/m2)/l2`` [rad/s]: Omega = omega sqrt(k2/m2)/l2 (eq. 17)."""
        return float(np.sqrt(self.k2 / self.m2) / self.l2)

    # ------------------------------------------------------------------ linear matrices
    def mass_matrix(self) -> Matrix:
        """Mass matrix M of eq. (11) [kg m^2]; symmetric positive definite."""
        w = (self.m2 * self.l2 + self.m3 * self.h) * self.l1
        return np.array([[self.m1 * self.d**2 + (self.m2 + self.m3) * self.l1**2, w],
                         [w, self.m2 * self.l2**2 + self.m3 * self.h**2]])

    def stiffness_matrix(self) -> Matrix:
        """Elastic stiffness matrix K of eq. (11) [N m]."""
        return np.array([[self.k1 + self.k2, -self.k2], [-self.k2, self.k2]])

    def viscosity_matrix(self) -> Matrix:
        """Hinge viscosity matrix C of eq. (26) [N m s]."""
        return np.array([[self.c1 + self.c2, -self.c2], [-self.c2, self.c2]])

    def follower_load_matrix(self) -> Matrix:
        """dG/dP [m]: the unsymmetric part of the geometric matrix, per unit follower load."""
        return np.array([[-self.l1, self.l1], [0.0, 0.0]])

    def dead_load_matrix(self) -> Matrix:
        """dG/dH [m]: the symmetric geometric matrix per unit dead load."""
        return np.array([[-self.l1, 0.0], [0.0, -self.l2]])

    def geometric_matrix(self, P: float = 0.0, H: float = 0.0) -> Matrix:
        """Geometric matrix G of eq. (11) as corrected (eq. 13): [[-l1(P+H), P l1], [0, -H l2]]."""
        P = check_real("P", P)
        H = check_real("H", H)
        return P * self.follower_load_matrix() + H * self.dead_load_matrix()

    # ------------------------------------------------------------------ nonlinear kinematics
    def positions(self, alpha1: ArrayLike, alpha2: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Positions of A, D, B, E, C (eq. 1, with D corrected to use alpha1), shape (..., 2)."""
        a1 = np.asarray(alpha1, dtype=float)
        a2 = np.asarray(alpha2, dtype=float)
        u1 = np.stack([np.cos(a1), np.sin(a1)], axis=-1)
        u2 = np.stack([np.cos(a2), np.sin(a2)], axis=-1)
        B = self.l1 * u1
        return {"A": np.zeros_like(B), "D": self.d * u1, "B": B,
                "E": B + self.h * u2, "C": B + self.l2 * u2}

    def equations_of_motion(self, state: ArrayLike, P: float = 0.0, H: float = 0.0) -> Matrix:
        """Right-hand side of the nonlinear equations of motion, eq. (10), with hinge viscosity.

        Parameters
        ----------
        state : array_like, shape (4,) or (4, n)
            ``[alpha1, alpha2, alpha1_dot, alpha2_dot]`` [rad, rad/s].
        P, H : float
            Follower and dead loads [N], positive when compressive.

        Returns
        -------
        ndarray
            ``d(state)/dt``, same shape as ``state``.
        """
        a1, a2, w1, w2 = np.asarray(state, dtype=float)
        s, c = np.sin(a1 - a2), np.cos(a1 - a2)
        w = (self.m2 * self.l2 + self.m3 * self.h) * self.l1
        I1 = self.m1 * self.d**2 + (self.m2 + self.m3) * self.l1**2
        I2 = self.m2 * self.l2**2 + self.m3 * self.h**2
        # Generalised forces moved to the right-hand side of eq. (10): M(alpha) alpha'' = f.
        f1 = (-w * w2**2 * s - self.k1 * a1 - self.k2 * (a1 - a2)
              - self.c1 * w1 - self.c2 * (w1 - w2) + P * self.l1 * s + H * self.l1 * np.sin(a1))
        f2 = (w * w1**2 * s + self.k2 * (a1 - a2) - self.c2 * (w2 - w1)
              + H * self.l2 * np.sin(a2))
        det = I1 * I2 - (w * c) ** 2
        acc1 = (I2 * f1 - w * c * f2) / det
        acc2 = (I1 * f2 - w * c * f1) / det
        return np.array([w1, w2, acc1, acc2])
