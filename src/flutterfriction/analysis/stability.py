"""Linear stability of ``M q'' + C q' + (K0 + p K1) q = 0``, for any number of degrees of freedom.

Conventions follow the chapter: with ``q = a exp(-i Omega t)`` (eq. 12) the undamped problem is
the pencil ``(K0 + p K1 - Omega^2 M) a = 0`` (eq. 14); the eigenvalues of the first-order form
are ``s = -i Omega`` (the chapter's ``Omega~``, eq. 30ff), so instability means ``Re s > 0``.

Critical loads are computed as the exact points where the spectrum changes nature:

- **coalescence** (flutter onset, end of flutter = divergence onset for follower loads): two
  eigenvalues ``mu = Omega^2`` of the pencil become equal. We follow the sign of the
  discriminant ``D(p) = prod_{i<j} (mu_i - mu_j)^2``, a real analytic function of ``p`` that
  crosses zero linearly at a simple coalescence, and solve ``D(p) = 0`` with Brent's method.
  A threshold on ``Re s`` would be biased: near coalescence ``Re s ~ sqrt(p - p_c)``.
- **static bifurcation** (dead loads): ``det(K0 + p K1) = 0``, solved as the generalised
  eigenproblem ``K0 a = p (-K1) a``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.linalg as sla
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, minimize_scalar

from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_integer,
    check_positive,
    check_real,
)
from flutterfriction.results import Regime  # noqa: F401  (re-exported)

Matrix = NDArray[np.float64]


def square_matrices(**named: object) -> list[Matrix]:
    """Each named matrix as a float array, all finite, real and square of one size ``n >= 1``
    (the first one's), or a :class:`ParameterError` naming the first that is not (an outside
    review: NaN, 1-d, None or mismatched matrices ended in numpy's LinAlgError, ValueError or
    IndexError, and strings or booleans were read as numbers)."""
    out: list[Matrix] = []
    n = None
    for name, value in named.items():
        if n is None:
            shape = getattr(value, "shape", None)
            if shape is None:
                try:
                    shape = np.shape(value)
                except (ValueError, TypeError):  # ragged nesting
                    shape = None
            if shape is None or len(shape) != 2 or shape[0] != shape[1] or shape[0] < 1:
                raise ParameterError(f"{name} must be a square matrix (n x n, n >= 1) of "
                                     f"finite real numbers, got shape {shape}")
            n = int(shape[0])
        out.append(check_finite_array(name, value, (n, n),
                                      f"a finite real {n}x{n} matrix (the size of "
                                      f"{next(iter(named))})"))
    return out


def first_order_matrix(M: ArrayLike, K: ArrayLike, C: ArrayLike | None = None) -> Matrix:
    """State matrix ``A`` of ``x' = A x``, ``x = [q, q']``, for ``M q'' + C q' + K q = 0``."""
    if C is None:
        M, K = square_matrices(M=M, K=K)
        C = np.zeros_like(M)
    else:
        M, K, C = square_matrices(M=M, K=K, C=C)
    n = M.shape[0]
    try:
        MK, MC = np.linalg.solve(M, K), np.linalg.solve(M, C)
    except np.linalg.LinAlgError:
        raise ParameterError(f"M must be a nonsingular matrix, got {M.tolist()}") from None
    return np.block([[np.zeros((n, n)), np.eye(n)], [-MK, -MC]])


def state_eigenvalues(M: ArrayLike, K: ArrayLike, C: ArrayLike | None = None) -> NDArray:
    """Eigenvalues ``s = -i Omega`` of the first-order form, sorted by real part, descending."""
    s = np.linalg.eigvals(first_order_matrix(M, K, C))
    return s[np.lexsort((-s.imag, -s.real))]


