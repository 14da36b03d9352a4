"""The nonlinear rod (θ formulation): kinematics, linearisation, convergence to the exact
linear theory, energy conservation without damping."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from flutterfriction.analysis import rod as ar
from flutterfriction.analysis import rod_cycles as rc
from flutterfriction.analysis import rod_dynamics as rdyn
from flutterfriction.analysis.stability import discriminant, pencil_eigenvalues, refine_roots
from flutterfriction.errors import ConvergenceError, ParameterError
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
    return refine_roots(lambda P: float(discriminant(low(np.array([P])))[0]), grid,
                         discriminant(low(grid)))[0]


def test_linearised_flutter_load_converges_at_fourth_order():
    exact = ar.critical_loads(RodGroups()).p_flu * ROD.load_unit
    errors = [abs(_flutter(NonlinearRod(ROD, n)) - exact) / exact for n in (4, 8, 16)]
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(rates > 3.5), (errors, rates)
    assert errors[-1] < 2e-5


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_damped_linearised_flutter_load_converges_past_the_spectrum_round_off():
    """The damped load of the rod linearised on fine meshes: the first-order spectrum's
    round-off (the stiff Kelvin-Voigt modes) had put a floor under it (1.1e-8 relative at 48
    elements, 3.6e-7 at 64: finer was worse); polished on the quadratic eigenproblem it goes
    on converging at h^4 (5.8e-10, 1.8e-10; measured) to eq. (118)'s exact load."""
    exact = ar.critical_loads(ROD.groups()).p_flu * ROD.load_unit
    errors = [abs(rc.linearised_flutter_load(ROD, n) - exact) / exact for n in (48, 64)]
    assert errors[1] < errors[0] < 2e-9, errors


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


def test_power_balance_of_many_states_equals_the_kinematic_matrices():
    """power_balance integrates the velocities x_dot = G v as vectors; G itself
    (:meth:`NonlinearRod.kinematics`) applied to v must give the same powers, with
    Kelvin-Voigt damping and for a batch of states."""
    rod = Rod(length=ROD.length, B=ROD.B, rho=ROD.rho, D=ROD.D, kappa=1e-3, tip_mass=0.2)
    m = NonlinearRod(rod, 4)
    rng = np.random.default_rng(7)
    q, v = rng.normal(size=(m.n_dof, 5)), 20 * rng.normal(size=(m.n_dof, 5))
    _, _, G, G_tip = m.kinematics(q)
    xdot, xdot_tip = np.einsum("qmci,im->qmc", G, v), np.einsum("mci,im->mc", G_tip, v)
    power = -5.5 * (np.cos(q[-1]) * xdot_tip[:, 0] + np.sin(q[-1]) * xdot_tip[:, 1])
    dissipation = np.einsum("im,ij,jm->m", v, m.C, v) + rod.kappa * np.einsum(
        "q,qmc,qmc->m", m.w, xdot, xdot)
    got = m.power_balance(q, v, 5.5)
    np.testing.assert_allclose(got[0], power, rtol=1e-13, atol=1e-13 * np.abs(power).max())
    np.testing.assert_allclose(got[1], dissipation, rtol=1e-13)


@pytest.mark.slow  # ~5.5 s here
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


@pytest.mark.parametrize("rho_inf", [0.5, 0.8])
def test_generalized_alpha_is_second_order_on_a_large_motion(rho_inf):
    """From a large bend (the work-precision scene's start), where the mass matrix changes
    with the configuration: Chung and Hulbert's form (M(q_n) times the shifted acceleration)
    converged towards first order here for rho_inf < 1 (measured rates 1.2 to 1.6 on these
    steps, 0.9 to 1.0 on finer ones); the form of Arnold and Brüls at second order."""
    from flutterfriction.analysis.rod_dynamics import generalized_alpha

    m = NonlinearRod(ROD, 4)
    n = m.n_dof
    y0 = np.concatenate([1.2 * np.linspace(0, 1, n + 1)[1:], np.zeros(n)])
    T, P = 0.1, 5.5
    ref = solve_ivp(lambda t, y: m.rhs(t, y, P), (0, T), y0, method="DOP853", rtol=1e-12,
                    atol=1e-14).y[:, -1]
    errs = []
    for dt in (5e-4, 2.5e-4, 1.25e-4):
        _, ys, _ = generalized_alpha(m, P, y0, T, dt, rho_inf=rho_inf, sample_every=10**9)
        errs.append(np.abs(ys[-1] - ref).max() / np.abs(ref).max())
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(rates > 1.8), (errs, rates)


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
        # |Phi f - f| / |f| is the accepted iterate's periodicity error (a scaled Newton
        # correction of at most 30 rtol = 3e-7 here) seen through Phi - I, whose entries
        # reach ~100 (119 measured at 4 elements, 5.5 N): at most ~3e-5. Measured 5e-8 to
        # 5.8e-6, depending on how far below its threshold the last correction fell
        # (rounding-level changes move that).
        assert defect < 3e-5
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


