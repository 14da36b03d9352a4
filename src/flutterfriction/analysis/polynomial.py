"""Characteristic polynomials and exact root counting, without computing any eigenvalue.

These are the algebraic twins of the eigenvalue computations in :mod:`.stability`:

- :func:`characteristic_polynomial`: coefficients of ``det(M s^2 + C s + K)`` from its values on
  a circle (discrete Fourier transform; exact for a polynomial of degree 2n up to round-off);
- :func:`count_right_half_plane_roots`: Routh's array, in exact rational arithmetic;
- :func:`count_positive_real_roots`: Sturm's sequence, in exact rational arithmetic;
- :func:`regime_from_coefficients`: stable / flutter / divergence from the two counts
  (divergence: every root with Re s > 0 is real; flutter: some is not);
- :func:`discriminant_from_coefficients`: ``Res(p, p')`` (Sylvester), zero at a double root.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import ConvergenceError


def characteristic_polynomial(M: ArrayLike, C: ArrayLike, K: ArrayLike) -> NDArray[np.float64]:
    """Coefficients (highest degree first) of ``det(M s^2 + C s + K)``, degree ``2n``.

    For n <= 2 the determinant is expanded exactly. Otherwise it is evaluated at ``N = 2n + 1``
    points ``s_j = r exp(2 pi i j / N)`` with
    ``r = sqrt(||K|| / ||M||)`` (the frequency scale, which keeps the powers of ``s`` balanced),
    and the coefficients are recovered by an FFT.
    """
    M, C, K = (np.asarray(x, dtype=float) for x in (M, C, K))
    n = M.shape[0]
    if n <= 2:
        # Expand exactly: every coefficient keeps its own relative precision (the FFT's error is
        # relative to the largest coefficient, which spoils the O(damping) ones at small damping).
        entry = [[np.array([M[i, j], C[i, j], K[i, j]]) for j in range(n)] for i in range(n)]
        if n == 1:
            return entry[0][0]
        return np.polysub(np.polymul(entry[0][0], entry[1][1]),
                          np.polymul(entry[0][1], entry[1][0]))
    N = 2 * n + 1
    r = float(np.sqrt(np.linalg.norm(K) / np.linalg.norm(M))) or 1.0
    s = r * np.exp(2j * np.pi * np.arange(N) / N)
    values = np.linalg.det(M[None] * s[:, None, None] ** 2 + C[None] * s[:, None, None] + K[None])
    ascending = (np.fft.fft(values) / N).real / r ** np.arange(N)
    return ascending[::-1]


def _fractions(coeffs: ArrayLike) -> list[Fraction]:
    a = [Fraction(float(x)) for x in np.atleast_1d(np.asarray(coeffs, dtype=float))]
    while a and a[0] == 0:
        a.pop(0)
    if len(a) < 2:
        raise ValueError("need a polynomial of degree >= 1")
    return a


def _routh_first_column(a: list[Fraction], eps: Fraction) -> list[Fraction] | None:
    """First column of Routh's array; a zero pivot in a non-zero row is replaced by ``eps``
    (the epsilon method). None when a whole row vanishes (roots symmetric about the origin)."""
    rows = [a[0::2], a[1::2]]
    width = len(rows[0])
    rows = [r + [Fraction(0)] * (width - len(r)) for r in rows]
    if rows[1][0] == 0:
        if not any(rows[1]):
            return None
        rows[1][0] = eps
    for _ in range(len(a) - 2):
        r0, r1 = rows[-2], rows[-1]
        new = [(r1[0] * r0[j + 1] - r0[0] * r1[j + 1]) / r1[0] for j in range(width - 1)]
        new.append(Fraction(0))
        if new[0] == 0:
            if not any(new):
                return None
            new[0] = eps
        rows.append(new)
    return [r[0] for r in rows]


def count_right_half_plane_roots(coeffs: ArrayLike) -> int:
    """Number of roots with Re s > 0, from the sign changes of the first column of Routh's
    array (exact arithmetic).

    A zero pivot with a non-zero row (e.g. ``s^3 + 1``) is handled by the epsilon method, with
    an exact rational epsilon far below the coefficients' scale; the count is accepted only if a
    10^40 times smaller epsilon gives the same one. A vanishing row (roots symmetric about the
    origin, e.g. on the imaginary axis) leaves the count undefined: :class:`ConvergenceError`,
    and callers step off that point.
    """
    a = _fractions(coeffs)
    scale = max(abs(x) for x in a)
    counts = set()
    for exponent in (40, 80):
        first = _routh_first_column(a, scale / 10**exponent)
        if first is None:
            raise ConvergenceError("Routh array has a zero row (roots symmetric about the "
                                   "origin, e.g. on the imaginary axis)")
        counts.add(sum((x > 0) != (y > 0) for x, y in zip(first[:-1], first[1:], strict=True)))
    if len(counts) != 1:
        raise ConvergenceError("Routh's epsilon method is inconclusive for these coefficients")
    return counts.pop()


def _poly_rem(num: list[Fraction], den: list[Fraction]) -> list[Fraction]:
    num = list(num)
    while len(num) >= len(den):
        f = num[0] / den[0]
        for i in range(len(den)):
            num[i] -= f * den[i]
        num.pop(0)
    while num and num[0] == 0:
        num.pop(0)
    return num


def count_positive_real_roots(coeffs: ArrayLike) -> int:
    """Number of distinct real roots in (0, inf), by Sturm's theorem (exact arithmetic)."""
    p = _fractions(coeffs)
    n = len(p) - 1
    dp = [c * (n - i) for i, c in enumerate(p[:-1])]
    seq = [p, dp]
    while True:
        r = _poly_rem(seq[-2], seq[-1])
        if not r:
            break
        seq.append([-c for c in r])

    def changes(values: list[Fraction]) -> int:
        v = [x for x in values if x != 0]
        return sum((x > 0) != (y > 0) for x, y in zip(v[:-1], v[1:], strict=True))

    at_zero = [q[-1] for q in seq]
    at_inf = [q[0] for q in seq]  # sign of the leading coefficient
    return changes(at_zero) - changes(at_inf)


def regime_from_coefficients(coeffs: ArrayLike) -> Regime:
    """Stable / flutter / divergence of ``x(t) ~ exp(s t)`` from the characteristic polynomial
    alone: divergence when all the right-half-plane roots are real, flutter when some are not."""
    n_rhp = count_right_half_plane_roots(coeffs)
    if n_rhp == 0:
        return Regime.STABLE
    return Regime.DIVERGENCE if count_positive_real_roots(coeffs) >= n_rhp else Regime.FLUTTER


def discriminant_from_coefficients(coeffs: ArrayLike) -> float:
    """The resultant ``Res(p, p')`` (Sylvester determinant), normalised: zero exactly when ``p``
    has a multiple root, smooth in the coefficients (for Brent's method)."""
    a = np.atleast_1d(np.asarray(coeffs, dtype=float))
    a = a / np.max(np.abs(a))
    n = a.size - 1
    da = a[:-1] * np.arange(n, 0, -1)
    S = np.zeros((2 * n - 1, 2 * n - 1))
    for i in range(n - 1):
        S[i, i:i + n + 1] = a
    for i in range(n):
        S[n - 1 + i, i:i + n] = da
    return float(np.linalg.det(S))
