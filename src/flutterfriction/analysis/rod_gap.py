"""The gap of a nearly coincident pair of roots of eq. (118) (undamped rod), for deciding
regimes where the roots themselves are ill-conditioned.

Undamped, eq. (118) depends on ``omega~`` through ``mu = omega~^2`` only, and
``G(mu) = f(p, sqrt(mu))`` is an entire function of ``mu``, real on the real axis
(:mod:`flutterfriction.models.rod`). Near a coalescence two roots ``mu1, mu2`` nearly coincide:
each is known only to ~sqrt(eps) and Newton on either jitters (:func:`flutterfriction.analysis.
rod.refine_eigenvalues` refuses), while the pair's *centre* ``m`` (the simple root of ``G'``
between them) and its *gap* ``-G(m) / (G''(m)/2)`` are well conditioned:

- for ``G = c ((mu - m)^2 - d)`` the gap is ``d = ((mu1 - mu2)/2)^2``: positive for two real
  roots, negative for a complex-conjugate pair (a flutter pair), zero at the double root;
- the gap vanishes exactly where ``G = G' = 0`` (a change of regime, the double root the
  critical-load Newton solves), so the boundaries of a window are the zeros of ``gap(p)``, a
  smooth real function of the load, found by Brent's method in one variable. At a window's
  opening ``gap(p) ~ gap_max - c (p - p*)^2``: its zeros stay simple until the window is as
  narrow as the gap's round-off allows, where the two-variable Newton on ``(p, mu)`` (whose
  Jacobian is singular at the opening) already failed ~1e-7 in tan(alpha) earlier.

The Taylor coefficients of ``G`` at ``m`` come from Cauchy's integral on a circle (the
discrete Fourier transform of ``G`` at :data:`CIRCLE_POINTS` points of radius
``CIRCLE_RTOL max(1, |m|)``): exact for an entire function up to aliasing ``~ r^N``
(negligible) and round-off ``eps max|G|`` on the circle, which bounds the gap's error
(:func:`pair_gap` returns it).

Checked against the double roots of the two-variable Newton and against an outside review's
mpmath windows (``tests/test_rod.py``).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from flutterfriction.errors import ConvergenceError, ParameterError
from flutterfriction.models.rod import RodGroups, characteristic_function

#: Points on Cauchy's circle (the FFT's length): the Taylor coefficients up to order 2 are
#: needed; aliasing brings in order 32 times r^30, far below round-off.
CIRCLE_POINTS = 32
#: Radius of Cauchy's circle relative to max(1, |m|): small keeps the round-off of the gap
#: ~eps r^2 (measured: ~2e-14 at |m| ~ 170, 2e-13 at |m| ~ 550).
CIRCLE_RTOL = 1e-2
#: The centre's Newton stops at steps below this, relative to max(1, |m|) (its steps jitter
#: at the round-off of G', ~1e-14 relative; the gap's error from the centre's is its square).
CENTRE_RTOL = 1e-10
#: A gap within this many times its round-off bound gives no verdict (its sign is noise).
GAP_NOISE_FACTOR = 1e3
_EPS = float(np.finfo(float).eps)


def _taylor(p: float, g: RodGroups, m: float, r: float, variable: str
            ) -> tuple[np.ndarray, float]:
    """Taylor coefficients ``a0, a1, a2`` of ``G`` (scaled by one constant) at ``m``, and
    their round-off, ``eps max|G|`` on the circle: ``G(mu) = f(p, sqrt(mu))`` (undamped,
    ``variable`` "mu") or ``G(omega~) = f(p, omega~)`` ("omega": real on the real axis, damped
    or not)."""
    theta = 2 * np.pi * np.arange(CIRCLE_POINTS) / CIRCLE_POINTS
    z = m + r * np.exp(1j * theta)
    w = np.sqrt(z + 0j) if variable == "mu" else z
    F, sigma = characteristic_function(p, w, g, with_exponent=True)
    # one common scale: exp(sigma - max sigma) <= 1 (F is f exp(-sigma))
    v = F * np.exp(sigma - np.max(sigma.real))
    a = (np.fft.fft(v) / CIRCLE_POINTS)[:3] / r ** np.arange(3)
    return a.real, _EPS * float(np.max(np.abs(v)))


def pair_gap(p: float, g: RodGroups, mu0: float, variable: str = "mu"
             ) -> tuple[float, float, float]:
    """Centre ``m``, gap and the gap's round-off bound of the pair of real-axis roots of eq.
    (118) nearest ``mu0`` at load ``p``: in ``mu = omega~^2`` (``variable`` "mu", the
    undamped rod) or in ``omega~`` itself ("omega": a damped rod's double real root, where a
    divergence window opens or closes).

    The centre is Newton's root of ``G'`` from ``mu0`` (``G''`` from the same Cauchy sums);
    the gap is ``-a0/a2`` there (``((mu1 - mu2)/2)^2`` for a quadratic: > 0 two real roots,
    < 0 a complex pair). Raises :class:`ConvergenceError` where ``G''`` vanishes (three
    roots together) or the centre does not converge."""
    if variable not in ("mu", "omega"):
        raise ParameterError(f"variable must be 'mu' or 'omega', got {variable!r}")
    if variable == "mu" and g.damped:
        raise ParameterError("pair_gap in mu = omega~^2 is for the undamped rod: eta and "
                             f"gamma must be 0, got {g.eta!r} and {g.gamma!r}")
    m = float(mu0)
    for _ in range(60):
        r = CIRCLE_RTOL * max(1.0, abs(m))
        if variable == "omega" and g.eta > 0 and not r < 0.5 * abs(m + 1 / g.eta):
            # eq. (113)'s pole omega~ = -1/eta: the circle must stay clear of it
            raise ConvergenceError(f"the pair near omega~ = {m:.6g} at p = {p:.10g} lies "
                                   "next to the pole omega~ = -1/eta of eq. (113)")
        a, noise = _taylor(p, g, m, r, variable)
        if not abs(a[2]) > 1e3 * noise / r**2:
            raise ConvergenceError(f"no pair of roots near {m:.6g} at p = {p:.10g} "
                                   "(G'' vanishes: three roots together, or none)")
        step = -a[1] / (2 * a[2])
        m += step
        if abs(step) <= CENTRE_RTOL * max(1.0, abs(m)):
            break
    else:
        raise ConvergenceError(f"the centre of the pair near {mu0:.6g} at p = {p:.10g} "
                               "did not converge")
    a, noise = _taylor(p, g, m, CIRCLE_RTOL * max(1.0, abs(m)), variable)
    gap = -a[0] / a[2]
    # round-off of a0 (eps max|G|) over a2; the centre's own error d adds a1 d / a2 ~ 2 d^2
    # (a1 ~ 2 a2 d), below 1e-20 m^2: negligible
    return m, float(gap), float(noise / abs(a[2]))


def gap_roots(g: RodGroups, lo: float, hi: float, mu0: float, n: int = 40,
              variable: str = "mu") -> list[tuple[float, float]]:
    """Every load in ``[lo, hi]`` where the pair of roots near ``mu0`` coalesces, with its
    double root: ``[(p, mu), ...]`` in increasing ``p``.

    The gap is sampled at ``n + 1`` loads (the centre followed from one to the next); every
    change of sign is solved by Brent's method, and every sampled extremum that approaches
    zero without crossing is optimised (bounded Brent) and split if it crosses (a window
    narrower than the sampling). Raises :class:`ConvergenceError` where a gap the answer
    depends on is within :data:`GAP_NOISE_FACTOR` times its round-off."""
    ps = np.linspace(lo, hi, n + 1)
    centres, gaps, noises = [], [], []
    m = mu0
    for p in ps:
        m, gap, noise = pair_gap(float(p), g, m, variable)
        centres.append(m)
        gaps.append(gap)
        noises.append(noise)
    gaps_a = np.array(gaps)

    def checked(gap: float, noise: float, p: float) -> float:
        if abs(gap) <= GAP_NOISE_FACTOR * noise:
            raise ConvergenceError(
                f"the pair near mu = {mu0:.6g} is within round-off of a double root at "
                f"p = {p:.10g} (gap {gap:.3g}, round-off {noise:.1g}): a window narrower "
                "than eq. (118) resolves in doubles may open or close there")
        return gap

    for k in range(n + 1):
        checked(gaps[k], noises[k], float(ps[k]))

    def gap_at(p: float, k: int) -> float:
        return pair_gap(p, g, centres[k], variable)[1]

    def root(a: float, b: float, k: int) -> tuple[float, float]:
        p = brentq(lambda x: gap_at(x, k), a, b, xtol=4 * _EPS * max(1.0, b), maxiter=200)
        return float(p), pair_gap(float(p), g, centres[k], variable)[0]

    out: list[tuple[float, float]] = []
    for k in range(n):
        a, b = float(ps[k]), float(ps[k + 1])
        if gaps_a[k] * gaps_a[k + 1] < 0:
            out.append(root(a, b, k))
            continue
        # an extremum between samples that approaches zero: optimised on its two steps
        if 0 < k and (abs(gaps_a[k]) < abs(gaps_a[k - 1]) and abs(gaps_a[k]) <= abs(
                gaps_a[k + 1])) and gaps_a[k - 1] * gaps_a[k] > 0:
            sign = math.copysign(1.0, gaps_a[k])
            res = minimize_scalar(lambda x, k=k, sign=sign: sign * gap_at(x, k),
                                  bounds=(float(ps[k - 1]), b), method="bounded",
                                  options={"xatol": 1e-10 * max(1.0, b)})
            x = float(res.x)
            m_x, gap_x, noise_x = pair_gap(x, g, centres[k], variable)
            if sign * gap_x < 0:
                if out and out[-1][0] > float(ps[k - 1]):
                    raise ConvergenceError(f"two coalescences of the pair near mu = "
                                           f"{mu0:.6g} within one sampling step at p ~ {x:.6g}")
                out += [root(float(ps[k - 1]), x, k), root(x, b, k)]
            else:
                checked(gap_x, noise_x, x)
    return sorted(out)