def classify(s: ArrayLike, rtol: float = 1e-8) -> Regime:
    """Classify a spectrum ``s`` of the first-order form (chapter §2.3, list after eq. 37).

    Stable when no eigenvalue has ``Re s > tol``; otherwise flutter when an unstable eigenvalue
    has ``|Im s| > tol`` (an oscillation of growing amplitude) and divergence when the unstable
    eigenvalues are real (exponential growth). The tolerance is per eigenvalue,
    ``tol_i = rtol |s_i| + 1000 eps max|s|``: it absorbs round-off (undamped stable spectra have
    ``|Re s| ~ 1e-16 max|s|``) without letting one stiff, strongly damped mode (e.g. a fine FE
    mesh with Kelvin–Voigt damping, ``|s| ~ 1e7``) blur the low ones. Critical loads are never
    found with it, see :func:`coalescence_loads`.
    """
    rtol = check_real("rtol", rtol)
    if not 0.0 <= rtol < 1.0:  # (an outside review: NaN, 1e9 or -1 gave verdicts)
        raise ParameterError(f"rtol must be in [0, 1), got {rtol!r}")
    s = np.asarray(s, dtype=complex)
    if not np.all(np.isfinite(s)):  # (an outside audit: [nan, -1] was "stable")
        raise ParameterError(f"s must be finite eigenvalues, got {s.tolist()}")
    scale = float(np.max(np.abs(s))) if s.size else 0.0
    tol = rtol * np.abs(s) + 1000 * np.finfo(float).eps * scale
    unstable = s.real > tol
    if not np.any(unstable):
        return Regime.STABLE
    if np.any(np.abs(s.imag[unstable]) > tol[unstable]):
        return Regime.FLUTTER
    return Regime.DIVERGENCE


def classify_rows(s: ArrayLike, rtol: float = 1e-8) -> list[Regime]:
    """:func:`classify` of each row of ``s`` (spectra, shape (m, n)), vectorised: the same
    comparisons elementwise, so the same verdicts (a scan's grid of spectra classified one
    call per load cost more than computing them). Rows that are empty or not finite go
    through :func:`classify`, which refuses them with its own message."""
    s = np.asarray(s, dtype=complex)
    if s.ndim != 2 or s.shape[1] == 0 or not np.all(np.isfinite(s)):
        return [classify(row, rtol) for row in s]
    rtol = check_real("rtol", rtol)
    if not 0.0 <= rtol < 1.0:
        raise ParameterError(f"rtol must be in [0, 1), got {rtol!r}")
    modulus = np.abs(s)
    scale = np.max(modulus, axis=1, keepdims=True)
    tol = rtol * modulus + 1000 * np.finfo(float).eps * scale
    unstable = s.real > tol
    flutter = np.any(unstable & (np.abs(s.imag) > tol), axis=1)
    return [Regime.FLUTTER if f else Regime.DIVERGENCE if u else Regime.STABLE
            for u, f in zip(np.any(unstable, axis=1).tolist(), flutter.tolist(), strict=True)]


def _cholesky_reduction(M: Matrix) -> Matrix:
    """``L^{-1}`` with ``M = L L^T``: the pencil (K, M) becomes the matrix ``L^{-1} K L^{-T}``."""
    L = np.linalg.cholesky(M)
    return sla.solve_triangular(L, np.eye(M.shape[0]), lower=True)


def pencil_eigenvalues(K0: ArrayLike, K1: ArrayLike, M: ArrayLike, loads: ArrayLike) -> NDArray:
    """Eigenvalues ``mu = Omega^2`` of ``(K0 + p K1, M)`` for each load ``p`` (eq. 14, 16).

    The pencil is reduced with the Cholesky factor of ``M`` (the chapter's ``M^{-1/2}`` step,
    eq. 16, with ``L`` in place of ``M^{1/2}``) and solved for all loads in one batched call.

    Returns
    -------
    ndarray, shape (len(loads), n), complex
        Sorted by real part, then imaginary part.
    """
    return _reduced_eigenvalues(*_reduce(K0, K1, M), loads)