def test_implicit_integrators_get_the_exact_jacobian():
    from flutterfriction.analysis.rod_cycles import rhs_derivatives
    from flutterfriction.analysis.rod_dynamics import exact_jacobian

    m = NonlinearRod(ROD, 3)
    y = np.random.default_rng(2).normal(scale=0.3, size=2 * m.n_dof)
    assert exact_jacobian(m, 5.5, "DOP853") == {}
    for method in ("BDF", "Radau", "LSODA"):
        J = exact_jacobian(m, 5.5, method)["jac"](0.0, y)
        J_cs = rhs_derivatives(m, y, 5.5)[1]  # complex steps: other rounding
        assert np.abs(J - J_cs).max() <= 1e-12 * np.abs(J_cs).max()


def test_prolongation_is_exact_for_the_coarse_fields():
    """Coarse P2 fields are P2 on the finer mesh too: interpolation loses nothing, and the
    pseudo-inverse takes them back."""
    from flutterfriction.models.rod_nonlinear import prolongation

    coarse, fine = NonlinearRod(ROD, 2), NonlinearRod(ROD, 3)
    Pm = prolongation(coarse, fine)
    y = np.random.default_rng(3).normal(size=2 * coarse.n_dof)
    nodes = np.linspace(0, ROD.length, fine.n_dof + 1)[1:]
    assert np.allclose((Pm @ y)[: fine.n_dof], coarse.nodal_values_at(y[: coarse.n_dof], nodes))
    assert np.allclose(np.linalg.pinv(Pm) @ Pm, np.eye(Pm.shape[1]), atol=1e-12)


@pytest.fixture(scope="module")
def cycle_2():
    """The 5.5 N cycle on 2 elements: flutter grown from a 1 mm flutter mode, then shooting
    with the exact monodromy."""
    from flutterfriction.analysis.rod_dynamics import grow_into_cycle, shoot_cycle

    m = NonlinearRod(ROD, 2)
    tr = grow_into_cycle(m, 5.5, amplitude=1e-3, rtol=1e-6, tol=3e-3)
    T0 = tr.crossings_t[-1] - tr.crossings_t[-2]
    return tr, shoot_cycle(m, tr.section_states[-1], T0, 5.5, None, "DOP853", rtol=1e-9,
                           tol=1e-7)


def test_transient_grows_from_the_straight_rod_into_the_shooting_cycle(cycle_2):
    """Flutter grows at the linear rate from 1 mm, saturates, and the section points approach
    the Newton cycle at the rate of its slow Floquet multiplier (all inside the unit
    circle)."""
    from flutterfriction.analysis.rod_cycles import tip_lateral
    from flutterfriction.analysis.rod_dynamics import section_distance

    tr, cyc = cycle_2
    A = np.array(tr.crossings_A)
    assert A[0] < 0.01 and A[-1] > 0.2
    # early growth per period ~ exp(sigma T_linear)
    M0, C, K, K1 = cyc.model.linear_matrices()
    assert tr.growth_rate > 0
    d = np.array([section_distance(cyc.model, s, cyc) for s in tr.section_states])
    ratios = d[-6:] / d[-7:-1]
    mu = cyc.floquet.nontrivial
    slow = mu[np.argmin(np.abs(mu - 1))].real
    assert cyc.floquet.max_modulus < 1
    assert np.all(np.abs(ratios - slow) < 0.02), (ratios, slow)
    assert abs(tip_lateral(cyc.model, cyc.y) / A[-1] - 1) < 0.05
    # the monodromy maps the flow direction to itself (the trivial multiplier)
    assert cyc.floquet.trivial_defect < 1e-5


