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

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields, replace
from fractions import Fraction
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import (
    ParameterError,
    check_finite_reals,
    check_nonnegative,
    check_positive,
    check_real,
    named_parameters,
    shown_beside,
)

Matrix = NDArray[np.float64]

#: Numerical range of the model (see :meth:`ZieglerPendulum.check_numerical_range`): the
#: largest allowed decimal exponent of the ratios m1/m2, m3/m2, l1/l2 and k1/k2 (each within
#: [10^-RATIO_DECADES, 10^RATIO_DECADES]). Where the digits come from (measured against
#: 60-digit mpmath): one ratio at a time from list (47), the undamped P_flu, P_div and the dead
#: H_cr, H_sup err by at most 3e-14 up to 1e6 (under 1 s each); the flutter loads lose digits
#: like eps times a power of the ratio beyond (4e-13 at k1/k2 = 1e8, 6e-9 at 1e-16, while
#: m1/m2 = 1e10 and l1/l2 = 1e10 are refused by the solver). At the 192 corners of the box
#: (ratios 1e+-6, d/l1 and h/l2 in {1e-6, 1}, m3 = 0 too) the worst accepted load errs by
#: 3e-13 and 51 corners are refused (mass matrix singular, or a flutter interval too narrow to
#: bracket: ConvergenceError), none answered wrong, each in under 4 s.
RATIO_DECADES = 6
#: Smallest relative determinant of the mass matrix, det M/(M11 M22) (1 for two decoupled
#: inertias, 0 when all the mass sits at C so that both rods carry one point mass). Measured:
#: at 1e-12 (m3 = 0, m1 d^2 = 1e-12 m2 l1^2) the flutter loads err by 1.8e-11 against mpmath;
#: below, Cholesky's factor of M loses the small inertia (at 1e-18 M is not positive definite
#: in floating point).
MIN_RELATIVE_MASS_DET = 1e-12
#: Smallest non-zero relative viscosity c_i/(l2 sqrt(k2 m2)): below 1e-150 the products of two
#: of them in the characteristic polynomial (eq. 30, order eps^2) leave the normal doubles
#: (1e-300 > 2.2e-308). Nothing is lost: the damped loads depend on eps through eps^2 (eq. 54,
#: and the damped divergence load), so from eps ~ 1e-8 on they equal their eps -> 0 limits
#: (the Ziegler paradox values) to double precision.
MIN_RELATIVE_VISCOSITY = 1e-150
#: Largest relative viscosity: the damped loads grow like eps^2 (eq. 54); at 1e3 (5e5 load
#: units) the Routh and eigenvalue flutter loads still agree to 3e-10 and the damped
#: divergence load by eigenvalues and by Routh/Sturm to 6e-10, in under 10 s (measured).
MAX_RELATIVE_VISCOSITY = 1e3
#: Load unit k2/l1 [N] kept inside [1e-250, 1e250] so that loads up to 1e12 units (more than
#: the range above allows) stay normal finite doubles when converted to newtons.
LOAD_UNIT_RANGE = (1e-250, 1e250)


class DimensionlessMatrices(NamedTuple):
    """The pendulum's matrices divided by their natural units (eqs. 17, 29, 32):
    ``M/(m2 l2^2)``, ``C/(l2 sqrt(k2 m2))``, ``K/k2`` and the geometric matrix per unit
    dimensionless load, ``dG/dP l1^-1`` (follower, gamma = P l1/k2) and ``dG/dH l1^-1``
    (dead, eta = H l1/k2). Built from the groups only, so they cannot overflow."""

    M: Matrix
    C: Matrix
    K: Matrix
    G_follower: Matrix
    G_dead: Matrix


