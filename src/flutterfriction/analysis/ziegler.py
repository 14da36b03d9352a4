"""Numerical stability analysis of the Ziegler pendulum (chapter §2.2–2.3), from its matrices only.

These are the numerical twins of the closed forms in :mod:`flutterfriction.closed_forms.ziegler`:
nothing here uses the chapter's formulas (19)–(48).
"""

from __future__ import annotations

import functools
import math
from fractions import Fraction
from typing import Any

import numpy as np
import scipy.linalg as sla
from numpy.typing import ArrayLike, NDArray

from flutterfriction.analysis.damped import confirm_onset, divergence_onset, flutter_onset
from flutterfriction.analysis.polynomial import characteristic_polynomial, regime_from_coefficients
from flutterfriction.analysis.stability import (
    Regime,
    classify,
    coalescence_loads,
    first_order_matrix,
    state_eigenvalues,
)
from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_finite_reals,
    check_integer,
    check_real,
)
from flutterfriction.models.ziegler import DimensionlessMatrices, ZieglerPendulum, check_pendulum
from flutterfriction.results import CriticalLoads  # noqa: F401  (re-exported)


def _dimensionless(pendulum: ZieglerPendulum) -> DimensionlessMatrices:
    """The pendulum's matrices in the units of eqs. (17), (29), (32), after refusing a pendulum
    outside the model's numerical range (:meth:`ZieglerPendulum.check_numerical_range`).

    Loads come out in units of ``k2/l1`` (gamma, eta), so no SI scale can overflow; they are
    converted to newtons by one multiplication at the end."""
    check_pendulum(pendulum).check_numerical_range()
    return pendulum.dimensionless_matrices()


#: Zoomed scan windows (each 8 times smaller) tried when the first brackets nothing: down to
#: 8^-12 = 1.5e-11 of it, below any coalescence of the model's numerical range (ratios 1e+-6).
ZOOMS = 12


def follower_critical_gammas(pendulum: ZieglerPendulum, n_scan: int = 512,
                             max_doublings: int = 40) -> tuple[float, float]:
    """Dimensionless ``(gamma_flu, gamma_div) = (P_flu, P_div) l1/k2`` under the follower load
    alone, from the dimensionless matrices (see :func:`follower_critical_loads`).

    The scan window starts at ``4 max(1, k1/k2)``; where it brackets nothing, it shrinks
    (:data:`ZOOMS` times by 8), then doubles at most ``max_doublings - 1`` times
    (to ``2e12`` load units with 40: far above any coalescence in the model's numerical range,
    where ``gamma_div`` stays below ``~1e8``). A discriminant at its round-off floor is never
    minimised: there, and where no window brackets the pair (a flutter interval narrower than
    the scan's step at every zoom), the two loads are solved from the discriminant's factors
    (:func:`_coalescences_by_factors`)."""
    n_scan = check_integer("n_scan", n_scan, 8, 10**6)
    max_doublings = check_integer("max_doublings", max_doublings, 1, 1000)
    m = _dimensionless(pendulum)
    base = 4.0 * max(1.0, pendulum.k1 / pendulum.k2)
    # the window k1/k2 suggests first; where it brackets nothing, windows 8, 64, ... times
    # smaller (both loads can lie in its first step: k1/k2 = 1e6 with l1/l2 = 1e3 puts them at
    # 1e3 and 5e3 load units, within 4e6/512; an outside audit), then larger ones
    windows = [base] + [base * 8.0**-j for j in range(1, ZOOMS + 1)] \
        + [base * 2.0**j for j in range(1, max_doublings)]
    i = 0
    while i < len(windows):
        load_max = windows[i]
        try:
            roots = coalescence_loads(m.K, m.G_follower, m.M, load_max, n_scan,
                                      noise_floor=True)
        except ConvergenceError as exc:
            # The eigenvalues' discriminant is at its round-off floor (a flutter interval
            # ~1e-6 wide): the same coalescences from the discriminant's factors.
            return _coalescences_by_factors(m.K, m.G_follower, m.M, f"{exc}; the load unit is "
                                          f"k2/l1 = {pendulum.load_unit:.4g} N")
        if len(roots) >= 2:
            if len(roots) > 2:
                raise ConvergenceError(f"expected two coalescence loads, found {roots} "
                                       f"(in units of k2/l1)")
            return roots[0], roots[1]
        # One load in the first window: the pendulum's other coalescence lies above it (the
        # zoomed windows lie inside it, and its scan brackets pairs far below its step, see
        # coalescence_loads), so the larger windows come next: list (47) scanned 2 windows,
        # not 14 (0.24 -> 0.04 s a pendulum; the hypothesis tests spent minutes in the zooms).
        i = ZOOMS + 1 if (i == 0 and len(roots) == 1) else i + 1
    # No window brackets the pair (a flutter interval narrower than the scan's step at every
    # zoom, the discriminant never at its floor either: an outside review, relative gaps down
    # to 2e-10): the same coalescences from the discriminant's factors.
    return _coalescences_by_factors(
        m.K, m.G_follower, m.M,
        f"no flutter/divergence coalescence bracketed from P = {windows[ZOOMS]:.3g} to "
        f"{windows[-1]:g} k2/l1 (a flutter interval narrower than the scan resolves)")