def test_fixed_load_shooting_is_periodic_orbit_newton(cycle_2):
    """The scene's shooting at a fixed load and rod_cycles.PeriodicOrbitNewton (load fixed by
    its parametrising condition) converge to the same cycle."""
    from flutterfriction.analysis.rod_cycles import PeriodicOrbitNewton

    _, cyc = cycle_2
    pt = PeriodicOrbitNewton(cyc.model, 0.25, 5.5, rtol=1e-10, tol=1e-9).solve(
        cyc.y, cyc.T, 5.5, (0.0, 1.0), 1.0)
    assert pt.P == pytest.approx(5.5, rel=1e-12)
    assert pt.T == pytest.approx(cyc.T, rel=1e-7)
    assert np.abs(pt.y - cyc.y).max() <= 1e-6 * np.abs(cyc.y).max()


def test_secant_shooting_on_a_finer_mesh_from_the_prolongated_monodromy(cycle_2):
    """On 3 elements, the chord/secant iteration started from the 2-element cycle and its
    monodromy converges to the cycle that exact Newton finds there."""
    from flutterfriction.analysis.rod_dynamics import shoot_cycle
    from flutterfriction.models.rod_nonlinear import prolongation

    _, c2 = cycle_2
    m3 = NonlinearRod(ROD, 3)
    Pm = prolongation(c2.model, m3)
    chord = shoot_cycle(m3, Pm @ c2.y, c2.T, 5.5, Pm @ c2.monodromy @ np.linalg.pinv(Pm),
                        "BDF", rtol=1e-9, tol=1e-7)
    exact = shoot_cycle(m3, chord.y, chord.T, 5.5, None, "DOP853", rtol=1e-10, tol=1e-7)
    assert chord.T == pytest.approx(exact.T, rel=1e-6)
    assert np.abs(chord.y - exact.y).max() <= 1e-5 * np.abs(exact.y).max()
    # and it contracted: every correction smaller than the one before
    assert np.all(np.diff(np.log(chord.corrections)) < 0)


@pytest.mark.slow
def test_beck_limit_cycle_scene_quick_preset_shows_flutter_growing_into_the_cycle():
    """The scene at the quick preset: the stored transient starts at the small flutter mode and
    ends near the cycle, sampled at a fixed step; the cycle's evidence and the mesh chain."""
    from flutterfriction.config import load_config, scene_params
    from flutterfriction.scenes.rod import beck_limit_cycle

    config = load_config("workflow/config.yaml")
    config["fidelity"] = "quick"
    params = scene_params(config, "beck_limit_cycle")
    d = beck_limit_cycle(params)
    h, tr = d["history"], d["transient"]
    assert abs(h["u2"][0]) <= 1.01 * tr["initial_amplitude_m"]  # from a small perturbation
    assert max(h["u2"]) > 0.2  # into the 0.25 m cycle
    dt = np.diff(h["t"])
    assert np.ptp(dt[:-1]) < 1e-3 * dt[0]  # a fixed step (the last one ends on the section)
    assert d["quantities"]["reaches_limit_cycle"]["value"] == "limit cycle"
    assert d["quantities"]["reaches_limit_cycle"]["independent"] == "limit cycle"
    assert tr["section_distance"][-1] < tr["section_distance"][0]
    assert set(d["cycles"]) == {str(n) for n in d["meshes"]}
    for c in d["cycles"].values():
        assert c["newton_corrections"][-1] <= params["tol"]
    # the cycle drawn as one closed loop, four times finer than the transient's sampling
    loop = np.array([d["cycle_loop"]["u1"], d["cycle_loop"]["u2"]])
    assert loop.shape[1] == 4 * params["samples_per_period"] + 1
    assert np.abs(loop[:, 0] - loop[:, -1]).max() < 1e-4
    # Figs. 15-17 draw it: start, transient and cycle in the legend, units on every axis.
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flutterfriction.plotting.rod import plot_fig15, plot_fig16, plot_fig17

    for plot in (plot_fig15, plot_fig16, plot_fig17):
        fig = plot(d)
        labels = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
        assert [s.split(":")[0] for s in labels] == [
            "start", "transient", "limit cycle (periodic-orbit Newton)"]
        for ax in fig.axes:
            if ax.get_label() != "<colorbar>":
                assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()
        plt.close(fig)


