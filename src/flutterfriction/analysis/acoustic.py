"""Analysis of the acoustic tensor (chapter §3.3–3.5): classification of a direction, the
maximum of the localization modulus over all directions, and flutter intervals found by brute
force (the independent twins of the isotropic closed forms in :mod:`..models.solid`)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize

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


def discriminant_polynomial(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike
                            ) -> np.polynomial.Polynomial:
    """The cubic discriminant of ``A(n; g) = A_el - p (x) q / g`` (eq. 161) as a polynomial in
    ``x = 1/g``. ``A`` is a rank-one update of ``A_el``, so its invariants are affine in ``x``:
    ``I1 = tr A_el - x p.q``, ``I2 = I2_el - x (tr A_el p.q - q.A_el p)``,
    ``I3 = det A_el - x q.adj(A_el) p`` (matrix determinant lemma), and the discriminant is a
    quartic in ``x``. Its coefficients are formed once, so no cancellation grows with ``x``,
    which is what limits evaluating the discriminant from the invariants at each ``g``."""
    from numpy.polynomial import Polynomial

    n = np.asarray(n, dtype=float)
    Ael = elastic_acoustic_tensor(E, n)
    p, q = acoustic_vectors(E, P, Q, n)
    t, pq = float(np.trace(Ael)), float(p @ q)
    i2_el = 0.5 * (t**2 - float(np.trace(Ael @ Ael)))
    adj = np.linalg.det(Ael) * np.linalg.inv(Ael)
    i1 = Polynomial([t, -pq])
    i2 = Polynomial([i2_el, -(t * pq - float(q @ Ael @ p))])
    i3 = Polynomial([float(np.linalg.det(Ael)), -float(q @ adj @ p)])
    b, c, d = -i1, i2, -i3  # eta^3 + b eta^2 + c eta + d
    return 18 * b * c * d - 4 * b**3 * d + b**2 * c**2 - 4 * c**3 - 27 * d**2


def flutter_interval_bruteforce(E: NDArray, P: ArrayLike, Q: ArrayLike, n: ArrayLike,
                                g_max: float, decades: float = 8.0) -> list[tuple[float, float]]:
    """Intervals of ``g`` in ``[g_max 10^-decades, g_max]`` where the acoustic tensor (eq. 161)
    has complex eigenvalues, from the tensors alone (no closed form): the discriminant of the
    eigenvalue problem as a quartic in ``x = 1/g`` (:func:`discriminant_polynomial`), its real
    roots polished by Newton on the polynomial, and its sign between them. An interval
    touching an end of the range is cut there."""
    g_max, decades = float(g_max), float(decades)
    if not (np.isfinite(g_max) and g_max > 0):
        raise ParameterError(f"g_max must be finite and > 0, got {g_max}")
    if not (np.isfinite(decades) and 0.0 < decades <= 300.0):
        raise ParameterError(f"decades must be in (0, 300], got {decades}")
    disc = discriminant_polynomial(E, P, Q, n)
    ddisc = disc.deriv()
    lo, hi = 1.0 / g_max, 10.0**decades / g_max

    def polish(x: float) -> float:  # Newton on the polynomial, kept only when it helps
        for _ in range(3):
            slope = float(ddisc(x))
            if slope == 0.0:
                break
            x_new = x - float(disc(x)) / slope
            if not abs(float(disc(x_new))) < abs(float(disc(x))):
                break
            x = x_new
        return x

    # Candidate ends: the real parts of all roots (a near-double root may come out as a
    # complex pair), polished and clipped to the range; the sign is read inside each piece.
    cands = sorted({float(np.clip(polish(r.real), lo, hi)) for r in disc.roots()
                    if abs(r.imag) <= 1e-6 * abs(r)} | {lo, hi})
    intervals: list[tuple[float, float]] = []
    for a, b in zip(cands[:-1], cands[1:], strict=True):
        if b > a and float(disc(np.sqrt(a * b))) < 0:
            if intervals and intervals[-1][0] == 1.0 / a:  # adjacent pieces: one interval
                intervals[-1] = (1.0 / b, intervals[-1][1])
            else:
                intervals.append((1.0 / b, 1.0 / a))
    return sorted(intervals)