def _coalescences_by_factors(K: NDArray, G: NDArray, M: NDArray, why: str = ""
                           ) -> tuple[float, float]:
    """The two coalescence loads of a two-degree-of-freedom pencil, each as the simple root of
    its own factor of the discriminant.

    ``det(K + g G - mu M) = det(M) mu^2 - b(g) mu + c(g)`` with ``b = b0 + g b1`` (the
    cofactor-weighted trace) and ``c = det(K + g G) = c0 + g c1 + g^2 c2``; ``mu`` is double
    where ``D(g) = b^2 - 4 det(M) c`` vanishes, and ``D = f_+ f_-`` with
    ``f_(+/-)(g) = b(g) -/+ 2 sqrt(det(M) c(g))``: the flutter and the divergence load are the
    roots of different factors, each simple however close the two loads are (where ``D``'s
    own roots, as a quadratic's, cancel: its discriminant ``A1^2 - 4 A2 A0`` loses every digit
    at a relative gap ~1e-8, an outside review refused pendulums with gaps of 2e-10..1.3e-6).
    Each factor's root by Newton from the root with ``c`` frozen at ``c0`` (exact for a
    follower load, whose ``c`` is constant). Generic 2x2 algebra on the matrices (no formula
    of the chapter), used where the eigenvalues' discriminant is at its round-off floor."""
    dM = float(np.linalg.det(M))

    def cofactor_trace(A: NDArray, B: NDArray) -> float:
        return float(A[0, 0] * B[1, 1] + A[1, 1] * B[0, 0] - A[0, 1] * B[1, 0]
                     - A[1, 0] * B[0, 1])

    b0, b1 = cofactor_trace(K, M), cofactor_trace(G, M)
    c0, c1, c2 = float(np.linalg.det(K)), cofactor_trace(K, G), float(np.linalg.det(G))
    if not (dM > 0 and c0 > 0 and b1 != 0):
        raise ConvergenceError(f"{why}; nor from the discriminant's factors: det M = {dM:.3g}, "
                               f"det K = {c0:.3g} and the load's trace {b1:.3g} leave none")
    roots = []
    for sign in (1.0, -1.0):
        g = (-b0 + sign * 2 * math.sqrt(dM * c0)) / b1
        for _ in range(60):
            c = c0 + g * (c1 + g * c2)
            if not c > 0:
                g = math.nan
                break
            root = math.sqrt(dM * c)
            f = b0 + g * b1 - sign * 2 * root
            df = b1 - sign * dM * (c1 + 2 * g * c2) / root
            step = f / df if df != 0 else math.inf
            g -= step
            if abs(step) <= 1e-14 * abs(g):
                break
        else:
            g = math.nan
        if not (math.isfinite(g) and g > 0):
            raise ConvergenceError(f"{why}; nor from the discriminant's factors: no positive "
                                   f"coalescence load of the factor b {'-' if sign > 0 else '+'}"
                                   f" 2 sqrt(det M c)")
        roots.append(g)
    return float(min(roots)), float(max(roots))


def follower_critical_loads(pendulum: ZieglerPendulum, n_scan: int = 512,
                            max_doublings: int = 40) -> tuple[float, float]:
    """Flutter and divergence loads ``(P_flu, P_div)`` [N] under the follower load alone (H = 0).

    Both are coalescence points of the eigenvalues ``Omega^2`` of ``(K + P dG/dP, M)`` (eq. 14),
    found by :func:`~flutterfriction.analysis.stability.coalescence_loads` on the
    dimensionless matrices (loads in units of ``k2/l1``)."""
    g_flu, g_div = follower_critical_gammas(pendulum, n_scan, max_doublings)
    u = pendulum.load_unit
    return g_flu * u, g_div * u