@named_parameters
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

    def __post_init__(self) -> None:
        # Refused by name as ZieglerPendulum refuses its parameters (an outside review: NaN,
        # inf, negatives, strings and y1 = 5 were accepted and the closed forms computed on
        # them, e.g. flutter loads for a mass off the rod). Values are kept as given: exact
        # fractions stay exact (ZieglerPendulum.groups(exact=True)).
        for name in ("rho1", "rho2", "y1", "y2", "lam", "k"):
            value = getattr(self, name)
            x = check_real(name, value)
            if name in ("rho1", "lam", "k", "y1"):
                check_positive(name, x)
            else:
                check_nonnegative(name, x)
            if name in ("y1", "y2") and x > 1.0:
                raise ParameterError(f"{name} = {'d/l1' if name == 'y1' else 'h/l2'} must be "
                                     f"<= 1 (the mass on its rod), got {x!r}")
            if not isinstance(value, Fraction):
                object.__setattr__(self, name, x)  # a float, not a numpy scalar or an int

    @property
    def equal_rods(self) -> bool:
        """l1 = l2 = L and k1 = k2 = K: the pendulum of eq. (25)'s H_cr = (3 - sqrt 5)/2 K/L."""
        return self.lam == 1.0 and self.k == 1.0

    @property
    def symmetric(self) -> bool:
        """The pendulum of eqs. (46) and (50)-(54): equal rods, m1 = m2, d = l1, m3 = 0 (with
        c1 = c2, eq. 54's 4/3 + eps^2/2); a user's other pendulum has its own loads."""
        return self.equal_rods and self.rho1 == 1.0 and self.y1 == 1.0 and self.rho2 == 0.0