@pytest.mark.parametrize("extra", [{}, {"kappa": 0.01, "tip_mass": 0.02}])
def test_one_state_rhs_is_the_batched_definition(extra):
    """The one-state fast path (the compiled kernel of models/rod_kernel.py) and the batched
    equations of motion agree to rounding (measured <= 3e-14 relative at 1-8 elements), and a
    state whose mass matrix is not positive definite is refused, not integrated."""
    rod = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6, **extra)
    rng = np.random.default_rng(4)
    for n_el in (1, 3, 8):
        m = NonlinearRod(rod, n_el)
        y = rng.normal(scale=0.5, size=2 * m.n_dof)
        n = m.n_dof
        batched = np.concatenate([y[n:], m.accelerations(y[:n], y[n:], 5.5)])
        assert np.abs(m.rhs(0.0, y, 5.5) - batched).max() <= 1e-12 * np.abs(batched).max()
        # the compiled (M, g) of the generalized-alpha residual (M symmetric, whole)
        M, g = m.dynamic_terms(y[:n], y[n:], 5.5)
        M_c, g_c = m.dynamic_terms_at(5.5)(y[:n], y[n:])
        assert np.abs(M_c - M).max() <= 1e-12 * np.abs(M).max()
        assert np.abs(g_c - g).max() <= 1e-12 * np.abs(g).max()
    with pytest.raises(ConvergenceError, match="positive definite"):
        m.rhs(0.0, np.full(2 * m.n_dof, np.nan), 5.5)
    with pytest.raises(ParameterError, match="shape"):
        m.dynamic_terms_at(5.5)(0.0, np.zeros(m.n_dof))
    with pytest.raises(ParameterError, match="real"):
        m.dynamic_terms_at(5.5)(np.zeros(m.n_dof) + 1e-30j, np.zeros(m.n_dof))


@pytest.mark.parametrize("extra", [{}, {"kappa": 0.01, "tip_mass": 0.02}])
def test_compiled_jacobian_is_the_complex_step_of_the_batched_definition(extra):
    """The hand-differentiated, compiled Jacobian and load derivative (models/rod_kernel.py)
    equal the complex steps of the batched equations of motion to rounding (measured <= 6e-14
    relative at 1-8 elements, random states far from the straight rod)."""
    from flutterfriction.analysis.rod_cycles import rhs_derivatives

    rod = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6, **extra)
    rng = np.random.default_rng(5)
    for n_el in (1, 3, 8):
        m = NonlinearRod(rod, n_el)
        Y = rng.normal(scale=0.5, size=(2 * m.n_dof, 3))
        J, f_P = m.jacobians(Y, 5.5)
        for k in range(Y.shape[1]):
            _, J_cs, f_P_cs = rhs_derivatives(m, Y[:, k], 5.5)
            assert np.abs(J[k] - J_cs).max() <= 1e-12 * np.abs(J_cs).max()
            assert np.abs(f_P[k] - f_P_cs).max() <= 1e-12 * np.abs(f_P_cs).max()
    with pytest.raises(ConvergenceError, match="positive definite"):
        m.jacobians(np.full((2 * m.n_dof, 1), np.nan), 5.5)
    # the compiled kernels do not check their indices: a wrong shape is refused before them
    for bad in (np.zeros(2 * m.n_dof - 1), np.zeros((2 * m.n_dof, 2))):
        with pytest.raises(ParameterError, match="shape"):
            m.rhs_at(5.5)(0.0, bad)
    with pytest.raises(ParameterError, match="shape"):
        m.rhs(0.0, np.zeros(2 * m.n_dof + 1), 5.5)
    for bad in (np.zeros(2 * m.n_dof), np.zeros((2 * m.n_dof + 2, 3))):
        with pytest.raises(ParameterError, match="shape"):
            m.jacobians(bad, 5.5)


