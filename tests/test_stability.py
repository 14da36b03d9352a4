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