def dead_critical_etas(pendulum: ZieglerPendulum) -> tuple[float, float]:
    """Dimensionless ``(eta_cr, eta_sup) = (H_cr, H_sup) l1/k2`` (see :func:`dead_critical_loads`).

    The symmetric-definite pencil ``K a = eta B a`` (``B = -dG/dH``, diagonal positive) is
    reduced to ``S = B^-1/2 K B^-1/2``. Its larger eigenvalue ``(tr S + sqrt((S11 - S22)^2 +
    4 S12^2))/2`` adds positive terms only (no cancellation), and the smaller one is
    ``det S / larger`` with ``det S = det K / det B``, where ``det K = k1 k2`` is taken from the
    factorised stiffness ``K = T^T diag(k1, k2) T`` (elastic energy of the two hinges,
    ``T = [[1, 0], [1, -1]]``): the difference ``(k1 + k2) k2 - k2^2`` is never formed, so
    ``H_cr`` keeps full precision when ``k1 << k2`` (``eigh`` on ``K`` loses ``eps k2/k1``)."""
    m = _dimensionless(pendulum)
    b = np.sqrt(-np.diag(m.G_dead))  # B^(1/2), B diagonal
    S = m.K / np.outer(b, b)
    tr_half = 0.5 * (S[0, 0] + S[1, 1])
    upper = tr_half + math.hypot(0.5 * (S[0, 0] - S[1, 1]), S[0, 1])
    T = np.array([[1.0, 0.0], [1.0, -1.0]])
    det_K = (pendulum.k1 / pendulum.k2) * np.linalg.det(T) ** 2  # det(T^T diag(k, 1) T)
    det_S = det_K / float(np.prod(b**2))
    lower = det_S / upper
    if not (0 < lower <= upper and math.isfinite(upper)):
        raise ConvergenceError(f"dead buckling loads not resolved: {lower!r}, {upper!r}")
    return float(lower), float(upper)


def dead_critical_loads(pendulum: ZieglerPendulum) -> tuple[float, float]:
    """Buckling loads ``(H_cr, H_sup)`` [N] under the dead load alone (P = 0).

    Quasi-static bifurcations ``det(K + H dG/dH) = 0``, i.e. the symmetric-definite generalised
    eigenproblem ``K a = H diag(l1, l2) a``, solved in dimensionless form without cancellation
    (:func:`dead_critical_etas`)."""
    e_cr, e_sup = dead_critical_etas(pendulum)
    u = pendulum.load_unit
    return e_cr * u, e_sup * u


def is_damped(pendulum: ZieglerPendulum) -> bool:
    return pendulum.c1 > 0 or pendulum.c2 > 0


def _damped_args(pendulum: ZieglerPendulum, dead: bool = False) -> tuple:
    """``(M, C, K, dG)`` dimensionless (loads in units of k2/l1), range-checked, as exact
    fractions: the Routh, Sturm and Hurwitz verdicts on the characteristic polynomial are then
    exact for the pendulum itself (see :meth:`ZieglerPendulum.dimensionless_matrices`); the
    eigenvalue methods round them to doubles."""
    m = _exact_dimensionless(pendulum)
    return (m.M, m.C, m.K, m.G_dead if dead else m.G_follower)


def _exact_dimensionless(pendulum: ZieglerPendulum) -> DimensionlessMatrices:
    """:func:`_dimensionless`'s checks, then the matrices as exact fractions."""
    _dimensionless(pendulum)
    return pendulum.dimensionless_matrices(exact=True)


def _window(pendulum: ZieglerPendulum) -> float:
    return 4.0 * max(1.0, pendulum.k1 / pendulum.k2)


def damped_flutter_load(pendulum: ZieglerPendulum, method: str = "routh") -> float:
    """Flutter load [N] with viscous hinges (eq. 27): the follower load at which a pair of
    eigenvalues crosses the imaginary axis. ``method``: ``"routh"`` (exact Routh–Hurwitz on the
    characteristic polynomial, the accurate one at small viscosity) or ``"eigenvalues"``.

    As the viscosity vanishes the load tends to its eps -> 0 limit (the Ziegler paradox,
    eq. 54): the exact Routh verdict resolves it down to the smallest relative viscosity the
    model accepts. The eigenvalue crossing cannot resolve a growth rate below its round-off
    (``~1e-16`` of the spectral scale) and refuses (:class:`ConvergenceError`) when the
    spectrum's real parts are at round-off already at zero load."""
    args = _damped_args(pendulum)
    p = flutter_onset(*args, method=method, load_max=_window(pendulum))
    if method == "eigenvalues":  # a silent wrong crossing at extreme ratios: refused
        p = confirm_onset(*args, p, "flutter")
    return p * pendulum.load_unit