@pytest.mark.parametrize("n_elements", [1, 3, 8])
def test_tip_lateral_velocity_is_the_kinematics_tip_row(n_elements):
    """The section function's shortcut int cos(theta) theta_dot ds equals the second row of
    G_tip v from the cumulative integrals, for real states and their complex steps."""
    m = NonlinearRod(Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6, tip_mass=0.01),
                     n_elements)
    rng = np.random.default_rng(n_elements)
    for _ in range(5):
        q, v = rng.normal(size=m.n_dof), rng.normal(size=m.n_dof)
        q = q + 1e-20j * rng.normal(size=m.n_dof)
        full = (m.kinematics(q)[3] @ v)[1]
        short = m.tip_lateral_velocity(q, v)
        assert abs(short.real - full.real) <= 1e-14 * abs(full.real)
        assert abs(short.imag - full.imag) <= 1e-14 * abs(full.imag)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_work_precision_periods_start_on_the_section_at_the_quick_preset():
    """Each timed period starts on the Poincaré section, where the section function is zero
    only to rounding: its sign at t = 0 must not decide whether scipy's event search raises
    (it did, LSODA at 2 elements, rtol 1e-5, once the function's rounding changed). Every run
    returns to the section, and each measured period is close to the reference."""
    from flutterfriction.config import load_config, scene_params
    from flutterfriction.scenes.rod import beck_work_precision

    config = load_config("workflow/config.yaml")
    config["fidelity"] = "quick"
    d = beck_work_precision(scene_params(config, "beck_work_precision"))
    solved = [r for r in d["runs"] if r["method"] != "generalized-alpha"]
    assert solved and not any(r["failed"] for r in solved)
    assert all(r["period_error"] < 1e-2 for r in solved)


@pytest.mark.parametrize(("call", "name"), [
    (lambda r: NonlinearRod(r, 2.5), "n_elements"),
    (lambda r: NonlinearRod(r, "4"), "n_elements"),
    (lambda r: NonlinearRod(r, 4, n_gauss=0), "n_gauss"),
    (lambda r: NonlinearRod({}, 4), "rod"),
    (lambda r: rdyn.beck_limit_cycle(r, math.inf), "P"),
    (lambda r: rdyn.beck_limit_cycle(r, 5.5, method="bogus"), "method"),
    (lambda r: rdyn.beck_limit_cycle(r, 5.5, rtol=-1.0), "rtol"),
    (lambda r: rdyn.beck_limit_cycle(r, 5.5, samples_per_period=0), "samples_per_period"),
])
def test_nonlinear_rod_entry_points_refuse_bad_arguments(call, name):
    """Outside audit: NonlinearRod(rod, 2.5) meshed 2 elements and kept 2.5; P = inf, a bogus
    method, rtol < 0 and samples_per_period = 0 reached scipy or divided by zero."""
    rod = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)
    with pytest.raises(ParameterError, match=rf"^{name} "):
        call(rod)


def test_transient_does_not_depend_on_the_unit_of_time(cycle_2):
    """grow_into_cycle's bound and chunk are in the rod's time scale: the same rod twenty
    times slower (rho x 400, D x 20: the same groups) settles at twenty times the time, on the
    same amplitudes. In seconds (t_max 60 s) it was refused (an outside audit, on 3
    elements, ten times slower)."""
    from flutterfriction.analysis.rod_dynamics import grow_into_cycle

    tr, _ = cycle_2
    slow = Rod(length=ROD.length, B=ROD.B, rho=400 * ROD.rho, D=20 * ROD.D)
    other = grow_into_cycle(NonlinearRod(slow, 2), 5.5, amplitude=1e-3, rtol=1e-6, tol=3e-3)
    assert 20 * tr.t_end > 60.0  # beyond the old bound
    assert other.t_end == pytest.approx(20 * tr.t_end, rel=1e-3)
    assert other.crossings_A[-1] == pytest.approx(tr.crossings_A[-1], rel=1e-4)


