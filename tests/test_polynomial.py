"""Characteristic polynomials and exact root counts, against independent computations."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from flutterfriction.analysis.polynomial import (
    characteristic_polynomial,
    count_positive_real_roots,
    count_right_half_plane_roots,
    discriminant_from_coefficients,
    regime_from_coefficients,
)
from flutterfriction.analysis.stability import Regime, classify, state_eigenvalues
from flutterfriction.errors import ConvergenceError


def _random_system(rng, n):
    A = rng.normal(size=(n, n))
    M = A @ A.T + n * np.eye(n)
    B = rng.normal(size=(n, n))
    C = B @ B.T
    K = rng.normal(size=(n, n)) * 3
    return M, C, K


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_characteristic_polynomial_vs_eigenvalues(n):
    rng = np.random.default_rng(n)
    for _ in range(20):
        M, C, K = _random_system(rng, n)
        ours = characteristic_polynomial(M, C, K)
        ref = np.poly(state_eigenvalues(M, K, C)).real * np.linalg.det(M)
        assert np.allclose(ours, ref, rtol=1e-8, atol=1e-9 * np.abs(ref).max())


@given(st.lists(st.integers(-6, 6), min_size=2, max_size=7)
       .filter(lambda a: a[0] != 0 and a[-1] != 0))
def test_root_counts_vs_mpmath(coeffs):
    with mp.workdps(50):
        try:
            roots = mp.polyroots(coeffs, maxsteps=500, extraprec=300)
        except mp.NoConvergence:  # repeated roots: Durand-Kerner cannot settle them
            assume(False)
    try:
        count = count_right_half_plane_roots(coeffs)
    except ConvergenceError:
        # Only allowed when roots are symmetric about the origin (a zero row of the array).
        assert any(abs(r + q) < 1e-20 for r in roots for q in roots)
        return
    assert count == sum(mp.re(r) > 0 for r in roots)
    distinct_pos = {round(float(mp.re(r)), 12) for r in roots
                    if abs(mp.im(r)) < 1e-25 and mp.re(r) > 0}
    assert count_positive_real_roots(coeffs) == len(distinct_pos)


def test_singular_routh_array_is_reported():
    with pytest.raises(ConvergenceError, match="imaginary axis"):
        count_right_half_plane_roots([1.0, 0.0, 1.0])  # s^2 + 1


@pytest.mark.parametrize(("coeffs", "n_rhp"), [([1, 0, 0, 1], 2), ([1, 0, 0, 0, 0, 1], 2),
                                                ([1, 0, 0, 0, 0, -1], 3), ([1, 2, 2, 4, 1], 2)])
def test_epsilon_method_for_zero_pivots(coeffs, n_rhp):
    assert count_right_half_plane_roots(coeffs) == n_rhp


def test_regime_from_coefficients_vs_eigenvalues():
    rng = np.random.default_rng(7)
    for _ in range(300):
        M, C, K = _random_system(rng, 2)
        coeffs = characteristic_polynomial(M, C, K)
        assert regime_from_coefficients(coeffs) == classify(state_eigenvalues(M, K, C))


def test_discriminant_vanishes_at_double_roots():
    assert discriminant_from_coefficients(np.poly([1.0, 1.0, -2.0])) == pytest.approx(0, abs=1e-14)
    assert abs(discriminant_from_coefficients(np.poly([1.0, 2.0, -2.0]))) > 1e-3
    assert regime_from_coefficients(np.poly([2.0, -1.0])) == Regime.DIVERGENCE
    assert regime_from_coefficients(np.poly([1 + 1j, 1 - 1j]).real) == Regime.FLUTTER


@given(st.lists(st.floats(-1e3, 1e3, allow_nan=False).filter(lambda x: x != 0.0),
                min_size=3, max_size=9),
       st.lists(st.integers(-40, 40), min_size=9, max_size=9))
def test_integer_root_counts_equal_their_fraction_twins(mantissas, exponents):
    """The integer (fraction-free) Routh and Sturm counts against the same algorithms in
    Fractions, on coefficients spanning up to 80 decades (the extreme devices' spread)."""
    from fractions import Fraction

    from flutterfriction.analysis.polynomial import (
        _count_positive_real_roots_fractions,
        _fractions,
        _routh_first_column,
        _routh_signs_integer,
    )
    coeffs = [m * 10.0 ** e for m, e in zip(mantissas, exponents, strict=False)]
    a = _fractions(coeffs)
    assert count_positive_real_roots(coeffs) == _count_positive_real_roots_fractions(coeffs)
    signs = _routh_signs_integer(a)
    try:
        first = _routh_first_column(a, Fraction(0))
    except ZeroDivisionError:  # a zero pivot
        first = None
    if signs is None:  # a zero pivot: the integer path declines, the Fraction one sees it too
        assert first is None or any(x == 0 for x in first)
    else:
        assert first is not None and signs == [x > 0 for x in first]