# Memoised (the pendulum is a frozen dataclass): the configuration check and the §2.9 scenes
# ask for the same pendulum's load 3-5 times in one process, ~65 ms each (the exact scan).
def damped_divergence_load(pendulum: ZieglerPendulum, method: str = "algebraic") -> float:
    """Divergence load [N] with viscous hinges: the follower load at which the unstable pair
    becomes real. ``method``: ``"algebraic"`` (Routh/Sturm root counts and the resultant of the
    characteristic polynomial; the default: exact verdicts at any ratio the model accepts) or
    ``"eigenvalues"`` (refused, ConvergenceError, where the exact verdicts do not confirm it:
    at extreme length ratios its round-off moved the load by up to 0.67, measured). The scan
    starts at the damped flutter load from the exact Routh criterion. Computed once per
    pendulum and method (the arguments checked before the cache: an outside audit's ``{}``
    gave "unhashable type")."""
    check_pendulum(pendulum)
    if not isinstance(method, str) or method not in ("algebraic", "eigenvalues"):
        raise ParameterError(f"method must be 'algebraic' or 'eigenvalues', got {method!r}")
    return _damped_divergence_load(pendulum, method)


@functools.lru_cache(maxsize=256)
def _damped_divergence_load(pendulum: ZieglerPendulum, method: str) -> float:
    args = _damped_args(pendulum)
    start = flutter_onset(*args, method="routh", load_max=_window(pendulum))
    # Doubling until the double range ends (~15 s at worst, bounded): an outside audit found
    # divergence 1e20 times the flutter load (c1 = 0, k1/k2 = 1e-2, m1/m2 = 1e6: 1.0e-14 N and
    # 999010.77 N) beyond the 60 doublings allowed before, refused.
    try:
        p = divergence_onset(*args, method=method, start=start, load_max=2 * start,
                             max_doublings=2000)
    except ConvergenceError as exc:  # its loads are in units of k2/l1: said in newtons
        raise ConvergenceError(f"damped divergence load: {exc} (loads in units of k2/l1 = "
                               f"{pendulum.load_unit:g} N)") from None
    if method == "eigenvalues":
        p = confirm_onset(*args, p, "divergence")
    return p * pendulum.load_unit


def damped_dead_load_onset(pendulum: ZieglerPendulum, method: str = "routh") -> float:
    """First dead load [N] at which the damped pendulum loses stability (it is H_cr: §2.2)."""
    return flutter_onset(*_damped_args(pendulum, dead=True), method=method,
                         load_max=_window(pendulum)) * pendulum.load_unit


def critical_loads(pendulum: ZieglerPendulum) -> CriticalLoads:
    """All critical loads of the pendulum, computed numerically from its matrices."""
    P_flu0, P_div0 = follower_critical_loads(pendulum)
    H_cr, H_sup = dead_critical_loads(pendulum)
    if is_damped(pendulum):
        P_flu, P_div = damped_flutter_load(pendulum), damped_divergence_load(pendulum)
    else:
        P_flu, P_div = P_flu0, P_div0
    return CriticalLoads(P_flu=P_flu, P_div=P_div, H_cr=H_cr, H_sup=H_sup,
                         P_flu_undamped=P_flu0, P_div_undamped=P_div0)


def _undamped_biquadratic(pendulum: ZieglerPendulum, P: float, H: float
                          ) -> tuple[Fraction, Fraction, Fraction]:
    """``(a, b, c)`` with ``det(M lam + K + gamma G_f + eta G_d) = a lam^2 + b lam + c``,
    ``lam = s^2`` in units of ``k2/(m2 l2^2)`` (the undamped eq. 11 plus eq. 26): the
    characteristic polynomial in exact fractions of the parameters and of the loads in units
    of k2/l1 (rounded once; :func:`_exact_loads`), whose odd coefficients vanish."""
    m = _exact_dimensionless(pendulum)
    a, _, b, _, c = characteristic_polynomial(m.M, m.C, _exact_loads(pendulum, m, P, H))
    return a, b, c