def test_limit_cycle_with_two_section_crossings_per_period():
    """A stable cycle whose lateral tip displacement has two positive maxima of different
    heights per period (eta = 0.1, 2.9 P_flu; an outside audit: refused as 'slow approach'
    although the crossings alternated 0.68487, 0.83119 exactly). Its period 0.770047 s and
    largest maximum 0.831186 m are the audit's (own Radau integration); the works by
    quadrature balance whatever the sampling (a fixed trapezoid was 50 % off on an
    impulsive cycle)."""
    rod = Rod(length=1.0, B=1.0, rho=1.0, D=0.1)
    runs = [rdyn.beck_limit_cycle(rod, 39.5, n_elements=4, method="LSODA", rtol=1e-8,
                                  atol=1e-10, tol=1e-5, initial_tip_rotation=1.2,
                                  samples_per_period=n) for n in (20, 200)]
    for c in runs:
        assert c.period_s == pytest.approx(0.770047, rel=2e-6)
        assert c.tip_amplitude_m == pytest.approx(0.831186, rel=2e-6)
        assert c.energy_balance_error < 1e-6
    assert runs[0].work_follower_J == pytest.approx(runs[1].work_follower_J, rel=1e-9)
    assert runs[0].tip_rotation_amplitude_rad == pytest.approx(
        runs[1].tip_rotation_amplitude_rad, rel=1e-9)


def test_cycle_chain_on_one_mesh():
    """beck_cycle_chain with a single mesh returns it (was an IndexError after all the work),
    and an empty list of meshes is refused before any."""
    with pytest.raises(ParameterError, match="meshes"):
        rdyn.beck_cycle_chain(ROD, 5.5, [])


def test_the_nonlinear_rods_public_functions_refuse_bad_input_before_any_work():
    """An outside audit of the nonlinear rod (its physics agreed with the auditor's own chain
    of rigid links to 1e-5..1e-7) found these taken silently: NaN loads (NaN accelerations, a
    NaN start state), a negative or zero period (minutes of backward integration, a bare
    LinAlgError), dt = 0, NaN or > t_end and rho_inf = -1 (ZeroDivisionError, ValueError, the
    initial state returned alone), A_max = inf (LinAlgError), max_points = 2.5, abscissae
    beyond the rod (extrapolated), and 30 N on list (119) (minutes of integration)."""
    m = NonlinearRod(ROD, 2)
    y = np.zeros(2 * m.n_dof)
    cases = [
        (lambda: m.rhs_at(math.nan), "P must be"),
        (lambda: m.rhs(0.0, y, math.inf), "P must be a finite load"),
        (lambda: m.jacobians(y[:, None], math.nan), "P must be"),
        (lambda: m.nodal_values_at(y[:m.n_dof], [-0.35]), "s must be finite abscissae"),
        (lambda: rdyn.shoot_cycle(m, y, -0.1, 3.2), "T must be"),
        (lambda: rdyn.shoot_cycle(m, y, 0.0, 3.2), "T must be"),
        (lambda: rdyn.shoot_cycle(m, y[:3], 0.1, 3.2), "y must be a finite state"),
        (lambda: rdyn.generalized_alpha(m, 3.0, y, 0.01, 0.0), "dt must be"),
        (lambda: rdyn.generalized_alpha(m, 3.0, y, 0.01, math.nan), "dt must be"),
        (lambda: rdyn.generalized_alpha(m, 3.0, y, 0.01, 0.1), r"dt must be in \(0, t_end\]"),
        (lambda: rdyn.generalized_alpha(m, 3.0, y, 0.01, 1e-3, rho_inf=-1.0), "rho_inf"),
        (lambda: rdyn.flutter_mode_start(m, 3.2, math.nan), "amplitude must be"),
        (lambda: rc.cycle_branch(ROD, 2, A_max=math.inf), "A_max must be"),
        (lambda: rc.cycle_branch(ROD, 2, max_points=2.5), "max_points must be"),
        (lambda: rdyn.beck_limit_cycle(ROD, 30.0, n_elements=2), r"P must be in \(2.9"),
    ]
    for call, match in cases:
        with pytest.raises(ParameterError, match=match):
            call()
    # ... and a load as a 0-d numpy array (numpy's reductions return them) is still a load
    f = m.rhs_at(np.array(5.5))
    assert np.array_equal(f(0.0, y + 0.01), m.rhs_at(5.5)(0.0, y + 0.01))


