"""Adaptive quadrature of a vector-valued integrand evaluated on many abscissae at once.

scipy's ``quad_vec`` calls its integrand at one abscissa at a time; where one evaluation is a
dense-output interpolation and a few small matrix products (the rod's powers over a period),
the calls' overhead is the cost. Here every pass evaluates all the abscissae it needs in one
call, so the same accuracy costs a few vectorised calls instead of ~10^5 scalar ones.
"""

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from flutterfriction.errors import ConvergenceError, ParameterError

# Gauss–Legendre nodes and weights on [-1, 1]: exact for polynomials of degree 2 * 10 - 1.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(10)
_BLOCK = 400  # abscissae per call: 16 elements then keep ~10 MB per kinematic array


def _panel_integrals(f: Callable[[NDArray], NDArray], a: NDArray, b: NDArray) -> NDArray:
    """The Gauss–Legendre value of ``f`` on every panel ``[a_i, b_i]``: shape (k, panels)."""
    half, mid = 0.5 * (b - a), 0.5 * (b + a)
    t = (mid[:, None] + half[:, None] * _NODES).ravel()  # (panels * nodes,)
    # at most _BLOCK abscissae per call: an integrand's work arrays stay small
    values = np.concatenate([np.asarray(f(t[i:i + _BLOCK]), dtype=float)
                             for i in range(0, t.size, _BLOCK)], axis=1)
    values = values.reshape(values.shape[0], a.size, _NODES.size)
    return (values @ _WEIGHTS) * half


def integrate_vectorised(f: Callable[[NDArray], NDArray], a: float, b: float, *,
                         epsrel: float = 1e-10, epsabs: float = 0.0, panels: int = 64,
                         max_passes: int = 40, max_panels: int = 4000) -> tuple[NDArray, float]:
    """``int_a^b f(t) dt`` for ``f(t) -> (k, m)`` evaluated at ``m`` abscissae per call.

    Globally adaptive bisection: each pass integrates every open panel's two halves by
    10-point Gauss–Legendre rules and takes ``|halves - whole|`` (the 2-norm over the ``k``
    components) as the error of the whole panel's value, an overestimate of the halves' error
    by orders of magnitude on a smooth panel. A panel is closed when that bound is below its
    share of the tolerance ``max(epsabs, epsrel |I|)`` (in proportion to its length, so the
    closed panels' bounds add up to at most the tolerance); the others are split. Returns the
    integral (k,) and the sum of the closed panels' bounds. Raises
    :class:`~flutterfriction.errors.ConvergenceError` if panels are still open after
    ``max_passes`` bisections (a singular or discontinuous integrand) or more than
    ``max_panels`` are open at once (a tolerance below the integrand's round-off, which no
    bisection reaches: without the bound their number doubles every pass), never a silent
    value.
    """
    if not (np.isfinite(a) and np.isfinite(b) and b > a):
        raise ParameterError(f"the interval must be finite with b > a, got [{a}, {b}]")
    edges = np.linspace(a, b, panels + 1)
    lo, hi = edges[:-1], edges[1:]
    whole = _panel_integrals(f, lo, hi)
    closed, closed_error = np.zeros(whole.shape[0]), 0.0
    for _ in range(max_passes):
        mid = 0.5 * (lo + hi)
        halves = _panel_integrals(f, np.concatenate([lo, mid]), np.concatenate([mid, hi]))
        left, right = halves[:, : lo.size], halves[:, lo.size:]
        finer = left + right
        error = np.linalg.norm(finer - whole, axis=0)
        tol = max(epsabs, epsrel * float(np.linalg.norm(closed + finer.sum(axis=1))))
        done = error <= tol * (hi - lo) / (b - a)
        closed = closed + finer[:, done].sum(axis=1)
        closed_error += float(error[done].sum())
        if done.all():
            return closed, closed_error
        keep = ~done
        lo, mid, hi = lo[keep], mid[keep], hi[keep]
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
        whole = np.concatenate([left[:, keep], right[:, keep]], axis=1)
        if lo.size > max_panels:
            break
    raise ConvergenceError(f"adaptive quadrature on [{a:.6g}, {b:.6g}]: {lo.size} panels still "
                           f"above the tolerance (epsrel {epsrel:g}) after {max_passes} "
                           f"bisections or {max_panels} open panels; the integrand is not "
                           f"smooth enough or the tolerance is below its round-off")