def _exact_loads(pendulum: ZieglerPendulum, m: DimensionlessMatrices, P: float, H: float
                 ) -> NDArray:
    """``K + gamma G_f + eta G_d`` in exact fractions, the loads in units of k2/l1 rounded once
    (refused, naming them, where they overflow)."""
    gamma, eta = P / pendulum.load_unit, H / pendulum.load_unit
    if not (math.isfinite(gamma) and math.isfinite(eta)):
        raise ParameterError(f"the loads P = {P!r}, H = {H!r} N overflow in units of k2/l1 = "
                             f"{pendulum.load_unit:.3g} N")
    return m.K + Fraction(gamma) * m.G_follower + Fraction(eta) * m.G_dead


def _undamped_regime(a: Fraction, b: Fraction, c: Fraction) -> Regime | None:
    """The regime from the exact biquadratic ``a s^4 + b s^2 + c`` (``a = det M > 0``): complex
    ``s^2`` is flutter, a positive real ``s^2`` divergence, two distinct negative ones stable;
    None on a boundary (``c = 0``: s = 0; a double ``s^2``)."""
    if a <= 0:
        return None
    disc = b * b - 4 * a * c
    if disc < 0:
        return Regime.FLUTTER
    if c < 0 or (c > 0 and b < 0):  # s^2 of opposite signs, or both positive
        return Regime.DIVERGENCE
    if c > 0 and b > 0 and disc > 0:
        return Regime.STABLE
    return None


def _undamped_spectrum(pendulum: ZieglerPendulum, a: Fraction, b: Fraction, c: Fraction
                       ) -> NDArray | None:
    """The undamped spectrum [1/s] from the exact biquadratic ``(a, b, c)``
    (:func:`_undamped_biquadratic`): ``s^2`` from its exact discriminant, the smaller root from
    the product ``c/a`` (no cancellation), ``s = +-sqrt``, in units of ``sqrt(k2/m2)/l2``;
    None where it leaves the double range."""
    disc = b * b - 4 * a * c
    if a <= 0:
        return None
    try:
        fa, fb, fc, fd = (float(v) for v in (a, b, c, disc))
        if disc >= 0:
            q = -(fb + math.copysign(math.sqrt(fd), fb)) / 2
            lams = [q / fa, fc / q] if q != 0 else [0.0, 0.0]
        else:
            w = math.sqrt(-fd) / (2 * fa)
            lams = [complex(-fb / (2 * fa), w), complex(-fb / (2 * fa), -w)]
    except (OverflowError, ZeroDivisionError):
        lams = _biquadratic_roots_by_ratios(a, b, c, disc)
    unit = math.sqrt(pendulum.k2) / (math.sqrt(pendulum.m2) * pendulum.l2)
    with np.errstate(over="ignore", invalid="ignore"):  # (an infinite root: None below)
        root = np.sqrt(np.array(lams, dtype=complex)) * unit
    s = np.concatenate([root, -root])
    if not np.all(np.isfinite(s)):
        return None
    return s[np.lexsort((-s.imag, -s.real))]


def _biquadratic_roots_by_ratios(a: Fraction, b: Fraction, c: Fraction, disc: Fraction
                                 ) -> list[complex]:
    """The roots ``lam`` of ``a lam^2 + b lam + c`` from exact ratios of the coefficients, each
    rounded once: where the coefficients or ``b^2`` leave the double range (an outside review:
    at P = 1e160 load units the first-order matrix's eigenvalues gave the slow pair as
    -3.4e63, 1.1e64 instead of +-7.1e-81). A ratio beyond the double range raises
    OverflowError (the roots themselves overflow)."""
    if b == 0:
        r = math.sqrt(abs(float(c / a)))
        return [r, -r] if c < 0 else [complex(0.0, r), complex(0.0, -r)]
    if disc >= 0:
        # q = -(b/2)(1 + sqrt(disc/b^2)); lam1 = q/a, lam2 = c/q
        # (b/2a, not b/a then halved: b/a times root overflowed for |b/a| > DBL_MAX/2, an
        # outside audit at P = 1e308 load units)
        root = 1.0 + math.sqrt(float(disc / (b * b)))
        return [-float(b / (2 * a)) * root, -2 * float(c / b) / root]
    w = math.sqrt(float(-disc / (4 * a * a)))
    re = -float(b / (2 * a))
    return [complex(re, w), complex(re, -w)]


