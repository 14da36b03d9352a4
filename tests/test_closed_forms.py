"""Every closed form of §2.2–2.3 against its numerical twin, over random pendulums (hypothesis)."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from conftest import pendulums
from hypothesis import assume, given
from hypothesis import strategies as st

from flutterfriction.analysis.stability import Regime, pencil_eigenvalues
from flutterfriction.analysis.ziegler import (
    critical_loads,
    dead_critical_loads,
    follower_critical_loads,
    regime,
)
from flutterfriction.closed_forms import ziegler as cf
from flutterfriction.models.ziegler import ZieglerPendulum


def _omega2(p: ZieglerPendulum, K1: np.ndarray, loads) -> np.ndarray:
    mu = pencil_eigenvalues(p.stiffness_matrix(), K1, p.mass_matrix(), loads)
    return mu * p.m2 * p.l2**2 / p.k2


@given(pendulums())
def test_flutter_divergence_loads_eqs_39_41(p):
    """Coalescence points of the eigenvalues = eqs. (39), (41) with sqrt(k a)."""
    P_flu, P_div = follower_critical_loads(p)
    g_flu, g_div = cf.flutter_divergence_gammas(p.groups())
    u = p.load_unit
    assert P_flu == pytest.approx(g_flu * u, rel=1e-9, abs=1e-12 * g_div * u)
    assert P_div == pytest.approx(g_div * u, rel=1e-9)
    assert 0 < P_flu < P_div


@given(pendulums())
def test_printed_eq39_is_wrong_unless_a_is_one(p):
    """The printed 2 sqrt(k) a differs from the eigenvalues' answer whenever a != 1, whatever k
    (k = 1 included: an earlier note said the forms agree there)."""
    g = p.groups()
    a = cf.coefficient_a(g)
    assume(abs(a - 1) > 1e-3)
    printed = cf.flutter_divergence_gammas_as_printed(g)
    P_flu, P_div = follower_critical_loads(p)
    assert abs(printed[1] * p.load_unit - P_div) > 1e-6 * P_div


def test_printed_eq39_misses_the_chapters_own_loads_for_list_47():
    """List (47) has k = 1 and a = 28/9: the chapter's quoted 4.8 N and 8.8 N follow from
    sqrt(k a), the printed sqrt(k) a gives 3.28 N and 10.33 N."""
    from flutterfriction.parameters import LIST_47

    p = ZieglerPendulum(**LIST_47)
    g = p.groups()
    assert g.k == pytest.approx(1.0) and cf.coefficient_a(g) == pytest.approx(28 / 9)
    correct = [x * p.load_unit for x in cf.flutter_divergence_gammas(g)]
    printed = [x * p.load_unit for x in cf.flutter_divergence_gammas_as_printed(g)]
    assert correct == pytest.approx([4.8038, 8.8042], abs=5e-5)  # the chapter's digits
    assert printed == pytest.approx([3.276, 10.332], abs=5e-4)


@given(pendulums(), st.floats(-3.0, 3.0))
def test_omega2_follower_eq34(p, s):
    """Eq. (34) = eigenvalues of (K + G(P), M), at loads around the critical ones."""
    g = p.groups()
    g_flu, g_div = cf.flutter_divergence_gammas(g)
    gamma = g_flu + s * (g_div - g_flu)
    num = np.sort_complex(_omega2(p, p.follower_load_matrix(), [gamma * p.load_unit])[0])
    closed = np.sort_complex(cf.omega2_follower(g, gamma))
    scale = np.abs(closed).max()
    # Sum and product of the roots are well conditioned everywhere ...
    assert num.sum() == pytest.approx(closed.sum(), rel=1e-10, abs=1e-10 * scale)
    assert np.prod(num) == pytest.approx(np.prod(closed), rel=1e-10, abs=1e-10 * scale**2)
    # ... the roots themselves only away from a coalescence, where they are ill-conditioned
    # (a defective eigenvalue moves like sqrt(perturbation)); there sum and product suffice.
    disc = (closed[0] - closed[1]) ** 2
    if abs(disc) > 1e-6 * scale**2:
        assert np.allclose(num, closed, rtol=1e-8, atol=1e-10 * scale)


@given(pendulums(), st.floats(-1.0, 4.0))
def test_regimes_eq37_match_eigenvalues(p, s):
    """Stable / flutter / divergence of eq. (37) = classification of the first-order spectrum."""
    g = p.groups()
    g_flu, g_div = cf.flutter_divergence_gammas(g)
    gamma = g_flu + s * (g_div - g_flu)
    # Stay away from the boundaries, where a classification is a matter of round-off.
    assume(min(abs(gamma - g_flu), abs(gamma - g_div)) > 1e-3 * (g_div - g_flu))
    assert regime(p, gamma * p.load_unit) == cf.follower_regime(g, gamma)


@given(pendulums())
def test_unloaded_and_tensile_states_are_stable(p):
    """§2.3 remarks: Delta(0) > 0, beta1 > 0; a tensile follower load is stable."""
    g = p.groups()
    assert cf.coefficient_beta1(g) ** 2 - 4 * g.k * cf.coefficient_a(g) > 0
    assert regime(p, 0.0) == Regime.STABLE
    assert regime(p, -10 * p.load_unit) == Regime.STABLE


@given(pendulums())
def test_buckling_loads_eq22(p):
    H_cr, H_sup = dead_critical_loads(p)
    e_cr, e_sup = cf.buckling_etas(p.groups())
    assert H_cr == pytest.approx(e_cr * p.load_unit, rel=1e-10)
    assert H_sup == pytest.approx(e_sup * p.load_unit, rel=1e-10)


@given(pendulums(), st.floats(0.0, 1.5))
def test_omega2_dead_load_eq19_and_regimes_eq23(p, s):
    """Eq. (19) = eigenvalues; sign pattern of eq. (23); dead loads only ever diverge."""
    g = p.groups()
    e_cr, e_sup = cf.buckling_etas(g)
    eta = s * e_sup
    assume(min(abs(eta - e_cr), abs(eta - e_sup)) > 1e-6 * e_sup)
    num = _omega2(p, p.dead_load_matrix(), [eta * p.load_unit])[0]
    assert np.all(np.abs(num.imag) <= 1e-10 * np.abs(num).max())  # symmetric: real (eq. 16)
    closed = cf.omega2_dead_load(g, eta)
    assert np.allclose(np.sort(num.real), closed, rtol=1e-8, atol=1e-8 * np.abs(closed).max())
    n_negative = int(np.sum(closed < 0))
    assert n_negative == (0 if eta < e_cr else 1 if eta < e_sup else 2)
    expected = Regime.STABLE if eta < e_cr else Regime.DIVERGENCE
    assert regime(p, 0.0, eta * p.load_unit) == expected


@given(pendulums(three_masses=False))
def test_two_mass_formula_eq42(p):
    g = p.groups()
    assert cf.two_mass_gammas(g.lam, g.y1, g.rho1, g.k) == pytest.approx(
        cf.flutter_divergence_gammas(g), rel=1e-10)


@given(st.floats(0.05, 2.0), st.floats(0.05, 2.0), st.floats(0.01, 10.0), st.floats(0.1, 1.0),
       st.floats(0.01, 10.0))
def test_optimal_loads_eqs_43_45(l1, l2, k2, y, m2):
    """Choose k1 so that eq. (43) holds; then the eigenvalues give eqs. (44), (45)."""
    d, m1 = y * l1, 2.0 * m2
    k1 = k2 * (d / l2) ** 2 * (m1 / m2)  # sqrt(k1/k2) = (d/l2) sqrt(m1/m2), eq. (43)
    p = ZieglerPendulum(l1=l1, l2=l2, d=d, h=0.0, m1=m1, m2=m2, m3=0.0, k1=k1, k2=k2)
    assert follower_critical_loads(p) == pytest.approx(
        cf.optimal_two_mass_loads(l1, l2, k1, k2), rel=1e-9)


def test_quoted_examples_eqs_25_46_48():
    equal = dict(l1=1.0, l2=1.0, d=1.0, h=0.0, m1=1.0, m2=1.0, m3=0.0, k1=1.0, k2=1.0)
    c = critical_loads(ZieglerPendulum(**equal))
    assert c.H_cr == pytest.approx((3 - math.sqrt(5)) / 2, rel=1e-13)
    assert (c.P_flu, c.P_div) == pytest.approx((2.0, 4.0), rel=1e-13)
    c = critical_loads(ZieglerPendulum(**{**equal, "d": 0.5}))
    assert (c.P_flu, c.P_div) == pytest.approx((17 / 8, 25 / 8), rel=1e-13)


def test_coalescence_digits_against_mpmath(list47):
    """The double root, computed at 50 digits with mpmath from the matrices, agrees with the
    double-precision coalescence to ~1e-14: the method is exact up to round-off."""
    p = list47

    def disc(P):
        A = mp.inverse(M) * (K + P * G1)
        return (A[0, 0] + A[1, 1]) ** 2 - 4 * mp.det(A)

    P_flu, P_div = follower_critical_loads(p)
    with mp.workdps(50):
        M, K, G1 = (mp.matrix(x.tolist()) for x in (p.mass_matrix(), p.stiffness_matrix(),
                                                     p.follower_load_matrix()))
        for ours in (P_flu, P_div):
            exact = mp.findroot(disc, mp.mpf(ours))
            assert abs(ours - float(exact)) <= 5e-15 * abs(ours)


def test_closed_form_refuses_what_the_numerical_twin_refuses():
    """Outside audit: k1 = 1e300 raised a raw OverflowError in the closed form, while the
    numerical twin refused it naming k1, k2."""
    from flutterfriction.errors import ParameterError

    p = ZieglerPendulum(l1=0.1, l2=0.1, d=0.05, h=0.0, m1=0.3, m2=0.1, m3=0.0, k1=1e300, k2=0.2)
    with pytest.raises(ParameterError, match=r"^k1, k2: the ratio k1/k2"):
        cf.critical_loads_closed_form(p)
    with pytest.raises(ParameterError, match=r"^pendulum must be a ZieglerPendulum"):
        cf.critical_loads_closed_form("x")
    with pytest.raises(ParameterError, match=r"^pendulum must be a ZieglerPendulum"):
        critical_loads("x")


def test_eq22_buckling_load_keeps_its_digits_at_extreme_ratios():
    """Outside audit: eq. (22) as (s - root)/2 cancelled to 4.8e-6 relative at k1/k2 = 1.6e-5,
    l1/l2 = 1.3e-6; from the roots' product k lam it agrees with the eigenvalue twin."""
    p = ZieglerPendulum(l1=1.3e-7, l2=0.1, d=1.3e-7, h=0.0, m1=0.2, m2=0.2, m3=0.0,
                        k1=0.189 * 1.6e-5, k2=0.189)
    H_cr, H_sup = dead_critical_loads(p)
    e_cr, e_sup = cf.buckling_etas(p.groups())
    assert e_cr * p.load_unit == pytest.approx(H_cr, rel=1e-12)
    assert e_sup * p.load_unit == pytest.approx(H_sup, rel=1e-12)


def test_the_closed_forms_refuse_a_damped_pendulum():
    """The closed forms are the undamped pendulum's: for one with hinge viscosity they
    returned the undamped loads under the damped fields' names (4.30 N where the damped
    flutter load is 3.03 N; an outside audit)."""
    from flutterfriction.errors import ParameterError
    from flutterfriction.models.ziegler import ZieglerPendulum

    base = dict(l1=1.0, l2=1.0, d=1.0, h=0.0, m1=1.0, m2=1.0, m3=0.0, k1=1.0, k2=1.0)
    damped = ZieglerPendulum(**base, c1=0.01, c2=0.01)
    with pytest.raises(ParameterError, match=r"undamped pendulum's, got c1 = 0.01"):
        cf.critical_loads_closed_form(damped)
    # eq. (46): 2 K/L without viscosity
    assert cf.critical_loads_closed_form(damped.with_(c1=0.0, c2=0.0)).P_flu == pytest.approx(
        2.0, rel=1e-12)