@pytest.mark.parametrize("extra", [{}, {"kappa": 0.01, "tip_mass": 0.02}])
@pytest.mark.parametrize("n_elements", [1, 4])
def test_compiled_dop853_is_scipys_dop853(extra, n_elements):
    """The compiled orbit integrator (models/rod_kernel.py: dop853_orbit) takes scipy's DOP853
    steps: the same number of steps and right-hand sides (to a few %: sums in another order
    move the step-size control's last digits), the same accuracy against a 1e-13 integration
    (measured within 1.5x of scipy's error at rtol 1e-6 and 1e-9, 1 and 4 elements; 3x
    allowed), and its interpolant is scipy's Dop853DenseOutput of the same coefficients."""
    from scipy.integrate import solve_ivp
    from scipy.integrate._ivp.common import OdeSolution
    from scipy.integrate._ivp.rk import Dop853DenseOutput

    from flutterfriction.analysis.rod_orbit import integrate_orbit

    m = NonlinearRod(Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6, **extra), n_elements)
    y0 = np.random.default_rng(3).normal(scale=0.2, size=2 * m.n_dof)
    T, P = 0.3, 5.5
    ref = solve_ivp(m.rhs_at(P), (0, T), y0, method="DOP853", rtol=1e-13, atol=1e-16).y[:, -1]
    for rtol in (1e-6, 1e-9):
        own = integrate_orbit(m, y0, T, P, rtol, rtol * 1e-3, dense_output=True)
        sp = solve_ivp(m.rhs_at(P), (0, T), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-3,
                       dense_output=True)
        assert own.success and own.t[0] == 0.0 and own.t[-1] == T
        assert abs(own.t.size - sp.t.size) <= 0.05 * sp.t.size
        assert abs(own.nfev - sp.nfev) <= 0.05 * sp.nfev
        scale = np.abs(ref).max()
        err_own = np.abs(own.y[:, -1] - ref).max() / scale
        err_sp = np.abs(sp.y[:, -1] - ref).max() / scale
        assert err_own <= 3 * err_sp + 1e-14
        # the interpolant: scipy's evaluation of the same steps, bit for bit, and the steps
        scipy_sol = OdeSolution(own.t, [Dop853DenseOutput(own.t[k], own.t[k + 1], own.y[:, k],
                                                          own.sol.F[k])
                                        for k in range(own.t.size - 1)])
        t = np.concatenate([np.random.default_rng(1).uniform(0, T, 50), own.t])
        assert np.array_equal(own.sol(t), scipy_sol(t))
        assert np.array_equal(own.sol(0.1234), scipy_sol(0.1234))
        assert np.abs(own.sol(own.t) - own.y).max() <= 1e-14 * np.abs(own.y).max()


def test_compiled_dop853_refuses_what_it_cannot_integrate():
    from flutterfriction.analysis.rod_orbit import integrate_orbit

    m = NonlinearRod(Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6), 2)
    y = np.zeros(2 * m.n_dof)
    with pytest.raises(ConvergenceError, match="positive definite"):  # a state far out
        integrate_orbit(m, np.full(2 * m.n_dof, 1e300), 0.1, 5.5, 1e-9, 1e-12)
    for T in (0.0, -1.0, np.inf, np.nan):
        with pytest.raises(ParameterError, match="T must be"):
            integrate_orbit(m, y, T, 5.5, 1e-9, 1e-12)
    with pytest.raises(ParameterError, match="shape"):
        integrate_orbit(m, y[:-1], 0.1, 5.5, 1e-9, 1e-12)
    with pytest.raises(ParameterError, match="P must"):
        integrate_orbit(m, y, 0.1, np.nan, 1e-9, 1e-12)
    # below scipy's 100 eps the steps grew without end (rtol 1e-20: > 60 s, 400 MB; an outside
    # review); a negative rtol integrated silently
    for rtol in (1e-20, 1e-17, -1e-9, np.nan, 1.0):
        with pytest.raises(ParameterError, match="rtol must be"):
            integrate_orbit(m, y, 0.1, 5.5, rtol, 1e-12)
    for atol in (-1.0, np.nan, np.inf):
        with pytest.raises(ParameterError, match="atol must be"):
            integrate_orbit(m, y, 0.1, 5.5, 1e-9, atol)
    with pytest.raises(ParameterError, match="finite"):
        integrate_orbit(m, np.full(2 * m.n_dof, np.inf), 0.1, 5.5, 1e-9, 1e-12)
    sol = integrate_orbit(m, y + 0.01, 0.1, 5.5, 1e-9, 1e-12, dense_output=True)
    with pytest.raises(ParameterError, match="1-D"):
        sol.sol(np.zeros((2, 2)))