#: Largest backward error of a damped pendulum's first-order eigenvalues against its exact
#: characteristic polynomial, ``|p(s)| / sum |a_i| |s|^i``: a backward-stable eigensolver gives
#: ~1e-15 (measured); above it the eigenvalues are not the polynomial's roots (an outside
#: review: at P = 1e9 load units the slow pair came out 5e-11 +- 9.2e-5i, flutter, instead of
#: the real +-2.24e-5, backward error ~1) and the roots are taken in multiple precision.
SPECTRUM_BACKWARD_ERROR = 1e-10


def _damped_spectrum(pendulum: ZieglerPendulum, s: NDArray, coefficients: NDArray) -> NDArray:
    """The first-order eigenvalues ``s`` [1/s] of a damped pendulum, checked against its exact
    characteristic polynomial (``coefficients``, highest degree first, in the dimensionless
    ``s`` of units ``sqrt(k2/m2)/l2``); where they are not its roots, the polynomial's roots
    in 40-digit arithmetic (mpmath's polyroots), sorted as :func:`state_eigenvalues`."""
    unit = math.sqrt(pendulum.k2) / (math.sqrt(pendulum.m2) * pendulum.l2)
    try:
        a = np.array([float(x) for x in coefficients])
        sigma = s / unit
        powers = sigma[:, None] ** np.arange(len(a) - 1, -1, -1)[None, :]
        with np.errstate(over="ignore", invalid="ignore"):
            backward = np.abs(powers @ a) / (np.abs(powers) @ np.abs(a))
        if np.all(np.isfinite(backward)) and backward.max() <= SPECTRUM_BACKWARD_ERROR:
            return s
    except OverflowError:
        pass
    import mpmath as mp

    with mp.workdps(40):
        exact = [mp.mpf(x.numerator) / x.denominator for x in coefficients]
        try:
            roots = mp.polyroots(exact, maxsteps=400, extraprec=200)
        except mp.libmp.NoConvergence:
            raise ConvergenceError(
                "the spectrum of this damped pendulum at these loads is beyond the "
                "first-order eigenvalues (they are not the characteristic polynomial's "
                "roots) and the polynomial's roots did not converge") from None
        out = np.array([complex(r) for r in roots]) * unit
    if not np.all(np.isfinite(out)):
        raise ParameterError("the loads put the spectrum beyond the double range")
    return out[np.lexsort((-out.imag, -out.real))]


def spectrum(pendulum: ZieglerPendulum, P: float = 0.0, H: float = 0.0) -> NDArray:
    """Eigenvalues ``s = -i Omega`` [1/s] of the first-order form of eq. (11) plus eq. (26).

    Undamped: the roots of the exact biquadratic ``det(M s^2 + K)`` (:func:`_undamped_spectrum`):
    the eigenvalues of the first-order matrix lose a slow pair to round-off when the spectrum
    spans ~1e10 (an outside audit: a pendulum with l1/l2 = 2.3e4, k1/k2 = 1.2e-5 in divergence
    at 1.5 H_cr gave the pair 6.8e-14 +- 1704i instead of +-1.083e-7). Damped: the eigenvalues
    of the first-order matrix."""
    return _spectrum(pendulum, P, H)[0]


def _spectrum(pendulum: ZieglerPendulum, P: float, H: float
              ) -> tuple[NDArray, tuple[Fraction, Fraction, Fraction] | None]:
    """:func:`spectrum`, and the undamped pendulum's exact biquadratic (None when damped), which
    :func:`regime` then uses without forming it again."""
    K = _finite_stiffness(check_pendulum(pendulum), P, H)
    coefficients = None
    if not is_damped(pendulum):
        coefficients = _undamped_biquadratic(pendulum, check_real("P", P), check_real("H", H))
        try:
            s = _undamped_spectrum(pendulum, *coefficients)
        except OverflowError:
            s = None
        if s is None:
            # the exact roots leave the double range: the first-order matrix's eigenvalues
            # there are round-off (an outside audit: at P = 1e308 load units they gave the
            # slow pair as +-3.1e145 instead of +-7e-155, and a positive real part where
            # regime() said stable)
            raise ParameterError(f"the loads P = {P!r}, H = {H!r} N put the squared "
                                 f"eigenvalues s^2 beyond the double range (load unit "
                                 f"k2/l1 = {pendulum.load_unit:.3g} N)")
        return s, coefficients
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            s = state_eigenvalues(pendulum.mass_matrix(), K, pendulum.viscosity_matrix())
    except np.linalg.LinAlgError:
        s = np.full(4, np.nan)
    if not np.all(np.isfinite(s)):
        raise ParameterError(f"the loads P = {P!r}, H = {H!r} N overflow the first-order "
                             f"matrix (load unit k2/l1 = {pendulum.load_unit:.3g} N)")
    if coefficients is None:  # damped: checked against the exact characteristic polynomial
        m = _exact_dimensionless(pendulum)
        s = _damped_spectrum(pendulum, s, characteristic_polynomial(
            m.M, m.C, _exact_loads(pendulum, m, check_real("P", P), check_real("H", H))))
    return s, coefficients


