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

import math
import numbers
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.analysis.stability import Regime
from flutterfriction.errors import ConvergenceError, ParameterError


def characteristic_polynomial(M: ArrayLike, C: ArrayLike, K: ArrayLike) -> NDArray[np.float64]:
    """Coefficients (highest degree first) of ``det(M s^2 + C s + K)``, degree ``2n``.

    Exact matrices (every entry an integer or a fraction, n <= 2, e.g.
    :meth:`~flutterfriction.models.ziegler.ZieglerPendulum.dimensionless_matrices` with
    ``exact=True``) give the exact coefficients as fractions (an object array), which the
    exact verdicts below use as they are; any float entry, or n > 2, means doubles.

    For n <= 2 the determinant is expanded exactly. Otherwise it is evaluated at ``N = 2n + 1``
    points ``s_j = r exp(2 pi i j / N)`` with
    ``r = sqrt(||K|| / ||M||)`` (the frequency scale, which keeps the powers of ``s`` balanced),
    and the coefficients are recovered by an FFT.
    """
    M, C, K = (np.asarray(x) for x in (M, C, K))
    exact = all_exact(M, C, K) and M.shape[0] <= 2
    M, C, K = (np.asarray(x, dtype=object if exact else float) for x in (M, C, K))
    n = M.shape[0]
    if n <= 2:
        # Expand exactly: every coefficient keeps its own relative precision (the FFT's error is
        # relative to the largest coefficient, which spoils the O(damping) ones at small damping).
        if n == 1:
            return np.array([M[0, 0], C[0, 0], K[0, 0]])
        # (a2 s^2 + a1 s + a0)(b2 s^2 + b1 s + b0) - (c2 s^2 + ...)(d2 s^2 + ...), term by term
        # (np.polymul's convolution in scalars, equal to it to the last bit or two: this runs
        # thousands of times in a load scan)
        a = (M[0, 0], C[0, 0], K[0, 0])
        b = (M[1, 1], C[1, 1], K[1, 1])
        c = (M[0, 1], C[0, 1], K[0, 1])
        d = (M[1, 0], C[1, 0], K[1, 0])
        return np.array([
            a[0] * b[0] - c[0] * d[0],
            (a[0] * b[1] + a[1] * b[0]) - (c[0] * d[1] + c[1] * d[0]),
            (a[0] * b[2] + a[1] * b[1] + a[2] * b[0]) - (c[0] * d[2] + c[1] * d[1] + c[2] * d[0]),
            (a[1] * b[2] + a[2] * b[1]) - (c[1] * d[2] + c[2] * d[1]),
            a[2] * b[2] - c[2] * d[2],
        ], dtype=object if exact else float)
    N = 2 * n + 1
    r = float(np.sqrt(np.linalg.norm(K) / np.linalg.norm(M))) or 1.0
    s = r * np.exp(2j * np.pi * np.arange(N) / N)
    values = np.linalg.det(M[None] * s[:, None, None] ** 2 + C[None] * s[:, None, None] + K[None])
    ascending = (np.fft.fft(values) / N).real / r ** np.arange(N)
    return ascending[::-1]


def all_exact(*arrays: ArrayLike) -> bool:
    """Whether every entry of every array is an integer or a fraction (object arrays of
    :class:`~fractions.Fraction`): the exact paths; a float entry anywhere means doubles (a
    float times a fraction is a float)."""
    return all(np.asarray(a).dtype == object
               and all(isinstance(x, (int, Fraction)) and not isinstance(x, bool)
                       for x in np.asarray(a).ravel().tolist()) for a in arrays)


def exact_coefficients(coeffs: ArrayLike) -> list[Fraction]:
    """The coefficients as exact fractions: fractions and integers as they are, floats as the
    rationals they are (every double is one), after refusing non-finite values."""
    arr = np.atleast_1d(np.asarray(coeffs, dtype=object))
    out = []
    for x in arr.tolist():
        if isinstance(x, np.ndarray) and x.ndim == 0:  # a numpy 0-d array is a number too
            x = x.item()
        # real numbers only (an outside audit: "1" and True were read as numbers, a complex
        # coefficient was a raw TypeError)
        if isinstance(x, bool | np.bool_) or not isinstance(x, numbers.Real):
            raise ParameterError(f"coeffs must be real numbers, got {arr.tolist()!r:.120}")
        if isinstance(x, (Fraction, int)):
            out.append(Fraction(x))
            continue
        v = float(x)
        if not math.isfinite(v):
            raise ParameterError(f"coeffs must be finite, got {arr.tolist()}")
        out.append(Fraction(v))
    return out


def _fractions(coeffs: ArrayLike) -> list[Fraction]:
    a = exact_coefficients(coeffs)
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