@pytest.mark.parametrize(("scene", "key"), [("beck_branch", "rtol"),
                                             ("beck_branch", "check_rtol"),
                                             ("beck_hopf", "rtol")])
def test_the_rod_cycle_scenes_refuse_an_rtol_the_orbit_integrator_cannot_meet(scene, key):
    """Below 100 eps the compiled DOP853's steps grow without end (an outside review: rtol
    1e-20 ran > 60 s and 400 MB); the workflow's schema already stops the config below 1e-12,
    and the scenes' own checks (their Python entry point) now refuse it before any work."""
    from flutterfriction.registry import SCENES

    for bad in (1e-20, -1e-9, "x", 0.5):
        with pytest.raises(ParameterError, match=f"{key} must be"):
            SCENES[scene].check({"rod": {"length": 0.35, "B": 0.0332, "rho": 0.0546,
                                         "D": 7.078e-6}, key: bad})


def test_the_polished_damped_flutter_load_converges_at_h4_and_ignores_the_scan():
    """The linearised rod's damped flutter load: the raw eigenvalue crossing has a round-off
    floor (~1e-9 relative at 32 elements, moving with the scan's range: the shown rate read
    5.15, then 4.63 after a 1-ulp change of that range); polished by Newton on the quadratic
    eigenproblem it does not move with the range (measured 3e-13) and its error falls at
    h^4 from 16 to 32 elements (measured rate 4.32; 3.8-4.6 allowed)."""
    from flutterfriction.analysis.damped import flutter_onset, polish_flutter_onset
    from flutterfriction.parameters import LIST_119

    rod = Rod(**{k: LIST_119[k] for k in ("length", "B", "rho", "D")})
    exact = ar.critical_loads(rod.groups()).p_flu * rod.load_unit
    errors = []
    for n in (16, 32):
        M, C, K, K1 = NonlinearRod(rod, n).linear_matrices()
        polished = [polish_flutter_onset(M, C, K, K1, flutter_onset(
            M, C, K, K1, load_max=3 * exact * f, n_scan=64)) for f in (1.0, 1 + 1e-15, 1.001)]
        assert max(polished) - min(polished) <= 1e-11 * exact
        errors.append(abs(polished[0] - exact) / exact)
    assert 3.8 < math.log2(errors[0] / errors[1]) < 4.6
    with pytest.raises(ConvergenceError, match="no flutter crossing|another pair|did not converge"):
        polish_flutter_onset(M, C, K, K1, 1.2 * polished[0])


@pytest.mark.parametrize(("kwargs", "text"), [
    ({"initial_tip_rotation": 1e6}, r"^initial_tip_rotation must be non-zero and within half "
                                    r"a turn \(0 < \|rotation\| <= pi rad\), got 1000000\.0"),
    ({"initial_tip_rotation": 0.0}, r"^initial_tip_rotation must be non-zero"),
    ({"t_max": 1e9}, r"^t_max must be in \(0, 314\.2\] s \(2000 time scales"),
])
def test_beck_limit_cycle_refuses_a_start_or_a_time_the_command_line_refuses(kwargs, text):
    """Outside audit: the Python API integrated a tip rotation of 1e6 rad until killed, and
    took any t_max; both are refused before any work, as the command line refuses them."""
    rod = Rod(length=0.35, B=0.0332, rho=0.0546, D=7.078e-6)
    with pytest.raises(ParameterError, match=text):
        rdyn.beck_limit_cycle(rod, 5.5, n_elements=4, method="LSODA", **kwargs)
