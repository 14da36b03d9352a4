"""Routh–Hurwitz of any degree against the roots, including at and near the stability boundary.

Near the boundary a root has Re s ~ 1e-16 |s|: double-precision roots cannot decide stability.
We therefore build the test polynomials from *known* roots, take the rounded float coefficients,
and obtain the truth for those exact coefficients from mpmath at 60 digits. The exact criterion
must agree every time; float eigenvalues are shown to fail where the margin is below round-off.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from conftest import pendulums
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from flutterfriction.analysis.polynomial import characteristic_polynomial
from flutterfriction.analysis.routh import (
    hurwitz_determinants,
    hurwitz_matrix,
    robustly_stable,
    routh_hurwitz,
)
from flutterfriction.analysis.ziegler import spectrum
from flutterfriction.errors import ParameterError


def true_max_real_part(coeffs) -> mp.mpf:
    """Largest real part of the roots of the *exact* (rational) coefficients, at 60 digits."""
    with mp.workdps(60):
        roots = mp.polyroots([mp.mpf(float(c)) for c in coeffs], maxsteps=2000, extraprec=400)
        return max(mp.re(r) for r in roots)


ANY_MARGIN = st.integers(-14, 0)


@st.composite
def polynomials_from_roots(draw, margin_exponent=ANY_MARGIN):
    """Monic real polynomials of degree 1..8 from random roots; the largest real part is
    +/- 10^margin_exponent, from far from the boundary to below double-precision round-off."""
    n_pairs = draw(st.integers(0, 4))
    n_real = draw(st.integers(0 if n_pairs else 1, 8 - 2 * n_pairs))
    roots = []
    for _ in range(n_pairs):
        re = -draw(st.floats(0.05, 5.0))
        im = draw(st.floats(0.1, 5.0))
        roots += [complex(re, im), complex(re, -im)]
    roots += [-draw(st.floats(0.05, 5.0)) for _ in range(n_real)]
    # Distinct roots: mpmath's Durand-Kerner iteration (our truth) stalls on multiple roots.
    r = np.array(roots)
    assume(np.min(np.abs(r[:, None] - r[None, :]) + 10 * np.eye(r.size)) > 1e-2)
    shift = draw(st.sampled_from([-1, 1])) * 10.0 ** draw(margin_exponent)
    lead = max(r.real for r in roots)
    roots = [r - lead + shift for r in roots]  # the rightmost root(s) now have Re = shift
    return np.poly(roots).real


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
@given(polynomials_from_roots())
def test_exact_criterion_matches_high_precision_roots(coeffs):
    truth = true_max_real_part(coeffs)
    assume(abs(truth) > mp.mpf(10) ** -40)  # exactly on the boundary: no strict verdict
    assert routh_hurwitz(coeffs).stable == bool(truth < 0)


@given(polynomials_from_roots(margin_exponent=st.integers(-3, 0)))
def test_float_hurwitz_determinants_match_far_from_boundary(coeffs):
    stable = routh_hurwitz(coeffs).stable
    assert stable == bool(np.all(hurwitz_determinants(coeffs) > 0))
    assert stable == bool(np.roots(coeffs).real.max() < 0)


def test_float_roots_can_be_wrong_at_the_boundary_while_the_exact_criterion_is_not():
    """A pair at Re = 1e-15 beside a cluster of left roots: the exact verdict agrees with the
    60-digit roots; the verdict is flagged as not robust to rounding of the coefficients."""
    roots = [1e-15 + 1j, 1e-15 - 1j, -1.0, -1.1, -1.2, -1.3]
    coeffs = np.poly(roots).real
    truth = true_max_real_part(coeffs)
    assert routh_hurwitz(coeffs).stable == bool(truth < 0)
    assert not robustly_stable(coeffs)  # a verdict this close must not be trusted to ulps


@given(pendulums(), st.floats(0.01, 1.0), st.floats(0.1, 10.0), st.floats(0.0, 3.0))
def test_damped_pendulum_routh_matches_eigenvalues(p, eps_scale, c_ratio, load):
    """Random damped pendulums, random follower loads: the exact criterion on the coefficients
    from the matrices agrees with the eigenvalues whenever the eigenvalues are decisive."""
    c2 = eps_scale * p.l2 * np.sqrt(p.k2 * p.m2)
    p = p.with_(c1=c_ratio * c2, c2=c2)
    P = load * p.load_unit
    s = spectrum(p, P)
    assume(abs(s.real.max()) > 1e-9 * np.abs(s).max())
    coeffs = characteristic_polynomial(p.mass_matrix(), p.viscosity_matrix(),
                                       p.stiffness_matrix() + p.geometric_matrix(P))
    assert routh_hurwitz(coeffs).stable == bool(s.real.max() < 0)


def test_quartic_conditions_of_eq53():
    """For p0 = 1, eq. (53): p1 > 0, p1 p2 - p3 > 0, (p1 p2 - p3) p3 - p1^2 p4 > 0, p4 > 0."""
    rng = np.random.default_rng(3)
    for _ in range(500):
        p1, p2, p3, p4 = rng.uniform(-1, 5, 4)
        eq53 = p1 > 0 and p1 * p2 - p3 > 0 and (p1 * p2 - p3) * p3 - p1**2 * p4 > 0 and p4 > 0
        assert routh_hurwitz([1.0, p1, p2, p3, p4]).stable == eq53


def test_hurwitz_matrix_layout():
    H = hurwitz_matrix([1.0, 2.0, 3.0, 4.0, 5.0])
    assert np.array_equal(H, [[2, 4, 0, 0], [1, 3, 5, 0], [0, 2, 4, 0], [0, 1, 3, 5]])


def test_negative_leading_coefficient_is_normalised():
    assert routh_hurwitz([-1.0, -3.0, -2.0]).stable  # -(s + 1)(s + 2)


@pytest.mark.parametrize("bad", [[1.0], [0.0, 1.0], [1.0, np.nan], [[1.0, 2.0]]])
def test_bad_coefficients(bad):
    with pytest.raises(ParameterError, match="coeffs"):
        routh_hurwitz(bad)


@settings(max_examples=60)
@given(pendulums(), st.floats(0.01, 1.0), st.floats(0.1, 10.0), st.sampled_from([-1, 1]))
def test_damped_pendulum_just_across_the_boundary(p, eps, c, side):
    """At P = P*(1 -/+ 1e-12), with P* the closed-form flutter load (exact to ~1e-16), the exact
    criterion on coefficients from the matrices gives the right verdict on both sides; the
    largest real part of the eigenvalues there is ~1e-12 |s|, close to its own round-off."""
    from flutterfriction.closed_forms.ziegler_damped import damped_flutter_gamma

    c2 = eps * p.l2 * np.sqrt(p.k2 * p.m2)
    pd = p.with_(c1=c * c2, c2=c2)
    P = damped_flutter_gamma(p.groups(), eps, c) * p.load_unit * (1 + side * 1e-12)
    coeffs = characteristic_polynomial(pd.mass_matrix(), pd.viscosity_matrix(),
                                       pd.stiffness_matrix() + pd.geometric_matrix(P))
    assert routh_hurwitz(coeffs).stable == (side < 0)


def _minors_in_fractions(a):
    """Reference: the Hurwitz minors by Bareiss elimination in Fractions (the former method)."""
    from fractions import Fraction

    n = len(a) - 1
    H = [[a[2 * j - i + 1] if 0 <= 2 * j - i + 1 <= n else Fraction(0) for j in range(n)]
         for i in range(n)]
    minors = []
    for k in range(1, n + 1):
        M = [row[:k] for row in H[:k]]
        sign, prev = 1, Fraction(1)
        for p in range(k - 1):
            if M[p][p] == 0:
                swap = next((r for r in range(p + 1, k) if M[r][p] != 0), None)
                if swap is None:
                    M[k - 1][k - 1] = Fraction(0)
                    break
                M[p], M[swap] = M[swap], M[p]
                sign = -sign
            for i in range(p + 1, k):
                for j in range(p + 1, k):
                    M[i][j] = (M[i][j] * M[p][p] - M[i][p] * M[p][j]) / prev
            prev = M[p][p]
        minors.append(sign * M[k - 1][k - 1])
    return minors


def test_integer_hurwitz_minors_equal_the_fraction_elimination():
    """The integer elimination (coefficients times their common denominator) gives exactly the
    minors of the same elimination in Fractions: degrees 1-8, coefficients over 16 decades,
    with exact zeros (pivot swaps)."""
    from fractions import Fraction

    from flutterfriction.analysis.routh import _exact_minors

    rng = np.random.default_rng(0)
    for n in range(1, 9):
        for _ in range(60):
            a = rng.normal(size=n + 1) * 10.0 ** rng.integers(-8, 8, size=n + 1)
            a[rng.random(n + 1) < 0.15] = 0.0
            a[0] = a[0] or 1.0
            coeffs = [Fraction(float(x)) for x in a]
            assert _exact_minors(coeffs) == _minors_in_fractions(coeffs)


def test_coefficients_that_are_not_real_numbers_or_leave_the_double_range_are_refused():
    """A second outside audit: complex coefficients were a raw TypeError, "1" and True were read
    as numbers, Hurwitz determinants beyond the double range came back as inf with a warning,
    a NaN perturbation was blamed on the coefficients."""
    from flutterfriction.analysis.routh import hurwitz_determinants, robustly_stable
    from flutterfriction.errors import ParameterError

    for coeffs in ([1, 2j, 1], ["1", "2"], [True, 2, 1]):
        with pytest.raises(ParameterError, match="^coeffs must be real numbers"):
            routh_hurwitz(coeffs)
        with pytest.raises(ParameterError, match="^coeffs must be real numbers"):
            hurwitz_determinants(coeffs)
    with pytest.raises(ParameterError, match="leave the double range"):
        hurwitz_determinants([1.0, 1e200, 1e200, 1.0])
    with pytest.raises(ParameterError, match="^rel_perturbation must be finite"):
        robustly_stable([1, 3, 3, 1], float("nan"))
    assert list(hurwitz_determinants([1, 3, 3, 1])) == pytest.approx([3, 8, 8])
