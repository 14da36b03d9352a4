"""Nonlinear dynamics of the Ziegler pendulum (§2.9): Jacobian, limit cycle, shooting."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from conftest import ROOT, pendulums
from hypothesis import given, settings
from hypothesis import strategies as st

from flutterfriction import ConvergenceError, ParameterError, ZieglerPendulum
from flutterfriction.analysis import dynamics as dy
from flutterfriction.analysis.ziegler import damped_flutter_load, linear_response
from flutterfriction.closed_forms.ziegler_damped import eq54_flutter_gamma, viscosity_groups

SEC29 = ZieglerPendulum(l1=0.1, l2=0.1, d=0.1, h=0.0, m1=0.2, m2=0.2, m3=0.0, k1=0.189,
                        k2=0.189, c1=0.006, c2=0.006)


@settings(max_examples=40)
@given(pendulums(), st.lists(st.floats(-2, 2), min_size=4, max_size=4), st.floats(0, 3))
def test_analytic_jacobian_vs_central_differences(p, state, load):
    p = p.with_(c1=0.1 * p.k1, c2=0.05 * p.k2)
    P = load * p.load_unit
    x = np.array(state)
    J = dy.jacobian(p, x, P, H=0.3 * p.load_unit)
    h = 1e-6
    fd = np.column_stack([(p.equations_of_motion(x + h * e, P, 0.3 * p.load_unit)
                           - p.equations_of_motion(x - h * e, P, 0.3 * p.load_unit)) / (2 * h)
                          for e in np.eye(4)])
    assert np.allclose(J, fd, rtol=1e-5, atol=1e-6 * np.abs(J).max())


@functools.cache
def _sympy_jacobian():
    """The Jacobian of eq. (10) differentiated by sympy from the equations written out again
    here (an independent derivation of the model's hand-written one)."""
    import sympy as sp

    names = "l1 l2 d h m1 m2 m3 k1 k2 c1 c2 P H"
    params = sp.symbols(names)
    l1, l2, d, h, m1, m2, m3, k1, k2, c1, c2, P, H = params
    a1, a2, w1, w2 = sp.symbols("a1 a2 w1 w2")
    s, c = sp.sin(a1 - a2), sp.cos(a1 - a2)
    w = (m2 * l2 + m3 * h) * l1
    I1 = m1 * d**2 + (m2 + m3) * l1**2
    I2 = m2 * l2**2 + m3 * h**2
    f1 = (-w * w2**2 * s - k1 * a1 - k2 * (a1 - a2) - c1 * w1 - c2 * (w1 - w2) + P * l1 * s
          + H * l1 * sp.sin(a1))
    f2 = w * w1**2 * s + k2 * (a1 - a2) - c2 * (w2 - w1) + H * l2 * sp.sin(a2)
    # M(alpha) alpha'' = f solved by sympy itself, not by the model's closed inverse
    M = sp.Matrix([[I1, w * c], [w * c, I2]])
    acc = M.LUsolve(sp.Matrix([f1, f2]))
    rhs = sp.Matrix([w1, w2, acc[0], acc[1]])
    fn = sp.lambdify(((a1, a2, w1, w2), params), rhs.jacobian([a1, a2, w1, w2]), "numpy")
    return lambda p, x, P, H: np.array(fn(tuple(x), (p.l1, p.l2, p.d, p.h, p.m1, p.m2, p.m3,
                                                      p.k1, p.k2, p.c1, p.c2, P, H)), float)


_VISCOSITY = st.one_of(st.just(0.0), st.floats(1e-6, 0.3))  # c / k [s]


@settings(max_examples=60)
@given(pendulums(), st.lists(st.floats(-3, 3), min_size=4, max_size=4), st.floats(-3, 3),
       st.floats(-1, 1), _VISCOSITY, _VISCOSITY)
def test_hand_jacobian_equals_sympys_derivative(p, state, load, dead, v1, v2):
    """The hand-differentiated Jacobian against sympy's, over pendulums, states, loads of both
    signs, dead loads and viscosities: the same to round-off (rtol 1e-9 of its largest entry:
    two orders of evaluation of the same rational expressions)."""
    p = p.with_(c1=v1 * p.k1, c2=v2 * p.k2)
    P, H = load * p.load_unit, dead * p.load_unit
    J = dy.jacobian(p, state, P, H=H)
    S = _sympy_jacobian()(p, state, P, H)
    assert np.allclose(J, S, rtol=1e-9, atol=1e-9 * np.abs(S).max())


def test_small_motions_follow_the_linear_solution():
    """Eq. (10) linearises to eq. (11): at 1e-5 rad they differ by O(alpha^3) ~ 1e-15 plus
    the integrator's absolute tolerance (1e-12), nothing more."""
    P = 0.5 * damped_flutter_load(SEC29)
    x0 = [1e-5, -1e-5, 0.0, 0.0]
    t = np.linspace(0, 1.0, 11)
    nl = dy.simulate(SEC29, P, x0, 1.0, t_eval=t).y.T
    li = linear_response(SEC29, P, 0.0, x0, t)
    assert np.allclose(nl, li, rtol=0, atol=1e-11)


def test_sampled_motion_is_simulate_s_motion_at_least_as_accurately():
    """LSODA's samples (odeint) against DOP853 at rtol 1e-13 over 40 s of §2.9's transient,
    from a start with velocities (scaled into the pendulum's time unit and back): within 1e-8
    (measured 5.3e-9 from rest; simulate at its defaults 1.7e-8), angles and velocities."""
    P = 1.5 * damped_flutter_load(SEC29)
    x0 = np.array([0.002, -0.001, 0.05, 0.03])
    t = np.linspace(0.0, 40.0, 2001)
    ref = dy.simulate(SEC29, P, x0, 40.0, t_eval=t, rtol=1e-13, atol=1e-14).y.T
    y = dy.sampled_motion(SEC29, P, x0, t)
    assert y.shape == (2001, 4) and np.allclose(y[0], x0, rtol=1e-15, atol=0)
    assert np.max(np.abs(y - ref)) < 1e-8
    assert np.max(np.abs(y[:, :2])) > 0.1  # (it grew to the cycle: a real comparison)


def test_sampled_motion_does_not_depend_on_the_unit_of_time():
    """The same pendulum with time in tau (masses / tau^2, viscosities / tau): the same angles
    at the same instants in that unit, velocities times tau, to the integration's own error
    (integrated in tau either way, but the rescaled parameters differ in their last bits, which
    moves LSODA's steps: measured 1.1e-10 over these 20 s; a wrong scaling is O(1e-3))."""
    P = 1.5 * damped_flutter_load(SEC29)
    x0 = np.array([0.002, 0.002, 0.04, -0.02])
    tau = dy.time_unit(SEC29)
    t = np.linspace(0.0, 20.0, 401)
    y = dy.sampled_motion(SEC29, P, x0, t)
    u = dy.sampled_motion(dy.in_time_unit(SEC29), P, x0 * [1, 1, tau, tau], t / tau)
    assert np.allclose(u[:, :2], y[:, :2], rtol=0, atol=1e-9)
    assert np.allclose(u[:, 2:], y[:, 2:] * tau, rtol=0, atol=1e-9)


@pytest.mark.parametrize("t, match", [
    ([0.5, 1.0], r"t must be at least two increasing instants from 0 .*got t\[0\] = 0\.5"),
    ([0.0, 1.0, 0.5], r"got t\[2\] = 0\.5 after t\[1\] = 1"),
    ([0.0], r"t must be at least two .*got shape \(1,\)"),
    ([0.0, 1e9], r"to at most 1\.029e\+04 s .*got t\[-1\] = 1e\+09 s"),
    ([0.0, float("nan")], "t must be finite"),
])
def test_sampled_motion_refuses_bad_instants_by_name(t, match):
    with pytest.raises(ParameterError, match=match):
        dy.sampled_motion(SEC29, 1.0, [0.1, 0.1, 0.0, 0.0], t)


def test_sampled_motion_says_when_lsoda_cannot_start():
    """A load far beyond the pendulum's scale: LSODA refuses its first step ("Illegal input
    detected (internal error)" in odeint's words), said in the pendulum's."""
    with pytest.raises(ConvergenceError, match="LSODA refused its start"):
        dy.sampled_motion(SEC29, 1e150, [0.5, -0.5, 0.0, 0.0], [0.0, 1.0])


def test_sampled_motion_says_when_the_state_turns_non_finite(monkeypatch):
    """odeint reports a motion that turned NaN as a success: the samples are checked."""
    original = ZieglerPendulum.motion_at

    def turning_nan(self, P=0.0, H=0.0):
        f = original(self, P, H)
        return lambda t, x: f(t, x) if t < 3.0 else np.full(4, np.nan)

    monkeypatch.setattr(ZieglerPendulum, "motion_at", turning_nan)
    with pytest.raises(ConvergenceError, match="the state became non-finite"):
        dy.sampled_motion(SEC29, 1.0, [0.1, 0.1, 0.0, 0.0], np.linspace(0.0, 1.0, 11))


def test_sampled_motion_says_when_the_motion_outruns_its_step_bound():
    """A pendulum moving far faster than its time unit (1e8 N on §2.9's): more than the step
    bound within one time unit, said so (odeint's "Excess work done ... Dfun type")."""
    with pytest.raises(ConvergenceError, match="more than 5000 steps within one time unit"):
        dy.sampled_motion(SEC29, 1e8, [0.5, -0.5, 0.0, 0.0], [0.0, 1.0])


def test_the_jacobian_refuses_a_state_beyond_the_double_range():
    """An outside review: velocities of 1e200 rad/s raised Python's OverflowError."""
    with pytest.raises(ParameterError, match="Jacobian of the equations of motion leaves"):
        dy.jacobian(SEC29, [0.0, 0.0, 1e200, 0.0], 1.0)


@pytest.fixture(scope="module")
def cycle():
    eps, _ = viscosity_groups(SEC29)
    P = 1.5 * eq54_flutter_gamma(eps) * SEC29.load_unit
    return P, dy.limit_cycle(SEC29, P, np.radians([0.1, 0.1, 0, 0]))


def test_limit_cycle_two_methods(cycle):
    P, lc = cycle
    shot = dy.shoot_periodic_orbit(SEC29, P, lc)
    assert lc.period_s == pytest.approx(shot.period_s, rel=1e-8)
    assert lc.alpha1_amplitude_rad == pytest.approx(shot.alpha1_amplitude_rad, rel=1e-8)
    assert lc.alpha2_amplitude_rad == pytest.approx(shot.alpha2_amplitude_rad, rel=1e-7)


def test_limit_cycle_independent_of_integrator(cycle):
    """A second integrator (LSODA with the analytic Jacobian) finds the same orbit."""
    P, lc = cycle
    other = dy.limit_cycle(SEC29, P, np.radians([0.1, 0.1, 0, 0]), method="LSODA",
                           rtol=1e-11, atol=1e-13, tol=1e-7)
    assert other.period_s == pytest.approx(lc.period_s, rel=1e-6)


def test_limit_cycle_is_attracting_from_other_initial_conditions(cycle):
    P, lc = cycle
    other = dy.limit_cycle(SEC29, P, [0.0, 0.0, 0.5, 0.5])
    assert other.period_s == pytest.approx(lc.period_s, rel=1e-7)


def test_no_limit_cycle_below_flutter():
    P = 0.9 * damped_flutter_load(SEC29)
    with pytest.raises(ConvergenceError):
        dy.limit_cycle(SEC29, P, np.radians([0.1, 0.1, 0, 0]), t_max=30.0)


def test_simulate_rejects_bad_input():
    with pytest.raises(ParameterError, match="state0"):
        dy.simulate(SEC29, 1.0, [0.0, 0.0], 1.0)
    with pytest.raises(ParameterError, match="t_end"):
        dy.simulate(SEC29, 1.0, [0.0] * 4, -1.0)
    with pytest.raises(ParameterError, match="P"):
        dy.simulate(SEC29, math.nan, [0.0] * 4, 1.0)
    # an infinite or astronomically long motion ran until killed (an outside audit)
    with pytest.raises(ParameterError, match="t_end must be finite"):
        dy.simulate(SEC29, 3.0, [0.01, 0.0, 0.0, 0.0], math.inf)
    with pytest.raises(ParameterError,
                       match=r"t_end must be in \(0, 1.029e\+04\] s \(100000 time "):
        dy.simulate(SEC29, 3.0, [0.01, 0.0, 0.0, 0.0], 1e9)


def test_tip_acceleration_is_second_derivative_of_position():
    P = 3.0
    t = np.linspace(0, 0.5, 5001)
    sol = dy.simulate(SEC29, P, [0.3, -0.2, 0.0, 1.0], 0.5, t_eval=t)
    C = SEC29.positions(sol.y[0], sol.y[1])["C"]
    fd = np.gradient(np.gradient(C, t, axis=0), t, axis=0)
    acc = dy.tip_acceleration(SEC29, sol.y.T, P)
    assert np.allclose(acc[10:-10], fd[10:-10], rtol=1e-3, atol=1e-3 * np.abs(acc).max())


def test_an_integration_started_on_the_section_never_trips_the_event_search():
    """A start on the section (its value a rounding-level residue of either sign): the event
    is 0 at the start, the section's own value after, with its direction; scipy then finds the
    next crossing whatever the residue's sign (it raised when the residue's sign was not
    reproduced by the dense output)."""
    from scipy.integrate import solve_ivp

    from flutterfriction.analysis.events import from_the_section

    event = from_the_section(lambda t, y: y[1])
    assert event.direction == -1.0
    assert event(0.0, np.array([1.0, 1e-17])) == 0.0
    assert event(0.5, np.array([1.0, -0.25])) == -0.25
    for residue in (1e-17, -1e-17, 0.0):  # y = (cos t, -sin t): y[1] falls through 0 at pi
        sol = solve_ivp(lambda t, y: [y[1], -y[0]], (0.0, 7.0), [-1.0, residue],
                        method="LSODA", rtol=1e-8, atol=1e-10, events=event)
        later = [t for t in sol.t_events[0] if t > 1.0]
        assert later and abs(later[0] - math.pi) < 1e-6


# An outside audit's independent references (its own Lagrange equations, transients and
# Newton shooting with the variational equations, closed to 5e-13).
_D5 = dict(l1=0.2, l2=0.4, d=0.05, h=0.2, m1=3, m2=0.05, m3=0, k1=0.5, k2=0.3, c1=0.01,
           c2=0.02)
_D8 = dict(l1=1, l2=1, d=1, h=0, m1=1, m2=1, m3=0, k1=1, k2=1, c1=0.5, c2=0.05)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_limit_cycle_with_several_maxima_of_alpha1_per_period():
    """D8 at 2.3 P_flu: a stable cycle with more than one maximum of alpha1 per period was
    refused (only consecutive section crossings were compared); the section-return check took
    the first crossing after half a period (27 % short on D8 at 1.5 P_flu)."""
    p = ZieglerPendulum(**_D8)
    r = dy.ziegler_limit_cycle(p, 4.517234848484848, 0.1)
    assert r["period_s"] == pytest.approx(5.431477299, rel=1e-9)
    assert r["alpha1_amplitude_rad"] == pytest.approx(0.3488657891, rel=1e-9)
    assert r["alpha2_amplitude_rad"] == pytest.approx(2.704009697, rel=1e-9)
    lc = dy.limit_cycle(p, 2.9460227272727275, [0.1, 0.1, 0.0, 0.0])
    t, _ = dy.section_return(p, 2.9460227272727275, lc.section_state, lc.period_s)
    assert lc.period_s == pytest.approx(6.2622976, rel=1e-7)
    assert t == pytest.approx(lc.period_s, rel=1e-8)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_limit_cycle_stops_on_the_distance_left_not_on_the_last_step():
    """Near the Hopf point the cycle attracts slowly (ratio 0.983 per period at 1.01 P_flu):
    stopping when successive crossings differ by tol left 60 tol (4.6e-6 at tol 1e-7)."""
    p = ZieglerPendulum(**_D5)
    lc = dy.limit_cycle(p, 1.01 * damped_flutter_load(p), [0.3, 0.3, 0.0, 0.0], tol=1e-7,
                        t_max=5000.0)
    assert lc.alpha1_amplitude_rad == pytest.approx(0.1138763729, rel=5e-7)


def _slower(p: ZieglerPendulum, s: float) -> ZieglerPendulum:
    """The same pendulum with its motions ``s`` times slower (masses x s^2, viscosities x s)."""
    return ZieglerPendulum(**{**{k: getattr(p, k) for k in _PENDULUM_KEYS},
                              "m1": p.m1 * s**2, "m2": p.m2 * s**2, "m3": p.m3 * s**2,
                              "c1": p.c1 * s, "c2": p.c2 * s})


_PENDULUM_KEYS = ("l1", "l2", "d", "h", "m1", "m2", "m3", "k1", "k2", "c1", "c2")


@pytest.mark.parametrize("s", [1e-4, 100.0])
def test_transient_and_shooting_do_not_depend_on_the_unit_of_time(cycle, s):
    """``limit_cycle`` and ``shoot_periodic_orbit`` run in the pendulum's time unit: the same
    orbit, ``s`` times slower, at the same cost. In seconds, the 100x slower pendulum was
    refused (600 s simulated = 120 tau) and the 1e-4 one integrated 20 s chunks of 18000
    periods between two checks of the step bound."""
    P, lc = cycle
    slow = _slower(SEC29, s)
    other = dy.limit_cycle(slow, P, np.radians([0.1, 0.1, 0, 0]))
    assert other.period_s == pytest.approx(s * lc.period_s, rel=1e-8)
    assert other.alpha1_amplitude_rad == pytest.approx(lc.alpha1_amplitude_rad, rel=1e-7)
    assert other.transient_s == pytest.approx(s * lc.transient_s, rel=1e-6)
    assert other.section_state[3] == pytest.approx(lc.section_state[3] / s, rel=1e-6)
    shot = dy.shoot_periodic_orbit(slow, P, other)
    assert shot.period_s == pytest.approx(s * lc.period_s, rel=1e-8)


@pytest.mark.slow  # > 4 s on a 2-core AMD EPYC host (2026-11-29)
def test_bifurcation_diagram_does_not_depend_on_the_unit_of_time():
    """The pendulum's bifurcation-diagram scene (limit_cycle_amplitude) for the §2.9 pendulum
    and the same pendulum 100x slower: the same amplitudes, periods x 100, the same verdict.
    Its decay test ran 400 s whatever the pendulum: 100x slower, the envelope had not halved
    and the scene reported 'subcritical?'."""
    from flutterfriction.scenes.ziegler_nonlinear import limit_cycle_amplitude

    def diagram(p):
        keys = {k: getattr(p, k) for k in _PENDULUM_KEYS}
        return limit_cycle_amplitude({"pendulum": keys, "load_factors": [1.05, 1.2, 1.5],
                                      "tol": 1e-6})

    ref, slow = diagram(SEC29), diagram(_slower(SEC29, 100.0))
    assert slow["alpha1_amplitude"] == pytest.approx(ref["alpha1_amplitude"], rel=1e-5)
    assert slow["period"] == pytest.approx([100 * t for t in ref["period"]], rel=1e-6)
    assert slow["quantities"]["hopf_type"]["value"] == "supercritical"
    assert slow["below"]["envelope_last"] == pytest.approx(ref["below"]["envelope_last"],
                                                           rel=1e-6)


def test_section29_cycle_load_is_a_multiple_of_the_pendulums_own_flutter_load():
    """An outside audit: Figs. 13-14 took P*_flu from eq. (54) for any pendulum, but eq. (54)
    is the symmetric pendulum's closed form: with c1 = 2 c2, 1.2 x eq. 54 = 3.13 N lies below
    the true damped flutter load 3.24 N (stable: the scene died), and with l2 = 0.12 m the
    figure's "1.5 P*_flu" was 1.62 P_flu. Now the exact damped flutter load (Routh-Hurwitz),
    equal to eq. (54) for §2.9's pendulum."""
    from flutterfriction.analysis.ziegler import damped_flutter_load
    from flutterfriction.closed_forms.ziegler_damped import eq54_flutter_gamma, viscosity_groups
    from flutterfriction.config import load_config, scene_params
    from flutterfriction.scenes.common import pendulum_of
    from flutterfriction.scenes.ziegler_nonlinear import damped_flutter_load_star, fig13

    params = scene_params(load_config(ROOT / "workflow" / "config.yaml"), "fig13")
    p = pendulum_of(params)
    star, is_eq54 = damped_flutter_load_star(p)
    assert is_eq54 and star == pytest.approx(
        eq54_flutter_gamma(viscosity_groups(p)[0]) * p.load_unit, rel=1e-12)
    own = {**params, "pendulum": {**p.as_dict(), "c1": 2 * p.c1}, "load_factor": 1.2,
           "tol": 1e-6, "n_samples": 200}
    d = fig13(own)
    exact = damped_flutter_load(pendulum_of(own), "routh")
    assert d["P_star_flu"] == pytest.approx(exact, rel=1e-12) and not d["P_star_is_eq54"]
    assert d["P"] == pytest.approx(1.2 * exact, rel=1e-12)
    assert d["limit_cycle"]["alpha1_amplitude_rad"] > 0


@pytest.mark.parametrize("factor, amplitude, period", [(1.03, 0.255, 1.10917),
                                                       (1.05, 0.326, 1.10247)])
def test_cycles_near_onset_are_answered(factor, amplitude, period):
    """An outside audit: at 1.05 P_flu of the §2.9 pendulum (and at 1.03 with other start
    values) the continuation was refused ("not making good progress") on a shooting residual
    of 6e-16: hybr's success flag was taken over the residual. References: the auditor's own
    shooting (separate Lagrangian equations, DOP853 at rtol 1e-13): the section point
    alpha1 = 0.255 rad lies on the cycle of 1.03002 P_flu with T = 1.10917 s, and 0.326 rad on
    that of 1.04991 P_flu with T = 1.10247 s (digits as given). Tolerances: those digits plus
    the loads' offsets, 2e-5 and 9e-5 P_flu (between the two references dT/dP = -0.34 s and
    dA/dP = 3.6 rad per P_flu: at most 3e-5 s and 3.3e-4 rad)."""
    from flutterfriction.analysis.dynamics import ziegler_limit_cycle

    P_flu = damped_flutter_load(SEC29)
    cycle = ziegler_limit_cycle(SEC29, factor * P_flu, 0.1)
    assert cycle["alpha1_amplitude_rad"] == pytest.approx(amplitude, abs=1e-3)
    assert cycle["period_s"] == pytest.approx(period, abs=5e-5)


def test_amplitude_shooting_refuses_a_period_shrinking_to_zero():
    """A review: the shooting residual phi_T(x0) - x0 vanishes as T -> 0, so from a poor
    period guess hybr converged to T = 6.7e-18 T0, which the residual test alone accepted.
    Periods below 1/8 of the linear flutter period are now outside the search (the §2.9
    cycles stay above 0.75 of it); from the linear period the orbit is found as before."""
    P_flu = damped_flutter_load(SEC29)
    omega, mode = dy.linear_flutter_mode(SEC29, P_flu)
    T0, A = 2 * np.pi / omega, 0.2
    bounds = (1e-12, 1e-14, 4 * T0, 6 * P_flu)
    for guess in (0.02, 0.1):
        with pytest.raises(ConvergenceError):
            dy._amplitude_orbit(SEC29, A, np.array([A * mode[1], A * mode[3], guess * T0,
                                                    P_flu]), *bounds)
    z = dy._amplitude_orbit(SEC29, A, np.array([A * mode[1], A * mode[3], T0, P_flu]), *bounds)
    assert 0.9 * T0 < z[2] < T0 and z[3] > P_flu


def test_figs_13_and_14_compute_their_motion_once_per_parameters():
    """Figs. 13 and 14 show the same motion (the issue: "Figs. 13 and 14 solve the same cycle
    twice"): the second scene reuses the first's, in a copy (Fig. 13 drops the velocities from
    its own), and other parameters are computed anew."""
    from flutterfriction.scenes import ziegler_nonlinear as zn

    params = {"pendulum": SEC29.as_dict(), "load_factor": 1.5, "alpha0_deg": 0.1,
              "tol": 1e-6, "n_samples": 50}
    d13 = zn.fig13(params)
    calls = []
    original = zn._compute_cycle
    zn._compute_cycle = lambda prm: calls.append(prm) or original(prm)
    try:
        d14 = zn.fig14(params)
        assert not calls and "alpha_dot" not in d13 and len(d14["alpha_dot"]) == 2
        assert d14["alpha"] == d13["alpha"] and d14["quantities"] == d13["quantities"]
        d14["alpha"][0][0] = 99.0  # a scene's change stays in its own copy
        assert zn.fig14(params)["alpha"][0][0] == d13["alpha"][0][0] != 99.0
        other = zn.fig14({**params, "load_factor": 1.4})
        assert len(calls) == 1 and other["P"] == pytest.approx(d13["P"] * 1.4 / 1.5, rel=1e-12)
    finally:
        zn._compute_cycle = original


@pytest.mark.slow  # ~13 s: the transient is tried first (12000 tau simulated)
def test_a_pendulum_damped_at_one_hinge_only_is_answered_or_refused_quickly():
    """An outside audit: c1 > 0, c2 = 0 (allowed: "c1 or c2 > 0") hung limit-cycle ziegler
    (its flutter mode barely moves alpha1: alpha2/alpha1 ~ 2e12 made a start state that
    integrated for minutes), and P*_flu of Figs. 13-14 raised on eq. (54)'s groups although the
    exact load was known. Now one line, exit 1, within seconds; and P*_flu is the exact one."""
    import subprocess
    import sys

    from flutterfriction.analysis.ziegler import damped_flutter_load
    from flutterfriction.scenes.ziegler_nonlinear import damped_flutter_load_star

    proc = subprocess.run(
        [sys.executable, "-m", "flutterfriction", "limit-cycle", "ziegler", "--l1", "1",
         "--l2", "1", "--d", "1", "--h", "0", "--m1", "2", "--m2", "1", "--m3", "0", "--k1",
         "1", "--k2", "1", "--c1", "0.01", "--c2", "0", "--P", "3", "--json"],
        capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr
    assert "barely moves alpha1" in proc.stderr
    p = ZieglerPendulum(l1=1, l2=1, d=1, h=0, m1=2, m2=1, m3=0, k1=1, k2=1, c1=0.01, c2=0.0)
    star, is_eq54 = damped_flutter_load_star(p)
    assert star == pytest.approx(damped_flutter_load(p, "routh"), rel=1e-14) and not is_eq54


def test_shooting_that_stalls_at_round_off_is_a_solution():
    """An outside audit's own pendulum at 1.5 P_flu: MINPACK stopped with "not making good
    progress" at a residual of 5e-16 (its xtol 1e-13 out of reach of the integration), and
    Figs. 13-14 failed. The orbit is the auditor's (their DOP853 integration of eq. (10) with
    the viscous terms, rtol 1e-12, 250 s: alpha1 0.8520107938819 rad, T 0.9430458153929 s;
    agreement 5e-12, tolerance 1e-10 relative)."""
    p = ZieglerPendulum(l1=0.2, l2=0.15, d=0.2, h=0.05, m1=0.3, m2=0.1, m3=0.05, k1=0.5,
                        k2=0.3, c1=0.004, c2=0.002)
    P = 1.5 * damped_flutter_load(p, "routh")
    a0 = np.radians(0.1)
    cycle = dy.limit_cycle(p, P, np.array([a0, a0, 0.0, 0.0]), tol=1e-8)
    shot = dy.shoot_periodic_orbit(p, P, cycle)
    assert shot.alpha1_amplitude_rad == pytest.approx(0.8520107938819, rel=1e-10)
    assert shot.period_s == pytest.approx(0.9430458153929, rel=1e-10)
