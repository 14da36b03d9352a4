"""The Beck and Pflüger rods (chapter §2.6–2.7): a cantilever of length ``l`` with bending
stiffness ``B``, Kelvin–Voigt internal viscosity ``D`` (eq. 83), mass per unit length ``rho``,
external damping ``kappa`` (per unit length) and a tip mass ``M``, loaded at the free end by a
tangential follower force ``P`` (positive when compressive). Beck: ``M = 0``. SI units.

Dimensionless groups (eq. 106): ``p = P l^2/B``, ``tan(alpha) = M/(rho l)``,
``eta = D/(B l^2) sqrt(B/rho)``, ``gamma = kappa l^2/sqrt(rho B)``; time ``tau = t/T`` with
``T = l^2 sqrt(rho/B)``, and ``v ~ exp(omega~ tau)`` (eq. 108), so Re omega~ > 0 is unstable.

:func:`characteristic_function` is eq. (118): ``f = det(115) / (lambda1 lambda2)``. Written with
``C1 = cosh(lambda1)``, ``S1 = sinh(lambda1)/lambda1``, ``c2 = cos(lambda2)``,
``s2 = sin(lambda2)/lambda2`` it is an entire function of ``lambda1^2`` and ``lambda2^2`` and
symmetric under the exchange of the two roots of eq. (113), hence an analytic function of
``omega~`` with no branch cut. We evaluate it in that form (stable as lambda1, lambda2 -> 0) with
the hyperbolic and trigonometric factors scaled by ``exp(-sigma)``,
``sigma = |Re lambda1| + |Im lambda2|``, so that nothing overflows for large or complex arguments.

Note on eq. (113)-(114): for ``sin(lambda2 xi)`` to solve eq. (109), ``lambda2^2`` must be
*minus* the second root of eq. (112) in ``lambda^2``:
``lambda1^2 = (-p + sqrt(Delta))/(2(1+eta w))``, ``lambda2^2 = (p + sqrt(Delta))/(2(1+eta w))``.
(The ``±`` of eq. 113 gives the two roots in ``lambda^2``; eq. 114 then uses
``lambda2 = sqrt(-lambda^2_2)``.)
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, fields

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import (
    ParameterError,
    check_nonnegative,
    check_positive,
    named_parameters,
)

#: Largest follower load of the nonlinear rod's cycle solvers (the ``limit-cycle beck`` command
#: and the beck_limit_cycle scene), in units of the linearised rod's damped flutter load: at 3
#: P_flu (8.9 N for list 119) the cycle takes ~14 s simulated; far above it the stiff
#: integration runs for minutes (an outside audit: 1e6 N ran until killed).
CYCLE_LOAD_MAX = 3.0
#: Further ranges of the cycle solvers: gamma and the tip-mass ratio M/(rho l) at most 100
#: (beyond, the integrations could run for hours or lose accuracy); the approach to the
#: cycle takes ~CYCLE_ATTRACTION_SCALES/eta time scales l^2 sqrt(rho/B) (measured on list
#: 119 at 5.5 N, 4 elements: converged at 14.6 s for eta = 1.36e-3, 35.6 s for 5.75e-4 and
#: 69.9 s for 2.9e-4), so eta must leave that within the simulated time allowed.
CYCLE_GAMMA_MAX, CYCLE_TIP_MASS_RATIO_MAX = 100.0, 100.0
CYCLE_ATTRACTION_SCALES = 0.13
#: The simulated time the cycle solvers allow, in time scales l^2 sqrt(rho/B): at most 2000,
#: 200 by default (31.4 s for list 119).
CYCLE_T_MAX_SCALES, CYCLE_T_MAX_DEFAULT_SCALES = 2000.0, 200.0

#: The rod solver's numerical range of the groups (analysis.rod checks it). Where the
#: numbers come from (measured with p_max up to 1000, see the stress report):
#: tan(alpha) <= 1e4: beyond it the tip mode's Omega^2 ~ 1/tan(alpha) sinks to the pencil's
#: round-off (eps ||A|| ~ 1e-12) and its flutter/divergence verdict is lost (1e5 fails at
#: p ~ 119); eta <= 1: at eta = 2 the damped-flutter Newton leaves for p -> 0 at p_max = 1000
#: (eta = 10 gives overdamped roots that the exact regime check cannot separate);
#: gamma <= 1e4: checked alone and with eta = 1, tan(alpha) = 1e4; the smallest positive
#: damping 1e-100 keeps every O(damping) imaginary part of eq. (118) (products with
#: omega~^3 ~ 1e6 or its inverse) a normal float, far above 1e-300.
GROUP_RANGES: dict[str, tuple[float, float]] = {
    "tan_alpha": (0.0, 1e4), "eta": (1e-100, 1.0), "gamma": (1e-100, 1e4)}


#: The SI units of a rod's parameters (:class:`Rod`), in its fields' order.
ROD_UNITS = {"length": "m", "B": "N m^2", "rho": "kg/m", "D": "N m^2 s", "kappa": "N s/m^2",
             "tip_mass": "kg"}


@named_parameters
@dataclass(frozen=True)
class RodGroups:
    """Dimensionless parameters of eq. (106) (the load ``p`` varies and is not stored)."""

    tan_alpha: float = 0.0  # M / (rho l)
    eta: float = 0.0  # internal (Kelvin-Voigt) viscosity
    gamma: float = 0.0  # external damping

    def __post_init__(self) -> None:
        for f in fields(self):
            object.__setattr__(self, f.name, check_nonnegative(f.name, getattr(self, f.name)))

    @property
    def damped(self) -> bool:
        return self.eta > 0 or self.gamma > 0


@named_parameters
@dataclass(frozen=True)
class Rod:
    """A Beck (``tip_mass = 0``) or Pflüger rod in SI units.

    Parameters
    ----------
    length : float
        ``l`` [m], > 0.
    B : float
        Bending stiffness [N m^2], > 0.
    rho : float
        Mass per unit length [kg/m], > 0.
    D : float
        Kelvin–Voigt internal viscosity, ``M = B theta' + D theta'_dot`` (eq. 83) [N m^2 s], >= 0.
    kappa : float
        External damping per unit length [N s/m^2], >= 0.
    tip_mass : float
        Concentrated mass at the loaded end [kg], >= 0 (rotary inertia neglected, eq. 104).
    """

    length: float
    B: float
    rho: float
    D: float = 0.0
    kappa: float = 0.0
    tip_mass: float = 0.0

    def __post_init__(self) -> None:
        for f in fields(self):
            check = check_positive if f.name in ("length", "B", "rho") else check_nonnegative
            object.__setattr__(self, f.name, check(f.name, getattr(self, f.name),
                                                   ROD_UNITS[f.name]))

    @property
    def time_scale(self) -> float:
        """``T = l^2 sqrt(rho/B)`` [s]: t = T tau (eq. 106)."""
        return power_product((self.length, 2), (self.rho, 0.5), (self.B, -0.5),
                             name="length, rho, B: the time scale l^2 sqrt(rho/B)")

    @property
    def load_unit(self) -> float:
        """``B/l^2`` [N]: P = p B/l^2 (eq. 106)."""
        return power_product((self.B, 1), (self.length, -2),
                             name="B, length: the load unit B/l^2")

    def groups(self) -> RodGroups:
        """Eq. (106)."""
        return RodGroups(
            tan_alpha=power_product((self.tip_mass, 1), (self.rho, -1), (self.length, -1),
                                    name="tip_mass: tan(alpha) = M/(rho l)"),
            eta=power_product((self.D, 1), (self.B, -0.5), (self.rho, -0.5), (self.length, -2),
                              name="D: eta = D/(B l^2) sqrt(B/rho)"),
            gamma=power_product((self.kappa, 1), (self.length, 2), (self.rho, -0.5),
                                (self.B, -0.5), name="kappa: gamma = kappa l^2/sqrt(rho B)"))


def power_product(*factors: tuple[float, float], name: str = "power_product") -> float:
    """``prod x**a`` over ``(x, a)``, ``x >= 0``, ``a`` in {±1/2, ±1, ±2}, with no overflow or
    underflow on the way: each ``x`` is split into its mantissa and binary exponent
    (``math.frexp``), the mantissas multiplied (a product of numbers in [1/2, 2)) and the
    exponents added, so that ``l^2 = 1e-320`` (a subnormal: digits lost) or
    ``rho/B = 1e400`` (an overflow) never occur when the result itself is a normal float
    (eq. 106's groups and units of extreme SI input). Exact to a few ulps. ``name``: the
    parameters and the group, for the refusal of a result outside the normal double range."""
    mantissa, exponent = 1.0, 0
    for x, a in factors:
        if x == 0:
            if a < 0:
                raise ZeroDivisionError("power_product: a zero factor with a negative power")
            return 0.0
        m, e = math.frexp(x)
        if abs(a) == 0.5:  # sqrt(m 2^e) = sqrt(m 2^(e mod 2)) 2^(e // 2)
            m, e = math.sqrt(m * 2.0 ** (e % 2)), e // 2
            a = math.copysign(1, a)
        mantissa, shift = math.frexp(mantissa * m ** int(a))
        exponent += shift + e * int(a)
    if exponent > sys.float_info.max_exp:
        raise ParameterError(f"{name} is beyond the double range (2^{exponent}; the "
                             f"product of {[x for x, _ in factors]} to the powers "
                             f"{[a for _, a in factors]}): rescale the input")
    if exponent < sys.float_info.min_exp:
        # A non-zero product below the normal range would round to a subnormal or to 0: a
        # damping group of 0 turns the vanishing-damping answer (10.94) into the undamped one
        # (20.05) without a sign.
        raise ParameterError(f"{name} is below the normal double range (2^{exponent}; the "
                             f"product of {[x for x, _ in factors]} to the powers "
                             f"{[a for _, a in factors]}): rescale the input")
    return math.ldexp(mantissa, exponent)


def _scaled_even_functions(lam: NDArray, trig: bool) -> tuple[NDArray, NDArray, NDArray]:
    """``(cosh lam, sinh lam / lam)`` (or ``cos``, ``sin/lam`` when ``trig``) times
    ``exp(-s)``, with ``s = |Re lam|`` (``|Im lam|`` for trig), and ``s`` itself."""
    z = 1j * lam if trig else lam  # cos(l) = cosh(i l), sin(l)/l = sinh(i l)/(i l)
    s = np.abs(z.real)
    ep = np.exp(z - s)
    em = np.exp(-z - s)
    c = 0.5 * (ep + em)
    small = np.abs(z) < 1e-3
    # Where |Re z| < 1 nothing can overflow: cosh and sinh directly. This keeps the digits of a
    # tiny Re z (a nearly real lambda2 at vanishing damping, Im ~ 1e-20), which the factors
    # exp(-2|Re z|) of the scaled form round away: Im cos(x + iy) = -sin(x) sinh(y).
    mild = s < 1.0
    zm = np.where(mild, z, 0.0)
    c = np.where(mild, np.cosh(zm) * np.exp(-s), c)
    with np.errstate(divide="ignore", invalid="ignore"):
        sc = np.where(small, (1 + z**2 / 6 + z**4 / 120) * np.exp(-s),
                      np.where(mild, np.sinh(zm) / z * np.exp(-s), 0.5 * (ep - em) / z))
    return c, sc, s


def lambda_squares(p: ArrayLike, w: ArrayLike, g: RodGroups) -> tuple[NDArray, NDArray]:
    """``(lambda1^2, lambda2^2)`` of eqs. (112)–(114): ``lambda1^2`` is a root of eq. (112) in
    ``lambda^2`` and ``lambda2^2`` minus the other one."""
    p = np.asarray(p, dtype=complex)
    w = np.asarray(w, dtype=complex)
    a = 1 + g.eta * w
    root = np.sqrt(p**2 - 4 * a * (g.gamma * w + w**2))
    return (-p + root) / (2 * a), (p + root) / (2 * a)


def characteristic_function(p: ArrayLike, w: ArrayLike, g: RodGroups,
                            with_exponent: bool = False):
    """Eq. (118), ``f(p, omega~, alpha, gamma, eta)``, evaluated stably (vectorised).

    Returns ``f exp(-sigma)`` and, when ``with_exponent``, ``sigma`` (so ``f = F exp(sigma)``);
    zeros of the returned value are exactly the zeros of ``f``. Non-finite arguments are
    refused (:class:`ParameterError`; they returned NaN silently, an outside audit).
    """
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(w))):
        raise ParameterError(f"p and omega~ must be finite (eq. 118), got p = {p!r}, "
                             f"omega~ = {w!r}")
    L1, L2 = lambda_squares(p, w, g)
    lam1, lam2 = np.sqrt(L1), np.sqrt(L2)
    C1, S1, s1 = _scaled_even_functions(lam1, trig=False)
    c2, s2, t2 = _scaled_even_functions(lam2, trig=True)
    w = np.asarray(w, dtype=complex)
    a = 1 + g.eta * w
    sigma = s1 + t2
    F = (a * (L1**2 + L2**2) * np.exp(-sigma) + 2 * a * L1 * L2 * C1 * c2
         + a * L1 * L2 * (L2 - L1) * S1 * s2
         - w**2 * g.tan_alpha * (L1 + L2) * (S1 * c2 - C1 * s2))
    return (F, sigma) if with_exponent else F
