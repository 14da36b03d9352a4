"""Routh–Hurwitz criterion for a real polynomial of any degree (chapter eq. 53 is the quartic case).

For ``p(s) = a0 s^n + a1 s^(n-1) + ... + an`` with ``a0 > 0``, all roots have negative real part
iff the leading principal minors ``Delta_1 ... Delta_n`` of the Hurwitz matrix
``H[i, j] = a_{2j - i + 1}`` (1-based, ``a_k = 0`` outside ``0..n``) are all positive.

Round-off. Near a stability boundary a root's real part is ~1e-16 relative, and the sign read
off floating-point eigenvalues (or float Hurwitz determinants) is then noise. The verdict here
is computed in exact rational arithmetic on the given coefficients (every float is a rational),
so it is the exact answer for those coefficients; what remains is the rounding of the
coefficients themselves, which :func:`hurwitz_margin` quantifies. Float determinants
(:func:`hurwitz_determinants`) are provided for root finding, where only sign changes of a
smooth function matter.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from flutterfriction.errors import ParameterError, check_real


def _coefficients(coeffs: ArrayLike) -> NDArray[np.float64]:
    if isinstance(coeffs, np.ndarray) and coeffs.dtype.kind in "iuf":
        a = np.atleast_1d(coeffs.astype(float))
    else:  # each entry checked (numpy reads [True, 2] as integers, "1" as a number)
        a = np.array([float(x) for x in _exact_coefficients(coeffs)])
    if a.ndim != 1 or a.size < 2:
        raise ParameterError("coeffs must be a 1-D sequence of at least two coefficients")
    if not np.all(np.isfinite(a)):
        raise ParameterError(f"coeffs must be finite, got {a}")
    if a[0] == 0.0:
        raise ParameterError("coeffs[0] (the leading coefficient) must be non-zero")
    return a if a[0] > 0 else -a


def hurwitz_matrix(coeffs: ArrayLike) -> NDArray[np.float64]:
    """The n-by-n Hurwitz matrix of ``a0 s^n + ... + an`` (coefficients highest degree first)."""
    a = _coefficients(coeffs)
    n = a.size - 1
    H = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            k = 2 * j - i + 1
            if 0 <= k <= n:
                H[i, j] = a[k]
    return H


def hurwitz_determinants(coeffs: ArrayLike) -> NDArray[np.float64]:
    """``Delta_1 ... Delta_n`` in floating point (smooth in the coefficients: for root finding)."""
    H = hurwitz_matrix(coeffs)
    with np.errstate(over="ignore", invalid="ignore"):
        minors = np.array([np.linalg.det(H[:k, :k]) for k in range(1, H.shape[0] + 1)])
    if not np.all(np.isfinite(minors)):  # (an outside audit: inf returned with a warning)
        raise ParameterError("the Hurwitz determinants of these coefficients leave the double "
                             "range: routh_hurwitz decides on them exactly")
    return minors


def _exact_minors(a: list[Fraction]) -> list[Fraction]:
    """Leading principal minors of the Hurwitz matrix by fraction-free (Bareiss) elimination.

    In integers: the coefficients times their common denominator ``D`` (a power of two for
    floats) are integers, the Hurwitz matrix's ``k``-th minor scales by ``D^k``, and Bareiss'
    divisions are exact in integers; each minor is returned as the exact fraction
    ``minor / D^k`` (~10x cheaper than the same elimination in ``Fraction``s, which reduce by
    a gcd at every operation)."""
    n = len(a) - 1
    D = math.lcm(*(x.denominator for x in a))
    c = [x.numerator * (D // x.denominator) for x in a]
    H = [[c[2 * j - i + 1] if 0 <= 2 * j - i + 1 <= n else 0 for j in range(n)]
         for i in range(n)]
    minors = []
    for k in range(1, n + 1):
        M = [row[:k] for row in H[:k]]
        sign, prev = 1, 1
        for p in range(k - 1):
            if M[p][p] == 0:  # pivot: swap with a lower row with a non-zero entry in column p
                swap = next((r for r in range(p + 1, k) if M[r][p] != 0), None)
                if swap is None:
                    M[k - 1][k - 1] = 0
                    break
                M[p], M[swap] = M[swap], M[p]
                sign = -sign
            for i in range(p + 1, k):
                for j in range(p + 1, k):
                    # exact: Bareiss' quotient is an integer (Sylvester's identity)
                    M[i][j] = (M[i][j] * M[p][p] - M[i][p] * M[p][j]) // prev
            prev = M[p][p]
        minors.append(Fraction(sign * M[k - 1][k - 1], D**k))
    return minors


class RouthHurwitz(NamedTuple):
    """Exact verdict of the criterion for the given coefficients."""

    stable: bool  # all roots strictly in the left half-plane
    minors: tuple[Fraction, ...]  # Delta_1 ... Delta_n, exact
    first_failure: int | None  # index k (1-based) of the first Delta_k <= 0, None if stable


def _exact_coefficients(coeffs: ArrayLike) -> list[Fraction]:
    """The coefficients as exact fractions (floats as the rationals they are; fractions, as
    :func:`~flutterfriction.analysis.polynomial.characteristic_polynomial` gives for exact
    matrices, as they are), checked as :func:`_coefficients`, leading coefficient positive."""
    from flutterfriction.analysis.polynomial import exact_coefficients

    arr = np.atleast_1d(np.asarray(coeffs, dtype=object))
    if arr.ndim != 1 or arr.size < 2:
        raise ParameterError("coeffs must be a 1-D sequence of at least two coefficients")
    a = exact_coefficients(arr)
    if a[0] == 0:
        raise ParameterError("coeffs[0] (the leading coefficient) must be non-zero")
    return a if a[0] > 0 else [-x for x in a]


def routh_hurwitz(coeffs: ArrayLike) -> RouthHurwitz:
    """Routh–Hurwitz criterion in exact rational arithmetic on the given coefficients (floats,
    or exact fractions: then the verdict is exact for the system itself).

    A zero minor (a root on the imaginary axis, exactly) counts as not stable: the criterion
    decides asymptotic stability.
    """
    a = _exact_coefficients(coeffs)
    minors = _exact_minors(a)
    failure = next((k + 1 for k, m in enumerate(minors) if m <= 0), None)
    return RouthHurwitz(stable=failure is None, minors=tuple(minors), first_failure=failure)


def robustly_stable(coeffs: ArrayLike, rel_perturbation: float = 8 * np.finfo(float).eps) -> bool:
    """Kharitonov's theorem: True iff *every* polynomial whose coefficients lie within
    ``rel_perturbation`` (relative) of ``coeffs`` is stable, i.e. the stable verdict survives the
    rounding of coefficients computed in double precision. Tests the four Kharitonov vertex
    polynomials exactly."""
    rel_perturbation = check_real("rel_perturbation", rel_perturbation)
    if not 0 <= rel_perturbation < 1:
        raise ParameterError(f"rel_perturbation must be in [0, 1), got {rel_perturbation!r}")
    a = _coefficients(coeffs)[::-1]  # ascending powers, a[i] multiplies s^i
    lo = np.minimum(a * (1 - rel_perturbation), a * (1 + rel_perturbation))
    hi = np.maximum(a * (1 - rel_perturbation), a * (1 + rel_perturbation))
    patterns = ("llhh", "hhll", "lhhl", "hllh")  # Kharitonov's four vertex polynomials
    for pattern in patterns:
        vertex = np.array([(lo if pattern[i % 4] == "l" else hi)[i] for i in range(a.size)])
        if not routh_hurwitz(vertex[::-1]).stable:
            return False
    return True
