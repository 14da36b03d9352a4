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
from enum import StrEnum

import numpy as np
import scipy.linalg as sla
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, minimize_scalar

from flutterfriction.errors import ConvergenceError

Matrix = NDArray[np.float64]


class Regime(StrEnum):
    """Nature of the linearised motion about equilibrium (chapter §2.3)."""

    STABLE = "stable"
    FLUTTER = "flutter"
    DIVERGENCE = "divergence"


def first_order_matrix(M: ArrayLike, K: ArrayLike, C: ArrayLike | None = None) -> Matrix:
    """State matrix ``A`` of ``x' = A x``, ``x = [q, q']``, for ``M q'' + C q' + K q = 0``."""
    M = np.asarray(M, dtype=float)
    K = np.asarray(K, dtype=float)
    n = M.shape[0]
    C = np.zeros((n, n)) if C is None else np.asarray(C, dtype=float)
    return np.block([[np.zeros((n, n)), np.eye(n)],
                     [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])


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
    s = np.asarray(s, dtype=complex)
    scale = float(np.max(np.abs(s))) if s.size else 0.0
    tol = rtol * np.abs(s) + 1000 * np.finfo(float).eps * scale
    unstable = s.real > tol
    if not np.any(unstable):
        return Regime.STABLE
    if np.any(np.abs(s.imag[unstable]) > tol[unstable]):
        return Regime.FLUTTER
    return Regime.DIVERGENCE


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
    Linv = _cholesky_reduction(np.asarray(M, dtype=float))
    A0 = Linv @ np.asarray(K0, dtype=float) @ Linv.T
    A1 = Linv @ np.asarray(K1, dtype=float) @ Linv.T
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


def _refine_roots(f: Callable[[float], float], grid: NDArray, values: NDArray) -> list[float]:
    """Roots of ``f`` from samples: every sign change is refined with Brent's method, and every
    sampled local minimum that stays positive is minimised on its bracket, so that a pair of
    roots closer than the sampling step (a narrow flutter interval) is found too."""
    roots = [float(x) for x, v in zip(grid, values, strict=True) if v == 0.0]
    for i in range(len(grid) - 1):
        if values[i] * values[i + 1] < 0.0:
            roots.append(_brent(f, grid[i], grid[i + 1]))
    for i in range(1, len(grid) - 1):
        v = values[i - 1:i + 2]
        if v.min() > 0.0 and v[1] <= v[0] and v[1] <= v[2]:
            lo, hi = grid[i - 1], grid[i + 1]
            res = minimize_scalar(f, bounds=(lo, hi), method="bounded",
                                  options={"xatol": 4 * np.finfo(float).eps * abs(hi)})
            if res.fun < 0.0:
                roots += [_brent(f, lo, res.x), _brent(f, res.x, hi)]
    return sorted(roots)


def coalescence_loads(K0: ArrayLike, K1: ArrayLike, M: ArrayLike, load_max: float,
                      n_scan: int = 2048) -> list[float]:
    """Loads in ``[0, load_max]`` where two eigenvalues of ``(K0 + p K1, M)`` coincide.

    For a follower load these are the flutter load (a pair of real ``Omega^2`` merges and leaves
    the real axis) and the divergence load (the complex pair returns to the real axis, negative).
    Sign changes of :func:`discriminant` on a uniform scan are refined to machine precision with
    Brent's method; positive local minima of the samples are minimised to catch two coalescences
    closer than the scan step. Callers that know how many to expect (the pendulum: two) check
    the count.
    """
    grid = np.linspace(0.0, float(load_max), int(n_scan) + 1)
    values = discriminant(pencil_eigenvalues(K0, K1, M, grid))

    def f(p: float) -> float:
        return float(discriminant(pencil_eigenvalues(K0, K1, M, [p]))[0])

    return _refine_roots(f, grid, values)


def static_bifurcation_loads(K0: ArrayLike, K1: ArrayLike) -> NDArray:
    """Loads ``p > 0`` with ``det(K0 + p K1) = 0`` (quasi-static bifurcation), ascending.

    Solved as the generalised eigenproblem ``K0 a = p (-K1) a``; symmetric-definite when
    ``-K1`` is positive definite (dead loads), general otherwise.
    """
    K0 = np.asarray(K0, dtype=float)
    B = -np.asarray(K1, dtype=float)
    if np.allclose(B, B.T) and np.allclose(K0, K0.T) and np.all(np.linalg.eigvalsh(B) > 0):
        p = sla.eigh(K0, B, eigvals_only=True)
    else:
        w = sla.eigvals(K0, B)
        w = w[np.isfinite(w)]
        p = w[np.abs(w.imag) <= 1e-12 * np.maximum(1.0, np.abs(w))].real
    return np.sort(p[p > 0])
