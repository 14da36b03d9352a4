"""Closed forms for the Ziegler pendulum, chapter §2.2 (dead load, eqs. 17–25) and §2.3
(follower load, eqs. 32–48).

Everything is written in the dimensionless groups of eq. (17) (see
:class:`~flutterfriction.models.ziegler.PendulumGroups`); :func:`critical_loads_closed_form`
converts to newtons with ``P = gamma k2/l1`` and ``H = eta k2/l1``.

Erratum (eqs. 37, 39, 41): the text prints the half-width of the flutter interval as
``2 sqrt(k) a / beta2``; it is ``2 sqrt(k a) / beta2`` (the discriminant of eq. 34 is
``(beta1 - gamma beta2)^2 - 4 k a``, and eq. 42 follows only from ``sqrt(k a)``). The two agree
only when ``a = 1``, whatever ``k``: for list (47) (``k = 1``, ``a = 3.111``) the printed form
gives 3.28 N and 10.33 N, not the chapter's own 4.8 N and 8.8 N. The printed form is kept in
:func:`flutter_divergence_gammas_as_printed` as evidence for ``workflow/reference.yaml``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import (
    ParameterError,
    check_finite_reals,
    check_positive,
    check_real,
)
from flutterfriction.models.ziegler import PendulumGroups, ZieglerPendulum
from flutterfriction.results import CriticalLoads, Regime


def _groups(g: object) -> PendulumGroups:
    """``g`` itself if it is the groups of eq. (17) (they check their own values)."""
    if not isinstance(g, PendulumGroups):
        raise ParameterError(f"g must be the PendulumGroups of a pendulum (eq. 17; "
                             f"ZieglerPendulum.groups()), got {type(g).__name__}")
    return g


def coefficient_a(g: PendulumGroups) -> float:
    """``a`` of eq. (21)/(35): the omega^4 coefficient of the characteristic polynomial, > 0."""
    return g.lam**2 * (g.y1**2 * g.rho1 + (1 - g.y2) ** 2 * g.rho2
                       + g.y1**2 * g.y2**2 * g.rho1 * g.rho2)


def coefficient_beta1(g: PendulumGroups) -> float:
    """``beta1`` of eq. (21)/(35), > 0."""
    return (g.lam * (2 + 2 * g.y2 * g.rho2 + g.lam * (1 + g.y1**2 * g.rho1 + g.rho2))
            + (g.k + 1) * (1 + g.rho2 * g.y2**2))


def coefficient_beta2(g: PendulumGroups) -> float:
    """``beta2`` of eq. (35), > 0: the follower-load slope of the omega^2 coefficient."""
    return 1 + g.lam + g.y2**2 * g.rho2 + g.y2 * g.lam * g.rho2


def coefficient_delta2(g: PendulumGroups) -> float:
    """``delta2`` of eq. (21), > 0: the dead-load slope of the omega^2 coefficient."""
    return 1 + g.lam * (1 + g.y1**2 * g.rho1 + g.rho2) + g.rho2 * g.y2**2


def coefficient_c(g: PendulumGroups, eta: ArrayLike) -> NDArray:
    """``c(eta)`` of eq. (21): the constant term, det of the dimensionless K + G."""
    g, eta = _groups(g), check_finite_reals("eta", eta)
    return eta**2 / g.lam - eta * (1 + 1 / g.lam + g.k / g.lam) + g.k


# ---------------------------------------------------------------------- dead load, §2.2
def omega2_dead_load(g: PendulumGroups, eta: ArrayLike) -> NDArray:
    """The two roots ``omega^2`` of eq. (19), shape (..., 2), lower root first."""
    g, eta = _groups(g), check_finite_reals("eta", eta)
    a = coefficient_a(g)
    b = coefficient_beta1(g) - eta * coefficient_delta2(g)
    disc = b**2 - 4 * a * coefficient_c(g, eta)  # eq. (20); >= 0 since the problem is symmetric
    root = np.sqrt(np.maximum(disc, 0.0))
    return np.stack([(b - root) / (2 * a), (b + root) / (2 * a)], axis=-1)


def buckling_etas(g: PendulumGroups) -> tuple[float, float]:
    """``(eta_cr, eta_sup) = (H_cr l1/k2, H_sup l1/k2)`` of eq. (22)."""
    s = 1 + g.k + g.lam
    root = math.sqrt((g.lam - g.k) ** 2 + 1 + 2 * g.k + 2 * g.lam)
    eta_sup = (s + root) / 2
    # The roots' product is k lam (s^2 - root^2 = 4 k lam): eta_cr from it, not as s - root,
    # which cancels to a few digits where eta_cr << eta_sup (measured: 4.8e-6 relative at
    # k = 1.6e-5, l1/l2 = 1.3e-6; outside audit)
    return g.k * g.lam / eta_sup, eta_sup


def buckling_eta_equal_rods() -> float:
    """Eq. (25): ``H_cr L/K = (3 - sqrt 5)/2`` for k1 = k2 = K, l1 = l2 = L."""
    return (3 - math.sqrt(5)) / 2


# ---------------------------------------------------------------------- follower load, §2.3
def omega2_follower(g: PendulumGroups, gamma: ArrayLike) -> NDArray:
    """The two roots ``omega^2`` of eq. (34), complex, shape (..., 2)."""
    g, gamma = _groups(g), check_finite_reals("gamma", gamma)
    a = coefficient_a(g)
    b = coefficient_beta1(g) - gamma * coefficient_beta2(g)
    root = np.sqrt((b**2 - 4 * g.k * a).astype(complex))
    return np.stack([(b - root) / (2 * a), (b + root) / (2 * a)], axis=-1)


def follower_line_and_parabola(g: PendulumGroups, gamma: ArrayLike) -> tuple[NDArray, NDArray]:
    """Fig. 3: the line ``beta1 - gamma beta2`` and the parabola ``(...)^2 - 4ka`` of eq. (34)."""
    g, gamma = _groups(g), check_finite_reals("gamma", gamma)
    line = coefficient_beta1(g) - gamma * coefficient_beta2(g)
    return line, line**2 - 4 * g.k * coefficient_a(g)


def flutter_divergence_gammas(g: PendulumGroups) -> tuple[float, float]:
    """``(gamma_flu, gamma_div)`` of eqs. (39) and (41), corrected: ``beta1 -/+ 2 sqrt(k a)``."""
    b1, b2 = coefficient_beta1(g), coefficient_beta2(g)
    half = 2 * math.sqrt(g.k * coefficient_a(g))
    return (b1 - half) / b2, (b1 + half) / b2


def flutter_divergence_gammas_as_printed(g: PendulumGroups) -> tuple[float, float]:
    """Eqs. (39), (41) exactly as printed, ``beta1 -/+ 2 sqrt(k) a`` (erratum evidence only)."""
    b1, b2 = coefficient_beta1(g), coefficient_beta2(g)
    half = 2 * math.sqrt(g.k) * coefficient_a(g)
    return (b1 - half) / b2, (b1 + half) / b2


def follower_regime(g: PendulumGroups, gamma: float) -> Regime:
    """Classification of eq. (37) and the list after Fig. 3 (stable / flutter / divergence)."""
    gamma = check_real("gamma", gamma)  # (an outside review: NaN was "divergence")
    g_flu, g_div = flutter_divergence_gammas(_groups(g))
    if gamma < g_flu:
        return Regime.STABLE
    return Regime.FLUTTER if gamma < g_div else Regime.DIVERGENCE


def two_mass_gammas(lam: float, y: float, rho: float, k: float) -> tuple[float, float]:
    """Eq. (42) for m3 = 0 and its divergence twin: ``((1+lam)^2 + (lam y sqrt(rho) -/+ sqrt k)^2)
    / (1+lam)``. The chapter prints only the flutter one; eq. (48) uses both."""
    lam, rho, k = (check_positive(n, v) for n, v in (("lam", lam), ("rho", rho), ("k", k)))
    y = check_positive("y", y)
    if y > 1.0:
        raise ParameterError(f"y = d/l1 must be <= 1 (the mass on its rod), got {y!r}")
    s = lam * y * math.sqrt(rho)
    if not math.isfinite(s * s / (1 + lam) + (1 + lam) + k / (1 + lam)):
        raise ParameterError("lam, y, rho, k: eq. (42) leaves the double range")
    return (((1 + lam) ** 2 + (s - math.sqrt(k)) ** 2) / (1 + lam),
            ((1 + lam) ** 2 + (s + math.sqrt(k)) ** 2) / (1 + lam))


def optimal_two_mass_loads(l1: float, l2: float, k1: float, k2: float) -> tuple[float, float]:
    """Eqs. (44), (45) [N]: ``P_flu``, ``P_div`` when eq. (43) (sqrt k = lam y sqrt rho) holds."""
    l1, l2 = check_positive("l1", l1, "m"), check_positive("l2", l2, "m")
    k1, k2 = check_positive("k1", k1, "N m"), check_positive("k2", k2, "N m")
    p_flu = k2 * (1 / l1 + 1 / l2)
    p_div = p_flu + 4 * k1 * (l2 / l1) / (l1 + l2)
    if not (math.isfinite(p_flu) and math.isfinite(p_div)):
        raise ParameterError("l1, l2, k1, k2: the loads of eqs. (44), (45) leave the double "
                             "range")
    return p_flu, p_div


def critical_loads_closed_form(pendulum: ZieglerPendulum) -> CriticalLoads:
    """Critical loads [N] of the undamped pendulum from eqs. (22), (39), (41), after refusing a
    pendulum with hinge viscosity (the closed forms are undamped) or outside the model's
    numerical range, as the numerical twin does
    (:meth:`ZieglerPendulum.check_numerical_range`: one line naming the parameter)."""
    if not isinstance(pendulum, ZieglerPendulum):
        raise ParameterError(f"pendulum must be a ZieglerPendulum, got {type(pendulum).__name__}")
    if pendulum.c1 != 0 or pendulum.c2 != 0:
        # the undamped loads under the damped fields' names would be a silent wrong answer
        # (an outside audit: 4.30 N for a pendulum whose damped flutter load is 3.03 N)
        raise ParameterError(f"pendulum: the closed forms (eqs. 22, 39, 41) are the undamped "
                             f"pendulum's, got c1 = {pendulum.c1:g}, c2 = {pendulum.c2:g} N m s; "
                             f"use analysis.ziegler.critical_loads (damped loads) or "
                             f"pendulum.with_(c1=0, c2=0)")
    pendulum.check_numerical_range()
    g = pendulum.groups()
    g_flu, g_div = flutter_divergence_gammas(g)
    e_cr, e_sup = buckling_etas(g)
    u = pendulum.load_unit
    return CriticalLoads(P_flu=g_flu * u, P_div=g_div * u, H_cr=e_cr * u, H_sup=e_sup * u,
                         P_flu_undamped=g_flu * u, P_div_undamped=g_div * u)