def _reduce(K0: ArrayLike, K1: ArrayLike, M: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
    """``(L^-1, L^-1 K0 L^-T, L^-1 K1 L^-T)`` with ``M = L L^T``; the matrices checked."""
    M, K0, K1 = square_matrices(M=M, K0=K0, K1=K1)
    if np.max(np.abs(M - M.T)) > 1e-12 * np.max(np.abs(M)):
        raise ParameterError(f"M must be a symmetric positive definite mass matrix, got "
                             f"{M.tolist()}")
    try:
        Linv = _cholesky_reduction(M)
    except np.linalg.LinAlgError:
        raise ParameterError(f"M must be a symmetric positive definite mass matrix, got "
                             f"{M.tolist()}") from None
    return Linv, Linv @ K0 @ Linv.T, Linv @ K1 @ Linv.T


def _reduced_eigenvalues(Linv: Matrix, A0: Matrix, A1: Matrix, loads: ArrayLike) -> NDArray:
    """Eigenvalues of ``A0 + p A1`` for each load, sorted as :func:`pencil_eigenvalues`."""
    p = np.atleast_1d(np.asarray(loads, dtype=float))
    mu = np.linalg.eigvals(A0[None] + p[:, None, None] * A1[None])
    order = np.lexsort((mu.imag, mu.real), axis=-1)
    return np.take_along_axis(mu, order, axis=-1)


def discriminant(mu: NDArray) -> NDArray:
    """Normalised discriminant ``prod_{i<j} (mu_i - mu_j)^2 / scale^(n(n-1))`` along the last axis.

    Real for the spectrum of a real matrix (complex-conjugate factors pair up); negative when an
    odd number of complex pairs is present. Normalising by the spectral scale keeps it O(1).
    """
    mu = np.asarray(mu, dtype=complex)
    n = mu.shape[-1]
    scale = np.max(np.abs(mu), axis=-1)
    scale = np.where(scale > 0, scale, 1.0)
    out = np.ones(mu.shape[:-1], dtype=complex)
    for i in range(n):
        for j in range(i + 1, n):
            out *= ((mu[..., i] - mu[..., j]) / scale) ** 2
    return out.real


def _brent(f: Callable[[float], float], a: float, b: float) -> float:
    xtol = 4 * np.finfo(float).eps * max(abs(a), abs(b), np.finfo(float).tiny)
    root, info = brentq(f, a, b, xtol=xtol, full_output=True, disp=False)
    if not info.converged:
        raise ConvergenceError(f"Brent's method did not converge in [{a}, {b}]")
    return float(root)


#: Round-off floor of the normalised discriminant, in units of ``eps (N(p) / scale)^2`` with
#: ``N(p) = || |L^-1| |K0 + p K1| |L^-T| ||_F`` (:func:`discriminant_noise_floor`). Where the
#: digits come from: a pair's factor ``((mu_i - mu_j)/scale)^2`` is ``(tr^2 - 4 det)/scale^2``
#: of the pair's 2x2 block; forming ``A = L^-1 K L^-T`` (Cholesky factor ``L`` of ``M``) errs
#: componentwise by about ``eps |L^-1| |K| |L^-T|`` and a backward-stable eigensolver adds a
#: few ``eps ||A||``, so the factor errs by a modest multiple of ``eps N^2``. (``||A||`` alone
#: under-estimated the error 12000-fold at m3/m2 = 1e6, where M is ill-conditioned;
#: ``||L^-1||^2 ||K||`` over-estimated it so much at m1/m2 = 1e6 that a resolved flutter load
#: was refused.) Measured against 40-digit mpmath on 257 loads in three windows each (list 47
#: with one of k1/k2, m1/m2, l1/l2, m3/m2 at 1e-6 or 1e6, k1/k2 = 1e-30, m3 = 0 with
#: d/l1 = 1e-4): at most 38 units (l1/l2 = 1e-6, loads below 10 k2/l1), at most 3.1 elsewhere;
#: 1000 leaves a margin of 26 (``tests/test_extremes_ziegler.py::test_noise_floor_covers_
#: roundoff``).
NOISE_FLOOR_FACTOR = 1000.0
#: With a noise floor, at most this many sampled dips of the discriminant are minimised per
#: scan (deepest first): the pendulum has one flutter interval, and 4 bounds the cost of a scan
#: at ~4 bounded minimisations even on a plateau of round-off.
MAX_MINIMISED_DIPS = 4


def discriminant_noise_floor(Linv: ArrayLike, K0: ArrayLike, K1: ArrayLike, loads: ArrayLike,
                             mu: NDArray) -> NDArray:
    """Round-off level of :func:`discriminant` for the pencil ``(K0 + p K1, M)`` reduced with
    ``Linv = L^-1`` (``M = L L^T``), spectra ``mu`` (shape (m, n)):
    ``NOISE_FLOOR_FACTOR eps (N(p) / scale)^2 4^(pairs - 1)``, ``N(p) = || |L^-1| |K0 + p K1|
    |L^-T| ||_F`` (the other pairs' factors are at most 4 each). A sampled value below it
    carries no sign information."""
    K0 = np.asarray(K0, dtype=float)
    K1 = np.asarray(K1, dtype=float)
    aL = np.abs(np.asarray(Linv, dtype=float))
    p = np.atleast_1d(np.asarray(loads, dtype=float))
    n = K0.shape[0]
    K = np.abs(K0[None] + p[:, None, None] * K1[None])
    norms = np.linalg.norm(aL[None] @ K @ aL.T[None], axis=(1, 2))
    scale = np.max(np.abs(mu), axis=-1)
    scale = np.where(scale > 0, scale, 1.0)
    pairs = n * (n - 1) // 2
    return NOISE_FLOOR_FACTOR * np.finfo(float).eps * (norms / scale) ** 2 * 4.0 ** (pairs - 1)


def refine_roots(f: Callable[[float], float], grid: NDArray, values: NDArray,
                  floor: NDArray | None = None,
                  floor_at: Callable[[float], float] | None = None) -> list[float]:
    """Roots of ``f`` from samples: every sign change is refined with Brent's method, and every
    sampled local minimum that stays positive is minimised on its bracket, so that a pair of
    roots closer than the sampling step (a narrow flutter interval) is found too.

    With ``floor`` (the round-off level of each sample, e.g. :func:`discriminant_noise_floor`)
    samples are judged against it: a sign change or a local minimum with every sample at or
    below the floor is round-off, not a root, and is refused (:class:`ConvergenceError`)
    instead of being minimised (minimising noise finds noise, and costs a minimisation per
    local minimum); of the minima above the floor only the :data:`MAX_MINIMISED_DIPS` deepest
    are minimised, and a negative minimum within the floor there (``floor_at``, the floor at
    any load) is refused too: at a double root the normalised discriminant is pure noise.
    Without ``floor`` the behaviour is the historical one (used by the rod code)."""
    values = np.asarray(values, dtype=float)
    fl = np.zeros_like(values) if floor is None else np.asarray(floor, dtype=float)

    def noise(lo: int, hi: int) -> None:
        if floor is not None and np.all(np.abs(values[lo:hi + 1]) <= fl[lo:hi + 1]):
            raise ConvergenceError(
                f"the discriminant is at its round-off floor for loads {grid[lo]:.6g}.."
                f"{grid[hi]:.6g}: a coalescence there is not resolved in double precision")

    if len(grid) != len(values):
        raise ValueError(f"grid and values differ in length ({len(grid)}, {len(values)})")
    roots = []
    # The samples' tests are vectorised (the same comparisons, in the same order of samples:
    # a Python loop over the grid was half the cost of a pendulum's critical loads).
    for i in np.flatnonzero(values == 0.0):
        # an exact zero is a root unless its neighbours are round-off too
        noise(max(i - 1, 0), min(i + 1, len(grid) - 1))
        roots.append(float(grid[i]))
    for i in np.flatnonzero(values[:-1] * values[1:] < 0.0):
        noise(i, i + 1)
        roots.append(_brent(f, grid[i], grid[i + 1]))
    candidates = []
    last = len(grid) - 1
    # the ends of the scan too, one-sided: a pair of roots within the first or the last
    # step leaves the end sample a minimum (an outside review: load_max = 1e5 put the
    # pendulum's flutter interval [2.09, 4.91] inside the first step of 49, and both loads
    # were missed, silently)
    idx = np.arange(len(grid))
    below, above = values[np.maximum(idx - 1, 0)], values[np.minimum(idx + 1, last)]
    with np.errstate(invalid="ignore"):
        dips = ((np.minimum(np.minimum(below, values), above) > 0.0)
                & (values <= below) & (values <= above))
    for i in np.flatnonzero(dips) if last > 0 else ():
        lo, hi = max(i - 1, 0), min(i + 1, last)
        depth = min(values[lo], values[hi]) - values[i]
        if floor is not None:
            if values[i] <= fl[i]:
                noise(lo, hi)
                continue  # a neighbour is above the floor: a touch at round-off level
            # A dip no deeper than round-off, two samples out too, is a plateau: the
            # scan's loads load_max 2^-k crowd where the discriminant is flat to the last
            # bits (list 47: four minimisations a window at loads ~1e-16, 6x the scan's
            # cost). Two out, because a narrow interval centred between samples i and
            # i + 1 leaves them equal, its dip seen only against i - 1 and i + 2.
            lo2, hi2 = max(i - 2, 0), min(i + 2, last)
            depth = max(depth, min(values[lo2], values[hi2]) - values[i])
            if depth <= np.max(fl[lo2:hi2 + 1]):
                continue
        candidates.append((depth, i))
    if floor is not None:
        # A round-off plateau has a local minimum at almost every sample (the historical hang:
        # hundreds of minimisations per scan). Only the deepest few dips are minimised; a
        # narrow flutter interval shows as the deepest dip of its scan.
        candidates = sorted(candidates, reverse=True)[:MAX_MINIMISED_DIPS]
    # A smooth dip is located in a few dozen bounded-Brent steps; 100 bounds the cost of a
    # noisy one (scipy's default allows 500). Only the sign of the minimum found is used.
    options = {"xatol": 4 * np.finfo(float).eps, "maxiter": 100 if floor is not None else 500}
    for _, i in candidates:
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, last)]
        res = minimize_scalar(f, bounds=(lo, hi), method="bounded",
                              options={**options, "xatol": options["xatol"] * abs(hi)})
        if res.fun < 0.0:
            level = max(np.max(fl[max(i - 1, 0):i + 2]),
                        0.0 if floor_at is None else floor_at(float(res.x)))
            if floor is not None and -res.fun <= level:
                raise ConvergenceError(
                    f"the discriminant dips to its round-off floor near load {res.x:.10g} "
                    f"(in the matrices' load unit) "
                    f"(minimum {res.fun:.3g}, floor {level:.3g}): a flutter interval that "
                    f"narrow is not resolved in double precision")
            roots += [_brent(f, lo, res.x), _brent(f, res.x, hi)]
    return sorted(roots)


