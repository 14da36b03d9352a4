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


def _norms(x: NDArray) -> NDArray:
    """The 2-norms of ``x``'s columns, scaled so that neither 1e300 nor 1e-300 over- or
    underflows (``np.linalg.norm`` squares its entries)."""
    scale = np.max(np.abs(x), axis=0)
    safe = np.where(scale > 0, scale, 1.0)
    return scale * np.sqrt(np.sum((x / safe) ** 2, axis=0))


def integrate_vectorised(f: Callable[[NDArray], NDArray], a: float, b: float, *,
                         epsrel: float = 1e-10, epsabs: float = 0.0, panels: int = 64,
                         max_passes: int = 40, max_panels: int = 4000) -> tuple[NDArray, float]:
    """``int_a^b f(t) dt`` for ``f(t) -> (k, m)`` evaluated at ``m`` abscissae per call.

    Globally adaptive bisection: each pass integrates every open panel's two halves by
    10-point Gauss–Legendre rules and takes ``|halves - whole|`` (the 2-norm over the ``k``
    components) as the error of the whole panel's value, an overestimate of the halves' error
    by orders of magnitude on a smooth panel. The integral is accepted when the closed and
    open panels' bounds add up to at most ``max(epsabs, epsrel |I|)``; otherwise a panel is
    closed when its bound fits its share of half that tolerance (in proportion to its width),
    or, smallest bounds first, the other half (a sharp peak is refined until its absolute
    error is small, not in proportion to its width), and the rest are split.
    Returns the integral (k,) and the sum of the bounds. Raises
    :class:`~flutterfriction.errors.ConvergenceError` if the integrand is not finite, if
    panels are still open after ``max_passes`` bisections (a singular or discontinuous
    integrand) or more than ``max_panels`` are open at once (a tolerance below the
    integrand's round-off, which no bisection reaches: without the bound their number doubles
    every pass). Limitation, as for any quadrature from samples: a feature narrower than the
    first sampling (64 panels of 10 nodes) that no node sees is missed (a spike of width 1e-5
    of the interval returns the background; scipy's ``quad_vec`` misses one of width 1e-3).
    """
    for name, value in (("a", a), ("b", b), ("epsrel", epsrel), ("epsabs", epsabs)):
        if not np.isfinite(value):
            raise ParameterError(f"{name} must be finite, got {value!r}")
    if not (b > a and np.isfinite(b - a)):
        raise ParameterError(f"the interval must be finite with b > a, got [{a}, {b}]")
    if not (epsrel >= 0 and epsabs >= 0 and (epsrel > 0 or epsabs > 0)):
        raise ParameterError(f"epsrel and epsabs must be >= 0, one of them > 0, got "
                             f"{epsrel!r}, {epsabs!r}")
    for name, value, low in (("panels", panels, 1), ("max_passes", max_passes, 1),
                             ("max_panels", max_panels, 1)):
        if isinstance(value, bool) or not isinstance(value, int) or value < low:
            raise ParameterError(f"{name} must be an integer >= {low}, got {value!r}")
    edges = np.linspace(a, b, panels + 1)
    lo, hi = edges[:-1], edges[1:]
    whole = _panel_integrals(f, lo, hi)
    closed, closed_error = np.zeros(whole.shape[0]), 0.0
    budget: float | None = None
    shared_error = peak_error = 0.0  # the closed panels' bounds, by how they closed
    for _ in range(max_passes):
        mid = 0.5 * (lo + hi)
        halves = _panel_integrals(f, np.concatenate([lo, mid]), np.concatenate([mid, hi]))
        if not (np.all(np.isfinite(halves)) and np.all(np.isfinite(whole))):
            raise ConvergenceError(f"adaptive quadrature on [{a:.6g}, {b:.6g}]: the integrand "
                                   f"or its panel integrals are not finite")
        left, right = halves[:, : lo.size], halves[:, lo.size:]
        finer = left + right
        error = _norms(finer - whole)
        total = closed + finer.sum(axis=1)
        tol = max(epsabs, epsrel * float(_norms(total[:, None])[0]))
        if closed_error + error.sum() <= tol:
            return total, closed_error + float(error.sum())
        # close the panels of smallest bound within half the smallest tolerance estimated so
        # far (an early pass can overestimate |I| many times over: a closed panel's bound must
        # fit the final tolerance), split the others
        budget = tol if budget is None else min(budget, tol)
        # a panel closes on its share of half the budget, in proportion to its width (the
        # shares add up to at most half), or, smallest bounds first, within the other half
        # (a sharp peak's narrow panels, whose shares would ask for less than round-off)
        done = error <= 0.5 * budget * (hi - lo) / (b - a)
        shared_error += float(error[done].sum())
        order = np.flatnonzero(~done)[np.argsort(error[~done], kind="stable")]
        fits = peak_error + np.cumsum(error[order]) <= 0.5 * budget
        done[order[fits]] = True
        peak_error += float(error[order[fits]].sum())
        closed_error = shared_error + peak_error
        closed = closed + finer[:, done].sum(axis=1)
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
