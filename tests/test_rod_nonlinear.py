"""The nonlinear rod (θ formulation): kinematics, linearisation, convergence to the exact
linear theory, energy conservation without damping."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flutterfriction.analysis import rod as ar
from flutterfriction.analysis.stability import _refine_roots, discriminant, pencil_eigenvalues
from flutterfriction.models.rod import Rod, RodGroups
from flutterfriction.models.rod_nonlinear import NonlinearRod

ROD = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)


def test_straight_and_bent_kinematics():
    m = NonlinearRod(ROD, 4)
    assert np.allclose(m.tip_position(np.zeros(m.n_dof)), [ROD.length, 0.0], atol=1e-14)
    # theta = k s (a circular arc, exactly representable by P2): tip at (sin kl, 1 - cos kl)/k.
    k = 3.0
    nodes = np.linspace(0, ROD.length, 2 * 4 + 1)[1:]
    tip = m.tip_position(k * nodes)
    L = ROD.length
    assert np.allclose(tip, [np.sin(k * L) / k, (1 - np.cos(k * L)) / k], atol=1e-10)


def test_nonlinear_rhs_linearises_to_the_linear_matrices():
    m = NonlinearRod(ROD, 3)
    n, P = m.n_dof, 5.5
    eps = 1e-7
    J = np.column_stack([(m.rhs(0, eps * e, P) - m.rhs(0, -eps * e, P)) / (2 * eps)
                         for e in np.eye(2 * n)])
    M0, C, K, K1 = m.linear_matrices()
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M0, K + P * K1), -np.linalg.solve(M0, C)]])
    assert np.allclose(J, A, rtol=1e-7, atol=1e-7 * np.abs(A).max())


def _flutter(m):
    M0, _, K, K1 = m.linear_matrices()

    def low(P):
        mu = pencil_eigenvalues(K, K1, M0, P)
        idx = np.argsort(np.abs(mu), axis=-1)[..., :6]
        return np.take_along_axis(mu, idx, axis=-1)

    grid = np.linspace(0, 20, 201)
    return _refine_roots(lambda P: float(discriminant(low(np.array([P])))[0]), grid,
                         discriminant(low(grid)))[0]


def test_linearised_flutter_load_converges_at_fourth_order():
    exact = ar.critical_loads(RodGroups()).p_flu * ROD.load_unit
    errors = [abs(_flutter(NonlinearRod(ROD, n)) - exact) / exact for n in (4, 8, 16)]
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(rates > 3.5), (errors, rates)
    assert errors[-1] < 2e-5


def test_energy_conserved_without_damping():
    rod = Rod(length=0.35, B=0.0332, rho=0.0546)  # no D: with P = 0 the motion is conservative
    m = NonlinearRod(rod, 3)
    n = m.n_dof
    y0 = np.concatenate([0.8 * np.linspace(0, 1, n + 1)[1:], np.zeros(n)])

    def energy(y):
        q, v = y[:n], y[n:]
        _, _, G, G_tip = m.kinematics(q)
        return 0.5 * v @ m.mass_matrix(G, G_tip) @ v + 0.5 * q @ m.K @ q

    sol = solve_ivp(lambda t, y: m.rhs(t, y, 0.0), (0, 0.2), y0, method="DOP853", rtol=1e-10,
                    atol=1e-12)
    E = [energy(y) for y in sol.y.T]
    assert max(E) - min(E) < 1e-7 * E[0]


def test_follower_load_power_balance_is_consistent():
    m = NonlinearRod(ROD, 3)
    q = 0.3 * np.linspace(0, 1, m.n_dof + 1)[1:]
    v = np.linspace(-1, 1, m.n_dof)
    P = 5.5
    power, dissipation = m.power_balance(q, v, P)
    # The generalised follower force times v is the power of -P t(l) at the tip.
    theta = m.phi @ q
    F = -P * (m.w * np.sin(q[-1] - theta)) @ m.phi
    assert power == pytest.approx(F @ v, rel=1e-12)
    assert dissipation == pytest.approx(v @ m.C @ v)


def test_generalized_alpha_converges_at_second_order():
    """The structural integrator against a tight adaptive solution, on a gentle motion."""
    from flutterfriction.analysis.rod_dynamics import generalized_alpha

    m = NonlinearRod(ROD, 2)
    n = m.n_dof
    y0 = np.concatenate([0.2 * np.linspace(0, 1, n + 1)[1:], np.zeros(n)])
    T, P = 0.05, 5.5
    ref = solve_ivp(lambda t, y: m.rhs(t, y, P), (0, T), y0, method="LSODA", rtol=1e-12,
                    atol=1e-14).y[:, -1]
    errs = []
    for dt in (1e-4, 5e-5, 2.5e-5):
        _, ys, _ = generalized_alpha(m, P, y0, T, dt, sample_every=10**9)
        errs.append(np.abs(ys[-1, :n] - ref[:n]).max())
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(rates > 1.7), (errs, rates)


def test_cycle_branch_leaves_the_hopf_point_towards_higher_loads():
    """Periodic-orbit continuation from the linear flutter mode (2 elements, a few small
    cycles): the branch starts at the model's damped flutter load, P - P_flu grows like A^2,
    and the period tends to 2 pi / omega_flu."""
    from flutterfriction.analysis.rod_cycles import cycle_branch

    rod = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)
    b = cycle_branch(rod, n_elements=2, A_first=0.01, A_max=0.03, rtol=1e-8, max_points=3)
    assert b.stopped_by == "max_points" and len(b.A) == 3
    A, dP = np.array(b.A), np.array(b.P) - b.P_flu
    assert np.all(np.diff(A) > 0) and np.all(dP > 0)
    ratio = (dP[-1] / dP[0]) / (A[-1] / A[0]) ** 2
    assert abs(ratio - 1) < 0.1
    assert abs(b.T[0] * b.omega_flu / (2 * np.pi) - 1) < 1e-3
    # Floquet: the monodromy maps the flow direction to itself; the slow (amplitude)
    # multiplier matches the normal form exp(-2 sigma T), sigma the growth rate of this same
    # 2-element model. 1 - mu comes from the return map on the section (no cancellation):
    # measured the same to 1e-8 relative at integrator rtol 1e-8, 1e-9 and 1e-11, while its
    # distance from the normal form is the O(A^2) correction, 2.2e-3 at A = 1 cm, 3.6e-3 at
    # 1.3 cm (measured); the 1% bound is that with a margin of about 3.
    m = NonlinearRod(rod, 2)
    M0, C, K, K1 = m.linear_matrices()
    n = m.n_dof
    for P, T, decay, defect, mu_max in zip(b.P, b.T, b.slow_decay, b.trivial_defect,
                                           b.max_floquet_modulus, strict=True):
        # |Phi f - f| / |f| is of the order of the accepted Newton correction, at most
        # 30 rtol = 3e-7 here (measured 3e-11 to 3.7e-8 depending on where Newton stopped)
        assert defect < 1e-6
        lin = np.block([[np.zeros((n, n)), np.eye(n)],
                        [-np.linalg.solve(M0, K + P * K1), -np.linalg.solve(M0, C)]])
        sigma = np.linalg.eigvals(lin).real.max()
        assert 0 < decay and mu_max < 1
        assert abs(decay / (1 - np.exp(-2 * sigma * T)) - 1) < 0.01, (P, decay, sigma)


def test_slow_multiplier_does_not_depend_on_the_integrator_tolerance():
    """The ill-conditioned quantity of the Hopf scene, 1 - mu ~ 1.6e-5, computed well
    conditioned: two integrator tolerances two decades apart agree to 1e-6 relative (measured
    1e-8; the previous eigenvalue route scattered by 2% between machines)."""
    from flutterfriction.analysis.rod_cycles import CycleContinuation

    rod = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)
    decays = [CycleContinuation(rod, n_elements=2, A_max=0.03, rtol=rtol).first(0.01)
              .floquet.slow_decay for rtol in (1e-8, 1e-10)]
    assert abs(decays[0] / decays[1] - 1) < 1e-6, decays


def test_complex_step_jacobian_matches_central_differences():
    from flutterfriction.analysis.rod_cycles import rhs_derivatives

    m = NonlinearRod(ROD, 3)
    y = np.random.default_rng(1).normal(scale=0.3, size=2 * m.n_dof)
    f, J, f_P = rhs_derivatives(m, y, 2.0)
    h = 1e-6
    Jd = np.column_stack([(m.rhs(0, y + h * e, 2.0) - m.rhs(0, y - h * e, 2.0)) / (2 * h)
                          for e in np.eye(y.size)])
    assert np.abs(J - Jd).max() <= 1e-7 * np.abs(J).max()
    assert np.allclose(f, m.rhs(0, y, 2.0), rtol=1e-12, atol=0)  # batched: other rounding
    # The rhs is affine in P (second difference 3e-16 of max|f|), so a central difference in P
    # is exact at any step: dP = 1 leaves only round-off, eps max|f| / max|f_P| ~ 1e-13
    # (measured <= 8.5e-14). At h = 1e-6 that round-off was 1e-7 itself: measured 1e-8 to
    # 7e-8 between BLAS kernels and 1-ulp changes of y, against this same 1e-7 bound.
    dP = 1.0
    f_Pd = (m.rhs(0, y, 2.0 + dP) - m.rhs(0, y, 2.0 - dP)) / (2 * dP)
    assert np.abs(f_P - f_Pd).max() <= 1e-10 * np.abs(f_P).max()


def test_monodromy_of_the_straight_rod_is_the_matrix_exponential():
    """At the equilibrium y = 0 the variational equations are linear with constant
    coefficients: Phi(T) = expm(A T), A from the linear matrices (independent of the complex
    step and of the orbit integration)."""
    from scipy.linalg import expm

    from flutterfriction.analysis.rod_cycles import variational_flow

    m = NonlinearRod(ROD, 2)
    M0, C, K, K1 = m.linear_matrices()
    n, P, T = m.n_dof, 2.5, 0.05
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M0, K + P * K1), -np.linalg.solve(M0, C)]])
    flow = variational_flow(m, np.zeros(2 * n), T, P, rtol=1e-10)
    Phi = flow.Phi
    assert np.abs(flow.S).max() == 0.0  # f_P vanishes on the straight rod
    assert np.abs(Phi - expm(A * T)).max() <= 1e-8 * np.abs(Phi).max()