def _integers(a: list[Fraction]) -> list[int]:
    """The coefficients times their common denominator (a power of two for floats): integers
    with the same roots. Integer arithmetic is ~10x cheaper than ``Fraction``'s, which reduces
    by a gcd at every operation."""
    D = math.lcm(*(x.denominator for x in a))
    return [x.numerator * (D // x.denominator) for x in a]


def _primitive(row: list[int]) -> list[int]:
    """``row`` divided by the gcd of its entries (a positive factor: signs are kept)."""
    g = math.gcd(*row)
    return [x // g for x in row] if g > 1 else row


def _routh_signs_integer(a: list[Fraction]) -> list[bool] | None:
    """Signs (True: positive) of the first column of Routh's array, fraction-free in integers.

    Row ``k`` is kept as ``R_k = c_k T_k`` (``T_k`` the true row): then
    ``R_{k+1}[j] = R_k[0] R_{k-1}[j+1] - R_{k-1}[0] R_k[j+1] = c_k c_{k-1} T_k[0] T_{k+1}[j]``,
    so only the sign of ``c_{k+1} = c_k c_{k-1} T_k[0]`` is tracked (dividing a row by the gcd
    of its entries keeps it). None at a zero pivot: the epsilon method is left to
    :func:`_routh_first_column`, in ``Fraction``s."""
    c = _integers(a)
    r0, r1 = c[0::2], c[1::2]
    width = len(r0)
    rows = [r0, r1 + [0] * (width - len(r1))]
    positive = [True, True]  # sign(c_k) > 0
    if rows[1][0] == 0:
        return None
    for _ in range(len(c) - 2):
        R0, R1 = rows[-2], rows[-1]
        new = [R1[0] * R0[j + 1] - R0[0] * R1[j + 1] for j in range(width - 1)] + [0]
        if new[0] == 0:
            return None
        t1_positive = (R1[0] > 0) == positive[-1]  # sign(T_k[0])
        positive.append(positive[-1] == positive[-2] if t1_positive
                        else positive[-1] != positive[-2])
        rows.append(_primitive(new))
    return [(R[0] > 0) == pos for R, pos in zip(rows, positive, strict=True)]


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
    signs = _routh_signs_integer(a)
    if signs is not None:  # no zero pivot: the exact count without any epsilon
        return sum(x != y for x, y in zip(signs[:-1], signs[1:], strict=True))
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


def _sturm_next(num: list[int], den: list[int]) -> list[int]:
    """The next member of Sturm's sequence, ``-rem(num, den)``, times a positive integer (the
    sequence is used only through signs), by pseudo-division in integers: each step
    ``num <- lc(den) num - num[0] x^k den`` multiplies the remainder by ``lc(den)``."""
    num = list(num)
    lead = den[0]
    steps = 0
    while len(num) >= len(den):
        f = num[0]
        num = [lead * x - f * den[i] if i < len(den) else lead * x
               for i, x in enumerate(num)][1:]
        steps += 1
    negate = not (lead < 0 and steps % 2 == 1)  # -rem = -sign(lead)^steps * pseudo-remainder
    while num and num[0] == 0:
        num.pop(0)
    return _primitive([-x for x in num] if negate else num) if num else []


def count_positive_real_roots(coeffs: ArrayLike) -> int:
    """Number of distinct real roots in (0, inf), by Sturm's theorem (exact arithmetic, in
    integers: :func:`_sturm_next`; :func:`_count_positive_real_roots_fractions` is its twin in
    ``Fraction``s)."""
    p = _integers(_fractions(coeffs))
    n = len(p) - 1
    seq = [p, [c * (n - i) for i, c in enumerate(p[:-1])]]
    while True:
        r = _sturm_next(seq[-2], seq[-1])
        if not r:
            break
        seq.append(r)
    return _sign_changes([q[-1] for q in seq]) - _sign_changes([q[0] for q in seq])


def _sign_changes(values: list) -> int:
    v = [x for x in values if x != 0]
    return sum((x > 0) != (y > 0) for x, y in zip(v[:-1], v[1:], strict=True))


def _count_positive_real_roots_fractions(coeffs: ArrayLike) -> int:
    """:func:`count_positive_real_roots` with the Sturm sequence in ``Fraction``s (the test's
    independent twin of the integer pseudo-division)."""
    p = _fractions(coeffs)
    n = len(p) - 1
    dp = [c * (n - i) for i, c in enumerate(p[:-1])]
    seq = [p, dp]
    while True:
        r = _poly_rem(seq[-2], seq[-1])
        if not r:
            break
        seq.append([-c for c in r])
    at_zero = [q[-1] for q in seq]
    at_inf = [q[0] for q in seq]  # sign of the leading coefficient
    return _sign_changes(at_zero) - _sign_changes(at_inf)


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