def _finite_stiffness(pendulum: ZieglerPendulum, P: float, H: float) -> NDArray:
    """``K + G(P, H)`` of eqs. (11), (26), refused (naming the loads) if it overflowed."""
    with np.errstate(over="ignore", invalid="ignore"):
        K = pendulum.stiffness_matrix() + pendulum.geometric_matrix(P, H)
    if not np.all(np.isfinite(K)):
        raise ParameterError(f"the loads P = {P!r}, H = {H!r} overflow the stiffness matrix "
                             f"(its scale is k2/l1 = {pendulum.load_unit:.3g} N)")
    return K


def regime(pendulum: ZieglerPendulum, P: float = 0.0, H: float = 0.0) -> Regime:
    """Stable, flutter or divergence at the loads ``P``, ``H`` [N].

    Undamped: from the exact biquadratic ``det(M s^2 + K)`` (:func:`_undamped_regime`; the
    eigenvalues called a pendulum in divergence stable, 4 of 400 random pendulums in range at
    1.1 H_cr, an outside audit). With hinge viscosity: from the exact Routh and Sturm root
    counts of the characteristic polynomial (exact fractions of the parameters and of the
    loads in units of k2/l1, which are rounded once,
    :func:`~.polynomial.regime_from_coefficients`). Why: a growth rate of order viscosity x
    load distance is below what the eigenvalues resolve at small viscosity (an outside audit:
    c = 1e-8 at P = 1.6 K/L, between the damped flutter load 4/3 and 2, max Re s = 1.3e-9 was
    read as stable); the exact counts resolve any growth rate. Exactly on a critical load (a
    root exactly on the imaginary axis, e.g. s = 0 at H_cr) the counts give no verdict and
    the eigenvalues decide (undamped too). A damped pendulum outside the model's numerical range
    is refused (:class:`ParameterError`), as its critical loads are."""
    check_pendulum(pendulum)
    P = check_real("P", P)
    H = check_real("H", H)
    if not is_damped(pendulum):
        s, coefficients = _spectrum(pendulum, P, H)  # (with the checks of the loads)
        verdict = _undamped_regime(*coefficients)
        return verdict if verdict is not None else classify(s)  # on a boundary: as before
    s = spectrum(pendulum, P, H)  # the same checks of the loads (finite matrices)
    m = _exact_dimensionless(pendulum)
    try:
        return regime_from_coefficients(
            characteristic_polynomial(m.M, m.C, _exact_loads(pendulum, m, P, H)))
    except ConvergenceError:  # a root exactly on the imaginary axis: a critical load
        return classify(s)


#: The largest error of the exponents ``s t`` the linear response accepts (the eigenvalues of
#: its rounded first-order matrix against the exact spectrum, times the longest time).
LINEAR_RESPONSE_EXPONENT_ERROR = 1e-6