def coalescence_loads(K0: ArrayLike, K1: ArrayLike, M: ArrayLike, load_max: float,
                      n_scan: int = 2048, noise_floor: bool = False) -> list[float]:
    """Loads in ``[0, load_max]`` where two eigenvalues of ``(K0 + p K1, M)`` coincide.

    For a follower load these are the flutter load (a pair of real ``Omega^2`` merges and leaves
    the real axis) and the divergence load (the complex pair returns to the real axis, negative).
    Sign changes of :func:`discriminant` on a uniform scan are refined to machine precision with
    Brent's method; positive local minima of the samples are minimised to catch two coalescences
    closer than the scan step. The scan adds the loads ``load_max 2^-k`` (k = 1..59), so a
    coalescence far below the uniform step is bracketed whatever ``load_max``. Callers that
    know how many to expect (the pendulum: two) check the count. With ``noise_floor`` the
    samples are judged against the discriminant's round-off level
    (:func:`discriminant_noise_floor`): round-off is refused, not minimised.
    """
    load_max = check_positive("load_max", load_max)
    n_scan = check_integer("n_scan", n_scan, 2, 10**6)
    # uniform, plus load_max 2^-k towards 0: coalescences at loads far below the uniform
    # step are bracketed at any scale (an outside review: the pendulum's flutter interval
    # [2.09, 4.91] was missed at load_max = 1e5 and 1e12)
    grid = np.union1d(np.linspace(0.0, load_max, n_scan + 1),
                      load_max * 2.0 ** -np.arange(1.0, 60.0))
    reduced = _reduce(K0, K1, M)  # once: the same numbers pencil_eigenvalues would form
    mu = _reduced_eigenvalues(*reduced, grid)
    values = discriminant(mu)
    floor = None
    if noise_floor:
        floor = discriminant_noise_floor(reduced[0], K0, K1, grid, mu)

    def f(p: float) -> float:
        return float(discriminant(_reduced_eigenvalues(*reduced, [p]))[0])

    def floor_at(p: float) -> float:
        mu_p = _reduced_eigenvalues(*reduced, [p])
        return float(discriminant_noise_floor(reduced[0], K0, K1, [p], mu_p)[0])

    return refine_roots(f, grid, values, floor, floor_at if noise_floor else None)


def static_bifurcation_loads(K0: ArrayLike, K1: ArrayLike) -> NDArray:
    """Loads ``p > 0`` with ``det(K0 + p K1) = 0`` (quasi-static bifurcation), ascending.

    Solved as the generalised eigenproblem ``K0 a = p (-K1) a``; symmetric-definite when
    ``-K1`` is positive definite (dead loads), general otherwise.
    """
    K0, K1 = square_matrices(K0=K0, K1=K1)
    B = -K1
    if np.allclose(B, B.T) and np.allclose(K0, K0.T) and np.all(np.linalg.eigvalsh(B) > 0):
        p = sla.eigh(K0, B, eigvals_only=True)
    else:
        w = sla.eigvals(K0, B)
        w = w[np.isfinite(w)]
        p = w[np.abs(w.imag) <= 1e-12 * np.maximum(1.0, np.abs(w))].real
    return np.sort(p[p > 0])
