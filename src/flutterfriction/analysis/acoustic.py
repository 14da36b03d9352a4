"""Analysis of the acoustic tensor (chapter §3.3–3.5): classification of a direction, the
maximum of the localization modulus over all directions, and flutter intervals found by brute
force (the independent twins of the isotropic closed forms in :mod:`..models.solid`)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, minimize

from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import ParameterError
from flutterfriction.models.solid import acoustic_vectors, elastic_acoustic_tensor


def cubic_discriminant(A: NDArray) -> NDArray:
    """Discriminant of ``det(A - eta I)`` from the invariants of ``A`` (..., 3, 3): positive for
    three distinct real eigenvalues, negative for a complex-conjugate pair (flutter), zero at a
    coalescence. No eigenvalue is computed."""
    A = np.asarray(A, dtype=float)
    i1 = np.trace(A, axis1=-2, axis2=-1)
    i2 = 0.5 * (i1**2 - np.trace(A @ A, axis1=-2, axis2=-1))
    i3 = np.linalg.det(A)
    # eta^3 - i1 eta^2 + i2 eta - i3: discriminant of a x^3 + b x^2 + c x + d
    a, b, c, d = 1.0, -i1, i2, -i3
    return (18 * a * b * c * d - 4 * b**3 * d + b**2 * c**2 - 4 * a * c**3
            - 27 * a**2 * d**2)


def flutters_somewhere(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray,
                       g_values: NDArray, rtol: float = 1e-9) -> NDArray:
    """For each direction, whether ``A(n; g)`` has a complex pair for some ``g`` of
    ``g_values`` (vectorised brute force). A discriminant counts as negative only below
    ``-rtol`` times its scale ``(tr A / 3)^6``, so that an exact coalescence, where it vanishes
    up to round-off, is not taken for flutter."""
    n = np.asarray(directions, dtype=float)
    Ael = np.einsum("ijkl,mj,ml->mik", E, n, n)
    p = np.einsum("ij,mj->mi", np.einsum("ijkl,kl->ij", E, np.asarray(P, float)), n)
    q = np.einsum("kl,ml->mk", np.einsum("ijkl,ij->kl", E, np.asarray(Q, float)), n)
    A = Ael[:, None] - np.einsum("mi,mk->mik", p, q)[:, None] / np.asarray(g_values)[None, :,
                                                                                     None, None]
    scale = (np.trace(A, axis1=-2, axis2=-1) / 3) ** 6
    return np.any(cubic_discriminant(A) < -rtol * np.abs(scale), axis=1)


def classify_acoustic(A: NDArray, rtol: float = 1e-10) -> Regime:
    """§3.3 (Rice 1977): stable when all ``c^2`` are positive, flutter when two are complex
    conjugate, divergence when one is real and negative."""
    eta = np.linalg.eigvals(np.asarray(A, dtype=float))
    scale = max(np.abs(eta).max(), np.finfo(float).tiny)
    if np.any(np.abs(eta.imag) > rtol * scale):
        return Regime.FLUTTER
    if np.any(eta.real < -rtol * scale):
        return Regime.DIVERGENCE
    return Regime.STABLE


def fibonacci_sphere(n: int) -> NDArray:
    """``n`` nearly uniform unit vectors on the upper half sphere (``n`` and ``-n`` are the
    same band direction), shape (n, 3)."""
    k = np.arange(n) + 0.5
    z = k / n  # z in (0, 1]: the half sphere
    phi = np.pi * (1 + 5**0.5) * k
    r = np.sqrt(1 - z**2)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


def localization_moduli(E: NDArray, P: ArrayLike, Q: ArrayLike, directions: NDArray) -> NDArray:
    """``g_cr^E(n)`` of eq. (166) for many directions at once (vectorised), rho = 1."""
    n = np.asarray(directions, dtype=float)
    Ael = np.einsum("ijkl,mj,ml->mik", E, n, n)
    EP = np.einsum("ijkl,kl->ij", E, np.asarray(P, dtype=float))
    EQt = np.einsum("ijkl,ij->kl", E, np.asarray(Q, dtype=float))
    p = np.einsum("ij,mj->mi", EP, n)
    q = np.einsum("kl,ml->mk", EQt, n)
    return np.einsum("mi,mi->m", q, np.linalg.solve(Ael, p[..., None])[..., 0])


def _angles_to_n(x: NDArray) -> NDArray:
    th, ph = x
    return np.array([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)])


def max_localization_modulus(E: NDArray, P: ArrayLike, Q: ArrayLike,
                             n_search: int = 4000) -> tuple[float, NDArray]:
    """``max_n g_cr^E(n)`` and the maximising direction: a global search on a Fibonacci grid,
    then Nelder–Mead refinement from the best few grid points (the modulus often has several
    symmetric maxima)."""
    grid = fibonacci_sphere(n_search)
    vals = localization_moduli(E, P, Q, grid)
    best_val, best_n = -np.inf, grid[0]
    for i in np.argsort(vals)[-5:]:
        n0 = grid[i]
        x0 = np.array([np.arccos(np.clip(n0[2], -1, 1)), np.arctan2(n0[1], n0[0])])
        res = minimize(lambda x: -localization_moduli(E, P, Q, _angles_to_n(x)[None])[0], x0,
                       method="Nelder-Mead", options={"xatol": 1e-12, "fatol": 1e-15,
                                                      "maxiter": 4000})
        if -res.fun > best_val:
            best_val, best_n = -res.fun, _angles_to_n(res.x)
    return float(best_val), best_n


def flutter_interval_bruteforce(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike,
                                g_max: float, decades: float = 8.0,
                                n_scan: int = 4000) -> list[tuple[float, float]]:
    """Intervals of ``g`` in ``[g_max 10^-decades, g_max]`` where the acoustic tensor
    (eq. 161) has complex eigenvalues: sign changes of :func:`cubic_discriminant` of
    ``A(n; g)`` on a logarithmic scan in ``x = 1/g``, refined with Brent's method. Uses no
    closed form. An interval touching an end of the scan is cut there.

    The discriminant is evaluated from the tensor's invariants, whose terms cancel more and more
    as ``g`` falls below the elastic scale: beyond 8 decades its sign is no longer resolved in
    double precision (noise intervals appear), so wider scans are refused."""
    decades = float(decades)
    if not 0.0 < decades <= 8.0:
        raise ParameterError(f"decades must be in (0, 8], got {decades:g}: further below the "
                             "elastic scale the discriminant's sign is not resolved in double "
                             "precision")
    n = np.asarray(n, dtype=float)
    Ael = elastic_acoustic_tensor(E, n)
    p, q = acoustic_vectors(E, P, Q, n)
    pq = np.outer(p, q)

    def disc(x: float) -> float:
        return float(cubic_discriminant(Ael - x * pq))

    xs = np.geomspace(1.0 / g_max, 10.0**decades / g_max, n_scan)
    vals = cubic_discriminant(Ael[None] - xs[:, None, None] * pq[None])
    edges = [float(xs[0])] if vals[0] < 0 else []
    edges += [brentq(disc, a, b, xtol=1e-15 * b)
              for a, b, fa, fb in zip(xs[:-1], xs[1:], vals[:-1], vals[1:], strict=True)
              if fa * fb < 0]
    if vals[-1] < 0:
        edges.append(float(xs[-1]))
    return sorted((1.0 / b, 1.0 / a) for a, b in zip(edges[::2], edges[1::2], strict=True))