def linear_response(pendulum: ZieglerPendulum, P: float, H: float, state0: ArrayLike,
                    times: ArrayLike) -> NDArray:
    """Exact solution of the linear eqs. (11) + (26) at the given instants.

    ``x(t) = expm(A t) x0`` with the first-order matrix ``A``: no time stepping, so the drawn
    configurations carry no integration error.

    Parameters
    ----------
    state0 : array_like, shape (4,)
        ``[alpha1, alpha2, alpha1_dot, alpha2_dot]`` at t = 0 [rad, rad/s].
    times : array_like, shape (n,)
        Instants [s].

    Returns
    -------
    ndarray, shape (n, 4)
    """
    check_pendulum(pendulum)
    P = check_real("P", P)
    H = check_real("H", H)
    x0 = check_finite_array("state0", state0, (4,), "4 finite numbers [a1, a2, a1_dot, a2_dot]")
    t = np.atleast_1d(check_finite_reals("times", times))  # real and finite
    if t.ndim != 1:
        raise ParameterError(f"times must be a 1-D array of finite instants [s], got shape "
                             f"{t.shape}")
    A = first_order_matrix(pendulum.mass_matrix(), _finite_stiffness(pendulum, P, H),
                           pendulum.viscosity_matrix())
    with np.errstate(over="ignore", invalid="ignore"):
        x = np.array([sla.expm(A * ti) @ x0 for ti in t])
    if not np.all(np.isfinite(x)):
        # exp(s t) beyond the double range (an outside audit: t = 1e300 returned all NaN)
        bad = t[~np.all(np.isfinite(x), axis=-1)]
        raise ParameterError(f"times: the linear response overflows the double range at "
                             f"t = {bad[0]:.3g} s (growth rate max Re s = "
                             f"{np.linalg.eigvals(A).real.max():.3g} 1/s)")
    exact = None if is_damped(pendulum) else \
        _undamped_spectrum(pendulum, *_undamped_biquadratic(pendulum, P, H))
    if exact is not None and t.size:
        # expm(A t) grows as the eigenvalues of the rounded A do: refused where they miss the
        # exact spectrum by more than 1e-6 over the times asked (an outside audit: a pendulum
        # with a spectrum spanning 1e10 grew at 1.2e-3 1/s instead of 3.8e-4)
        # (beyond the eigensolver's own error: 1e3 eps max|s|, and sqrt(eps) |s| at a
        # coalescence, where a Jordan block splits but expm does not)
        rounded = np.linalg.eigvals(A)
        scale = float(np.max(np.abs(exact)))
        eps = np.finfo(float).eps
        misses = [float(np.min(np.abs(rounded - z))) for z in exact]
        beyond = [m for m, z in zip(misses, exact, strict=True)
                  if m > 1e3 * eps * scale + 1e2 * math.sqrt(eps) * abs(z)]
        miss = max(beyond, default=0.0)
        if miss * float(np.max(np.abs(t))) > LINEAR_RESPONSE_EXPONENT_ERROR:
            raise ConvergenceError(
                f"the linear response of this pendulum is beyond double precision: the "
                f"eigenvalues of its first-order matrix miss the exact spectrum by {miss:.3g} "
                f"1/s, an error of {miss * float(np.max(np.abs(t))):.3g} in exp(s t) at "
                f"t = {float(np.max(np.abs(t))):.3g} s (its spectrum spans "
                f"{np.max(np.abs(exact)) / max(np.min(np.abs(exact)), 1e-300):.3g})")
    return x


def flutter_load_multiprecision(pendulum: ZieglerPendulum, dps: int = 50) -> Any:
    """Undamped flutter load [N] in ``dps``-digit arithmetic (an ``mpmath.mpf``): the smaller
    positive root of the discriminant of det(K + P F - Omega^2 M) in Omega^2, a quadratic in P
    (eq. 34), from the model's matrices of eq. (11) (exact in binary; no closed form of ours is
    used). The reference of the stress tests and the pendulum's work-precision scene."""
    import mpmath as mp

    # Fewer digits than a double's and the reference is no reference (an outside audit: dps 0
    # returned P_div for P_flu).
    dps = check_integer("dps", dps, 20, 10_000)
    with mp.workdps(dps):
        M = mp.matrix(pendulum.mass_matrix().tolist())
        K0 = mp.matrix(pendulum.stiffness_matrix().tolist())
        F = mp.matrix(pendulum.follower_load_matrix().tolist())

        def disc(P):
            K = K0 + P * F
            # det(K - x M) = a x^2 - b x + c
            a = mp.det(M)
            b = K[0, 0] * M[1, 1] + K[1, 1] * M[0, 0] - K[0, 1] * M[1, 0] - K[1, 0] * M[0, 1]
            c = mp.det(K)
            return b**2 - 4 * a * c

        # The discriminant is a quadratic in P: three values fix it exactly.
        d0, d1, d2 = disc(mp.mpf(0)), disc(mp.mpf(1)), disc(mp.mpf(2))
        A2 = (d2 - 2 * d1 + d0) / 2
        A1 = d1 - d0 - A2
        root = mp.sqrt(A1**2 - 4 * A2 * d0)
        roots = sorted([(-A1 - root) / (2 * A2), (-A1 + root) / (2 * A2)])
        return min(r for r in roots if r > 0)