@named_parameters
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
        if not isinstance(params, Mapping):  # (an outside review: None was a TypeError)
            raise ParameterError(f"pendulum parameters must be a mapping of {sorted(names)}, "
                                 f"got {type(params).__name__}")
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
        """A copy with some parameters changed (validated again; unknown names refused)."""
        names = {f.name for f in fields(self)}
        unknown = sorted(set(changes) - names)
        if unknown:  # (an outside review: a bare TypeError)
            raise ParameterError(
                f"unknown pendulum parameter(s) {unknown}; allowed: {sorted(names)}")
        return replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        return {f.name: getattr(self, f.name) for f in fields(self)}

    # ------------------------------------------------------------------ numerical range
    def check_numerical_range(self) -> None:
        """Refuse a pendulum whose loads double precision cannot resolve (ParameterError).

        The allowed ranges (one line naming the parameter): ``m1/m2``, ``m3/m2`` (when
        m3 > 0), ``l1/l2`` and ``k1/k2`` within ``[1e-6, 1e6]`` (:data:`RATIO_DECADES`); the
        mass matrix's relative determinant ``>= 1e-12`` (:data:`MIN_RELATIVE_MASS_DET`);
        relative viscosities ``c_i/(l2 sqrt(k2 m2))``
        zero or within ``[1e-150, 1e3]``; the load unit ``k2/l1`` within ``[1e-250, 1e250] N``.
        Ratios are compared through logarithms, so no quotient can overflow here.
        """
        lo, hi = -RATIO_DECADES, RATIO_DECADES
        rng = f"[1e-{RATIO_DECADES}, 1e{RATIO_DECADES}]"
        checks = [("m1, m2", "m1/m2", self.m1, self.m2), ("l1, l2", "l1/l2", self.l1, self.l2),
                  ("k1, k2", "k1/k2", self.k1, self.k2)]
        if self.m3 > 0:
            checks.append(("m3, m2", "m3/m2", self.m3, self.m2))
        for name, ratio, num, den in checks:
            e = math.log10(num) - math.log10(den)
            if not lo <= e <= hi:
                raise ParameterError(
                    f"{name}: the ratio {ratio} = 10^{e:.3g} is outside the model's numerical "
                    f"range {rng} (double precision cannot resolve the loads beyond it)")
        g = self.groups()  # safe now: every ratio is within 1e+-6 (y1, y2 are in [0, 1])
        # det M by Cauchy-Binet over the point masses (no cancellation), over M11 M22.
        y2c = (self.l2 - self.h) / self.l2
        det = g.lam**2 * (g.y1**2 * g.rho1 + y2c**2 * g.rho2 + (g.y1 * g.y2) ** 2 * g.rho1 * g.rho2)
        rel = det / (g.lam**2 * (g.rho1 * g.y1**2 + 1 + g.rho2) * (1 + g.rho2 * g.y2**2))
        if not rel >= MIN_RELATIVE_MASS_DET:
            raise ParameterError(
                f"m1, d: the mass matrix is singular to double precision, det M/(M11 M22) = "
                f"{shown_beside(rel, (MIN_RELATIVE_MASS_DET,), '.3g')} must be >= "
                f"{MIN_RELATIVE_MASS_DET:g} (inertia m1 d^2 at D or "
                f"m3 (l2 - h)^2 at E too small against m2 l1^2)")
        log_unit = math.log10(self.k2) - math.log10(self.l1)
        ulo, uhi = (math.log10(x) for x in LOAD_UNIT_RANGE)
        if not ulo <= log_unit <= uhi:
            raise ParameterError(
                f"k2: the load unit k2/l1 = 10^{log_unit:.4g} N is outside [1e{ulo:.0f}, "
                f"1e{uhi:.0f}] N (loads would overflow or leave the normal doubles)")
        scale = (math.log10(self.l2) + 0.5 * (math.log10(self.k2) + math.log10(self.m2)))
        for name in ("c1", "c2"):
            c = getattr(self, name)
            if c == 0:
                continue
            e = math.log10(c) - scale
            if not math.log10(MIN_RELATIVE_VISCOSITY) <= e <= math.log10(MAX_RELATIVE_VISCOSITY):
                raise ParameterError(
                    f"{name}: the relative viscosity {name}/(l2 sqrt(k2 m2)) = 10^{e:.4g} must be "
                    f"0 or within [{MIN_RELATIVE_VISCOSITY:g}, {MAX_RELATIVE_VISCOSITY:g}]")

    def relative_viscosity(self, c: float) -> float:
        """``c/(l2 sqrt(k2 m2))`` (eq. 29's epsilon for c = c2), formed from mantissas and
        exponents apart: ``l2 sqrt(k2) sqrt(m2)`` alone underflows to 0 at l2 = 1e-124,
        k2 = m2 = 1e-200 (a ZeroDivisionError; an outside audit) and overflows at the other
        end, while the group itself lies in the model's range."""
        c = check_nonnegative("c", c, "N m s/rad")  # (an outside review: NaN, -1 returned)
        if c == 0:
            return 0.0

        def root(x: float) -> tuple[float, int]:  # sqrt(x) as (mantissa, exponent)
            m, e = math.frexp(x)
            if e % 2:
                m, e = 2 * m, e - 1
            return math.sqrt(m), e // 2

        (mc, ec), (ml, el) = math.frexp(c), math.frexp(self.l2)
        (mk, ek), (mm, em) = root(self.k2), root(self.m2)
        return math.ldexp(mc / (ml * mk * mm), ec - el - ek - em)

    def dimensionless_matrices(self, exact: bool = False) -> DimensionlessMatrices:
        """Matrices in the units of eqs. (17), (29), (32) (see :class:`DimensionlessMatrices`).

        Call :meth:`check_numerical_range` first: then every entry is a normal double.
        ``exact``: the entries as exact fractions (object arrays) of the parameters (each a
        double, i.e. a rational; only the viscosity groups, which hold square roots, are
        rounded, once): the characteristic polynomial is then expanded without round-off. Why:
        in doubles ``k + 1`` loses the digits of ``k = k1/k2`` that the damped flutter
        condition depends on (an outside audit: with k1/k2 = 1e-5, m1/m2 = 100 and c1 = 0 the
        Routh verdicts on the rounded coefficients put the damped flutter load 0.28 % low, and
        34 % low at k1/k2 = 1e-4, m1/m2 = 1e4)."""
        g = self.groups(exact)
        one = Fraction(1) if exact else 1.0
        zero = 0 * one
        M = np.array([[g.lam**2 * (g.rho1 * g.y1**2 + 1 + g.rho2), g.lam * (1 + g.rho2 * g.y2)],
                      [g.lam * (1 + g.rho2 * g.y2), 1 + g.rho2 * g.y2**2]])
        e1, e2 = self.relative_viscosity(self.c1), self.relative_viscosity(self.c2)
        if exact:  # (a float times a fraction is a float)
            e1, e2 = Fraction(e1), Fraction(e2)
        C = np.array([[e1 + e2, -e2], [-e2, e2]])
        K = np.array([[g.k + 1, -one], [-one, one]])
        return DimensionlessMatrices(M=M, C=C, K=K,
                                     G_follower=np.array([[-one, one], [zero, zero]]),
                                     G_dead=np.array([[-one, zero], [zero, -1 / g.lam]]))

    # ------------------------------------------------------------------ dimensionless groups
    def groups(self, exact: bool = False) -> PendulumGroups:
        """The dimensionless groups of eq. (17); ``exact``: as exact fractions of the
        parameters (see :meth:`dimensionless_matrices`)."""
        v = Fraction if exact else float
        return PendulumGroups(rho1=v(self.m1) / v(self.m2), rho2=v(self.m3) / v(self.m2),
                              y1=v(self.d) / v(self.l1), y2=v(self.h) / v(self.l2),
                              lam=v(self.l1) / v(self.l2), k=v(self.k1) / v(self.k2))

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
        with np.errstate(over="ignore", invalid="ignore"):
            G = P * self.follower_load_matrix() + H * self.dead_load_matrix()
        if not np.all(np.isfinite(G)):  # (an outside review: an inf matrix was returned)
            raise ParameterError(f"the loads P = {P!r}, H = {H!r} N times the lengths leave "
                                 f"the double range")
        return G

    # ------------------------------------------------------------------ nonlinear kinematics
    def positions(self, alpha1: ArrayLike, alpha2: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Positions of A, D, B, E, C (eq. 1, with D corrected to use alpha1), shape (..., 2)."""
        a1, a2 = check_finite_reals("alpha1", alpha1), check_finite_reals("alpha2", alpha2)
        u1 = np.stack([np.cos(a1), np.sin(a1)], axis=-1)
        u2 = np.stack([np.cos(a2), np.sin(a2)], axis=-1)
        B = self.l1 * u1
        return {"A": np.zeros_like(B), "D": self.d * u1, "B": B,
                "E": B + self.h * u2, "C": B + self.l2 * u2}

    def equations_of_motion(self, state: ArrayLike, P: float = 0.0, H: float = 0.0, *,
                            check: bool = True) -> Matrix:
        """Right-hand side of the nonlinear equations of motion, eq. (10), with hinge viscosity.

        Parameters
        ----------
        state : array_like, shape (4,) or (4, n)
            ``[alpha1, alpha2, alpha1_dot, alpha2_dot]`` [rad, rad/s], finite.
        P, H : float
            Follower and dead loads [N], positive when compressive, finite.
        check : bool
            Refuse a state of another shape or a non-finite state or load
            (:class:`ParameterError`). Callers that validated the state and loads already
            pass ``False``; the integrators' ~1e6 calls per cycle go through
            :meth:`motion_at` (the same equations, bound once).

        Returns
        -------
        ndarray
            ``d(state)/dt``, same shape as ``state``.
        """
        if check:
            state = check_finite_reals("state", state)
            P, H = check_real("P", P), check_real("H", H)
            if state.ndim not in (1, 2) or state.shape[0] != 4 or state.size == 0:
                raise ParameterError(f"state must have shape (4,) or (4, n) "
                                     f"[alpha1, alpha2, alpha1_dot, alpha2_dot], got "
                                     f"{state.shape}")
            try:
                with np.errstate(over="ignore", invalid="ignore"):
                    out = self.equations_of_motion(state, P, H, check=False)
            except OverflowError:
                out = np.full(state.shape, np.inf)
            if not np.all(np.isfinite(out)):  # (an outside review: OverflowError, inf)
                raise ParameterError(f"state, P = {P!r}, H = {H!r}: the equations of motion "
                                     f"leave the double range")
            return out
        state = np.asarray(state, dtype=float)
        # One state: Python floats and math's functions, ~3x cheaper than numpy's on scalars;
        # several states: numpy. Same formulas (_motion).
        if state.ndim == 1:
            return np.array(self._motion(P, H, math.sin, math.cos)(*state.tolist()))
        return np.array(self._motion(P, H, np.sin, np.cos)(*state))

    def motion_at(self, P: float = 0.0, H: float = 0.0):
        """``f(t, state)``: :meth:`equations_of_motion`, unchecked, with the pendulum's
        constants and the loads bound once: an integrator's right-hand side (~2.0 us a call
        for one state against ~5.3 us, the same numbers; states of shape (4, n), as a
        ``vectorized`` integrator passes them, by numpy). ``P``, ``H`` [N] are checked here,
        once."""
        P, H = check_real("P", P), check_real("H", H)
        motion = self._motion(P, H, math.sin, math.cos)
        batched = self._motion(P, H, np.sin, np.cos)
        array = np.array

        def f(t: float, state: NDArray) -> NDArray:
            if state.ndim == 1:
                return array(motion(*state.tolist()))
            return array(batched(*state))

        return f

    def _inertia(self) -> tuple[float, float, float]:
        """``(w, I1, I2)`` of eq. (10)'s mass matrix ``[[I1, w c], [w c, I2]]``,
        ``c = cos(alpha1 - alpha2)``."""
        m2, m3, l1, l2 = self.m2, self.m3, self.l1, self.l2
        return ((m2 * l2 + m3 * self.h) * l1, self.m1 * self.d**2 + (m2 + m3) * l1**2,
                m2 * l2**2 + m3 * self.h**2)

    def _motion(self, P: float, H: float, sin, cos):
        """Eq. (10) solved for the accelerations: ``(a1, a2, w1, w2) -> (w1, w2, a1'', a2'')``
        with ``sin``, ``cos`` of math (floats) or numpy (arrays); the one definition of the
        equations of motion."""
        l1, l2 = self.l1, self.l2
        k1, k2, c1, c2 = self.k1, self.k2, self.c1, self.c2
        w, I1, I2 = self._inertia()

        def motion(a1, a2, w1, w2):
            s, c = sin(a1 - a2), cos(a1 - a2)
            # Generalised forces moved to the right-hand side of eq. (10): M(alpha) alpha'' = f.
            f1 = (-w * w2**2 * s - k1 * a1 - k2 * (a1 - a2)
                  - c1 * w1 - c2 * (w1 - w2) + P * l1 * s + H * l1 * sin(a1))
            f2 = (w * w1**2 * s + k2 * (a1 - a2) - c2 * (w2 - w1)
                  + H * l2 * sin(a2))
            det = I1 * I2 - (w * c) ** 2
            acc1 = (I2 * f1 - w * c * f2) / det
            acc2 = (I1 * f2 - w * c * f1) / det
            return w1, w2, acc1, acc2

        return motion

    def _motion_jacobian(self, P: float, H: float):
        """``(a1, a2, w1, w2) -> d(state')/d(state)`` of :meth:`_motion` (eq. 10), 4 x 4 nested
        lists, differentiated by hand term by term (the quotient rule on ``acc = N/det``); the
        tests hold it against sympy's derivative of the same equations and central
        differences. (sympy derived it at run time before: ~0.35-0.47 CPU-s of imports and
        algebra per process, measured, for a 4 x 4 matrix.)"""
        l1, l2 = self.l1, self.l2
        k1, k2, c1, c2 = self.k1, self.k2, self.c1, self.c2
        w, I1, I2 = self._inertia()
        sin, cos = math.sin, math.cos
        motion = self._motion(P, H, sin, cos)  # the accelerations: the one definition

        def jacobian(a1, a2, w1, w2):
            s, c = sin(a1 - a2), cos(a1 - a2)
            _, _, acc1, acc2 = motion(a1, a2, w1, w2)
            f1, f2 = I1 * acc1 + w * c * acc2, w * c * acc1 + I2 * acc2  # f = M(alpha) alpha''
            det = I1 * I2 - (w * c) ** 2
            # d f / d(a1, a2, w1, w2); s, c depend on a1 - a2 only
            g1 = (P * l1 - w * w2**2) * c
            g2 = w * w1**2 * c
            df1 = (g1 - k1 - k2 + H * l1 * cos(a1), k2 - g1, -c1 - c2, c2 - 2 * w * w2 * s)
            df2 = (g2 + k2, -g2 - k2 + H * l2 * cos(a2), 2 * w * w1 * s + c2, -c2)
            dc = (-s, s, 0.0, 0.0)  # d cos(a1 - a2)
            ddet = tuple(-2 * w * w * c * d for d in dc)
            row1 = [(I2 * a - w * c * b - w * f2 * d - acc1 * e) / det
                    for a, b, d, e in zip(df1, df2, dc, ddet, strict=True)]
            row2 = [(I1 * b - w * c * a - w * f1 * d - acc2 * e) / det
                    for a, b, d, e in zip(df1, df2, dc, ddet, strict=True)]
            return [[0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0], row1, row2]

        return jacobian


def check_pendulum(pendulum: object, name: str = "pendulum") -> ZieglerPendulum:
    """``pendulum`` if it is a :class:`ZieglerPendulum`, else a :class:`ParameterError` naming
    ``name`` (an outside audit: ``None`` gave AttributeErrors deep in the solvers)."""
    if not isinstance(pendulum, ZieglerPendulum):
        raise ParameterError(f"{name} must be a ZieglerPendulum, got {type(pendulum).__name__}")
    return pendulum
