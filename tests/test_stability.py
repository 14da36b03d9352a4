"""The general stability solver: spectra, classification, coalescence, buckling, exact motion."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flutterfriction.analysis.stability import (
    Regime,
    classify,
    coalescence_loads,
    discriminant,
    first_order_matrix,
    pencil_eigenvalues,
    static_bifurcation_loads,
)
from flutterfriction.analysis.ziegler import (
    follower_critical_loads,
    linear_response,
    regime,
    spectrum,
)
from flutterfriction.errors import ParameterError


def test_classify_simple_spectra():
    assert classify([1j, -1j, 2j, -2j]) == Regime.STABLE
    assert classify([-0.1 + 1j, -0.1 - 1j]) == Regime.STABLE
    assert classify([0.1 + 1j, 0.1 - 1j, -0.1 + 1j, -0.1 - 1j]) == Regime.FLUTTER
    assert classify([2.0, -2.0, 1j, -1j]) == Regime.DIVERGENCE
    assert classify([1e-15 + 1j, -1e-15 - 1j]) == Regime.STABLE  # round-off is not instability


def test_discriminant_sign():
    assert discriminant(np.array([[1.0, 2.0]]))[0] > 0
    assert discriminant(np.array([[1 + 1j, 1 - 1j]]))[0] < 0
    assert discriminant(np.array([[3.0, 3.0]]))[0] == 0


def test_coalescence_is_exact_not_a_threshold():
    """A 2x2 pencil with known coalescences p = 1 and p = 3: mu^2 - 4 mu + (4 - (p-1)(3-p))...
    built as K0 + p K1 with M = I; eigenvalues 2 ± sqrt((p - 1)(p - 3))."""
    # A(p) = [[2, p - 1], [p - 3, 2]]: eigenvalues 2 ± sqrt((p - 1)(p - 3)).
    K0, K1, M = np.array([[2.0, -1.0], [-3.0, 2.0]]), np.array([[0.0, 1.0], [1.0, 0.0]]), np.eye(2)
    roots = coalescence_loads(K0, K1, M, load_max=10.0, n_scan=37)
    assert roots == pytest.approx([1.0, 3.0], rel=4e-16, abs=4e-16)


def test_pencil_eigenvalues_match_scipy_generalised(list47):
    import scipy.linalg as sla
    P = 6.0
    ours = pencil_eigenvalues(list47.stiffness_matrix(), list47.follower_load_matrix(),
                              list47.mass_matrix(), [P])[0]
    ref = sla.eigvals(list47.stiffness_matrix() + P * list47.follower_load_matrix(),
                      list47.mass_matrix())
    assert np.allclose(np.sort_complex(ours), np.sort_complex(ref), rtol=1e-12)


def test_static_bifurcation_general_branch():
    """Unsymmetric K1 takes the general generalised-eigenvalue branch."""
    K0 = np.array([[2.0, -1.0], [-1.0, 1.0]])
    K1 = -np.array([[1.0, 0.2], [0.0, 1.0]])
    loads = static_bifurcation_loads(K0, K1)
    for p in loads:
        assert abs(np.linalg.det(K0 + p * K1)) < 1e-12


def test_regime_just_around_critical_loads(list47):
    P_flu, P_div = follower_critical_loads(list47)
    assert regime(list47, P_flu * (1 - 1e-6)) == Regime.STABLE
    assert regime(list47, P_flu * (1 + 1e-6)) == Regime.FLUTTER
    assert regime(list47, P_div * (1 - 1e-6)) == Regime.FLUTTER
    assert regime(list47, P_div * (1 + 1e-6)) == Regime.DIVERGENCE


def test_flutter_growth_rate_vanishes_like_a_square_root(list47):
    """Why thresholds on Re s are biased: Re s ~ c sqrt(P - P_flu) just above flutter."""
    P_flu, _ = follower_critical_loads(list47)
    growth = [spectrum(list47, P_flu * (1 + e)).real.max() for e in (1e-4, 4e-4)]
    assert growth[1] / growth[0] == pytest.approx(2.0, rel=1e-3)


@pytest.mark.parametrize("P", [3.0, 6.8, 15.4])
def test_matrix_exponential_matches_a_time_integrator(list47, P):
    """The exact linear solution (expm) vs an independent Runge-Kutta integration."""
    times = np.linspace(0.0, 0.2, 6)
    x0 = np.deg2rad([0.5, 0.5, 0.0, 0.0])
    exact = linear_response(list47, P, 0.0, x0, times)
    M = list47.mass_matrix()
    KG = list47.stiffness_matrix() + list47.geometric_matrix(P)

    def rhs(_t, x):
        return np.concatenate([x[2:], -np.linalg.solve(M, KG @ x[:2])])

    sol = solve_ivp(rhs, (0.0, 0.2), x0, method="DOP853", t_eval=times, rtol=1e-12,
                    atol=1e-14)
    assert np.allclose(exact, sol.y.T, rtol=1e-8, atol=1e-11 * np.abs(exact).max())


def test_linear_response_rejects_bad_input(list47):
    with pytest.raises(ValueError, match="state0"):
        linear_response(list47, 1.0, 0.0, [0.0, 0.0], [0.0])
    with pytest.raises(ParameterError, match="P"):
        linear_response(list47, float("nan"), 0.0, [0.0] * 4, [0.0])


@pytest.mark.parametrize("load_max", [10.0, 1e4, 1e5, 1e8, 1e12])
def test_coalescence_loads_whatever_the_scan_range(load_max):
    """An outside review: with load_max = 1e5 the 2048-step scan put both coalescences of
    this pendulum (7/2 -+ sqrt 2, m1 = 2, m2 = 1, l = k = 1) inside its first step, and none
    was returned, silently. The scan's ends are minimised as its interior dips are, and it
    adds the loads load_max 2^-k."""
    M, K0, K1 = [[3.0, 1.0], [1.0, 1.0]], [[2.0, -1.0], [-1.0, 1.0]], [[-1.0, 1.0], [0.0, 0.0]]
    loads = coalescence_loads(K0, K1, M, load_max)
    assert loads == pytest.approx([3.5 - 2 ** 0.5, 3.5 + 2 ** 0.5], rel=1e-14)


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"M": [[np.nan, 1.0], [1.0, 1.0]]}, "M must be a finite real 2x2"),
    ({"M": [[1.0, 2.0], [3.0, 4.0]]}, "M must be a symmetric positive definite"),
    ({"M": [[1.0, 0.0], [0.0, -1.0]]}, "M must be a symmetric positive definite"),
    ({"M": [1.0, 2.0]}, "M must be a square matrix"),
    ({"M": None}, "M must be a square matrix"),
    ({"K1": [[True, 0], [0, 1]]}, "K1 must be a finite real 2x2 matrix"),
    ({"K0": np.eye(3)}, "K0 must be a finite real 2x2 matrix"),
    ({"load_max": 1e-320}, "load_max must be >= 2.23e-308"),
    ({"load_max": float("inf")}, "load_max must be finite"),
    ({"n_scan": 0}, "n_scan must be an integer in"),
])
def test_coalescence_loads_refuses_bad_input_by_name(kwargs, match):
    """An outside review: NaN, singular, ragged or 1-d matrices ended in numpy's errors, and
    load_max = 1e-320 in a ValueError after 37 s."""
    args = {"K0": [[2.0, -1.0], [-1.0, 1.0]], "K1": [[-1.0, 1.0], [0.0, 0.0]],
            "M": [[3.0, 1.0], [1.0, 1.0]], "load_max": 10.0} | kwargs
    with pytest.raises(ParameterError, match=match):
        coalescence_loads(**args)


@pytest.mark.parametrize("rtol", [float("nan"), -1.0, 1e9, "1", True])
def test_classify_refuses_a_meaningless_tolerance(rtol):
    """An outside review: rtol = NaN or 1e9 called [1 +- 1j] stable, rtol = -1 called a
    stable pair flutter."""
    with pytest.raises(ParameterError, match="rtol"):
        classify([1 + 1j, 1 - 1j], rtol=rtol)


def test_first_order_matrix_refuses_a_singular_mass_matrix():
    with pytest.raises(ParameterError, match="M must be a nonsingular matrix"):
        first_order_matrix([[0.0, 0.0], [0.0, 0.0]], np.eye(2))
