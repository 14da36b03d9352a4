"""Limit cycle of the nonlinear Beck/Pflüger rod (chapter §2.9, Figs. 15–17).

Time integration of :class:`~flutterfriction.models.rod_nonlinear.NonlinearRod` with an implicit
scipy integrator (the Kelvin–Voigt term makes the system stiff); the cycle is detected on the
Poincaré section "lateral tip velocity = 0, tip on the positive side", and accepted when the
tip amplitude and the period of successive crossings agree to ``tol``. On the converged cycle
the work of the follower force per period must equal the viscous dissipation (energy check).
Only the tip's history is stored (what the figures draw).
"""

from __future__ import annotations

import bisect
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from flutterfriction.analysis.quadrature import integrate_vectorised
from flutterfriction.analysis.rod_cycles import (
    Floquet,
    _gradient,
    floquet,
    linearised_flutter_load,
    sampled_peak,
    section_value,
    tip_lateral,
    variational_flow,
)
from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_integer,
    check_positive,
    check_real,
)
from flutterfriction.models.rod import (
    CYCLE_LOAD_MAX,
    CYCLE_T_MAX_DEFAULT_SCALES,
    CYCLE_T_MAX_SCALES,
    Rod,
)
from flutterfriction.models.rod_nonlinear import NonlinearRod, prolongation


@dataclass
class RodLimitCycle:
    tip_amplitude_m: float  # half the peak-to-peak lateral tip displacement on the cycle
    period_s: float
    tip_rotation_amplitude_rad: float
    work_follower_J: float  # per period, on the cycle
    work_dissipated_J: float
    energy_balance_error: float  # |W_P - W_D| / W_D
    transient_s: float
    wall_s: float
    n_rhs: int
    section: list = field(default_factory=list, repr=False)  # (t, u2) at the crossings
    history: dict = field(default_factory=dict, repr=False)
    final_state: list = field(default_factory=list, repr=False)
    shapes: list = field(default_factory=list, repr=False)  # the rod over one period (GIF)

    def as_dict(self, with_history: bool = False) -> dict:
        d = asdict(self)
        d.pop("final_state")
        if not with_history:
            d.pop("shapes")
        if not with_history:
            d.pop("history")
        return d


def tip_state(model: NonlinearRod, y: NDArray) -> NDArray:
    n = model.n_dof
    q, v = y[:n], y[n:]
    _, _, _, G_tip = model.kinematics(q)
    x_tip = model.tip_position(q)
    return np.array([x_tip[0] - model.rod.length, x_tip[1], *(G_tip @ v)])


def exact_jacobian(model: NonlinearRod, P: float, method: str) -> dict:
    """``solve_ivp`` options giving the implicit integrators (BDF, Radau, LSODA) the exact
    Jacobian of the rod's right-hand side (compiled, :meth:`NonlinearRod.jacobians`; equal to
    the complex steps of :func:`~flutterfriction.analysis.rod_cycles.rhs_derivatives`)
    instead of their finite differences; none for the explicit ones."""
    if method not in ("BDF", "Radau", "LSODA"):
        return {}
    return {"jac": lambda t, y: model.jacobians(y[:, None], P)[0][0]}


#: scipy's integrators (solve_ivp's methods)
_METHODS = frozenset({"RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA"})


#: Largest number of section crossings (positive maxima of the lateral tip displacement) per
#: period that :func:`beck_limit_cycle` recognises (an outside audit found two, of different
#: heights, at eta = 0.1 and 2.9 P_flu).
MAX_MAXIMA_PER_PERIOD = 4
#: :func:`beck_limit_cycle`'s default bound on simulated time, in time scales l^2 sqrt(rho/B).
DEFAULT_T_MAX_SCALES = CYCLE_T_MAX_DEFAULT_SCALES


def _repeating_lag(crossings: list) -> int | None:
    """The smallest lag ``m`` at which the last section crossings' amplitudes nearly repeat
    (four crossings of one phase within 1e-3 of each other), None if none does yet."""
    for m in range(1, MAX_MAXIMA_PER_PERIOD + 1):
        if len(crossings) < 3 * m + 1:
            return None
        us = np.array([c[1] for c in crossings[-1::-m][:4]])
        if np.ptp(us) <= 1e-3 * abs(us[0]):
            return m
    return None


def _refined_peak(f: Callable[[float], float], tt: NDArray, samples: NDArray) -> float:
    """The maximum of ``f`` over ``[tt[0], tt[-1]]``: the largest sample, refined by a bounded
    search between its neighbours (the sampled maximum alone is low by ~(pi/N)^2/2 of the
    amplitude on N samples per period)."""
    from scipy.optimize import minimize_scalar

    k = int(np.argmax(samples))
    lo, hi = tt[max(k - 1, 0)], tt[min(k + 1, len(tt) - 1)]
    res = minimize_scalar(lambda t: -f(t), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-12 * (tt[-1] - tt[0])})
    return float(max(samples[k], -res.fun))


def _works_over(model: NonlinearRod, states_at: Callable[[NDArray], NDArray], t0: float,
                T: float, P: float) -> tuple[float, float]:
    """Work of the follower force and energy dissipated over ``[t0, t0 + T]`` [J]: adaptive
    quadrature of the powers on the dense output ``states_at(t) -> (2 n_dof, m)``, to 1e-10
    relative, every pass's states in one call (:func:`~flutterfriction.analysis.quadrature.
    integrate_vectorised`; scipy's ``quad_vec`` took them one at a time, ~70 % of a cycle's
    measures). (A fixed 200-sample trapezoid reported 0.155 and 0.314 J, an energy balance
    error of 0.51, for a cycle whose works are both 0.2119 J: its dissipation is impulsive,
    peaks of 210 times the mean; found by an outside audit.)"""
    n = model.n_dof

    def powers(t: NDArray) -> NDArray:
        s = states_at(t)
        return np.array(model.power_balance(s[:n], s[n:], P))

    works, _ = integrate_vectorised(powers, t0, t0 + T, epsrel=1e-10)
    return float(works[0]), float(works[1])


def beck_limit_cycle(rod: Rod, P: float, n_elements: int = 8, method: str = "BDF",
                     rtol: float = 1e-7, atol: float = 1e-9, tol: float = 1e-4,
                     t_max: float | None = None, initial_tip_rotation: float = 0.05,
                     samples_per_period: int = 200,
                     start: tuple[NonlinearRod, NDArray] | None = None,
                     progress: Callable[[str], None] | None = None) -> RodLimitCycle:
    """Integrate from a small bend (tip rotation ``initial_tip_rotation`` rad, linear in s), or
    from ``start`` (a state of another mesh, interpolated: mesh continuation), until the limit
    cycle converges to ``tol``; returns its measures and the tip's history.

    Convergence is tested at every crossing of the Poincaré section: the last three periods
    and four tip amplitudes agree to ``tol``, and so would the limit of the sequence (its
    geometric tail
    ``|d_k| mu / (1 - mu)``, ``mu`` the observed contraction), which matters where the
    approach is slow (near the flutter load the growth rate is tiny: 0.021 1/s at 1.1 times
    the damped flutter load of list (119), so transients there last minutes). A cycle may
    cross the section (a positive maximum of the lateral tip displacement) up to
    :data:`MAX_MAXIMA_PER_PERIOD` times per period: the crossings are compared at the
    smallest lag at which they nearly repeat (1e-3), so a cycle with two maxima of different
    heights per period (eta = 0.1 at 2.9 P_flu, found by an outside audit) is recognised.

    ``t_max`` [s] bounds the simulated time (default 200 time scales ``l^2 sqrt(rho/B)``,
    31.4 s for list 119: in the rod's own time, so that the same rod in other units gets the
    same bound). The measures are taken on the last period: the largest lateral tip
    displacement from the section crossings themselves, the smallest and the tip rotation
    refined from ``samples_per_period`` samples by a bounded search on the dense output, and
    the works by adaptive quadrature (:func:`_works_over`).

    ``progress(message)``, if given, hears of every section crossing (simulated time, tip
    amplitude, the relative changes tested against ``tol``); it never changes the result."""
    if not check_real("P", P) > 0:
        raise ParameterError(f"P must be > 0, got {P}")
    if method not in _METHODS:
        raise ParameterError(f"method must be one of {sorted(_METHODS)}, got {method!r}")
    if t_max is None:
        t_max = DEFAULT_T_MAX_SCALES * rod.time_scale
    for name, value in (("rtol", rtol), ("atol", atol), ("tol", tol), ("t_max", t_max)):
        if not check_real(name, value) > 0:
            raise ParameterError(f"{name} must be > 0, got {value!r}")
    # as the command line bounds them (an outside audit: a tip rotation of 1e6 rad, or
    # 1e300, integrated until killed; t_max had no upper bound here)
    t_limit = CYCLE_T_MAX_SCALES * rod.time_scale
    if not t_max <= t_limit:
        raise ParameterError(f"t_max must be in (0, {t_limit:.4g}] s ({CYCLE_T_MAX_SCALES:g} "
                             f"time scales l^2 sqrt(rho/B)), got {t_max!r}")
    if not 0 < abs(check_real("initial_tip_rotation", initial_tip_rotation)) <= np.pi:
        raise ParameterError(f"initial_tip_rotation must be non-zero and within half a turn "
                             f"(0 < |rotation| <= pi rad), got {initial_tip_rotation!r}")
    check_integer("samples_per_period", samples_per_period, 2)
    model = NonlinearRod(rod, n_elements)
    # The load where a cycle exists and is reached in reasonable time, as the scene and the
    # command line check it (an outside audit: 30 N on list 119 ran for minutes here)
    check_cycle_load(rod, P, n_elements)
    n = model.n_dof
    y = np.zeros(2 * n)
    y[:n] = initial_tip_rotation * np.linspace(0, 1, n + 1)[1:]
    if start is not None:
        coarse, yc = start
        nodes = np.linspace(0.0, rod.length, n + 1)[1:]
        y[:n] = coarse.nodal_values_at(yc[:coarse.n_dof], nodes)
        y[n:] = coarse.nodal_values_at(yc[coarse.n_dof:], nodes)
    counter = {"rhs": 0}

    one_state = model.rhs_at(P)  # the compiled kernel, its arguments bound once

    def rhs(t, z):
        counter["rhs"] += 1
        return one_state(t, z)

    def section(t, z):  # lateral tip velocity; -1: at the maximum of the lateral displacement
        return section_value(model, z)

    section.direction = -1.0
    t_begin = time.perf_counter()
    options = exact_jacobian(model, P, method)
    t0, crossings, chunks = 0.0, [], []
    chunk = 6 * rod.time_scale  # several first-mode periods, until the period is measured
    converged = False
    while t0 < t_max and not converged:
        sol = solve_ivp(rhs, (t0, min(t0 + chunk, t_max)), y, method=method, rtol=rtol,
                        atol=atol, events=section, dense_output=True, **options)
        if not sol.success:
            raise ConvergenceError(f"rod integration failed after t = {t0:.4g} s: "
                                   f"{sol.message}")
        chunks.append(sol)
        for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
            if tip_state(model, ye)[1] <= 0:
                continue
            crossings.append((float(te), float(tip_state(model, ye)[1]), ye.copy()))
            chunk = 4 * (crossings[-1][0] - crossings[-2][0]) if len(crossings) > 1 else chunk
            found = _repeating_lag(crossings)
            if found is None and len(crossings) < 4:
                continue
            # Four crossings of one phase: three periods and four amplitudes agree to tol
            # (after a mesh change the sequence beats, and two agreeing crossings can be a
            # coincidence), and the geometric tail of a steadily contracting sequence is below
            # tol too. Until the crossings repeat at some lag, consecutive ones are reported
            # (the progress lines) but never taken for a cycle.
            lag = found or 1
            phase = crossings[-1::-lag][:4][::-1]
            ts = np.array([c[0] for c in phase])
            us = np.array([c[1] for c in phase])
            periods = np.diff(ts)
            d_c, d_b = us[-1] - us[-2], us[-2] - us[-3]
            mu = d_c / d_b if d_b != 0 else 0.0
            tail = abs(d_c) * mu / (1 - mu) if 0 < mu < 1 else 0.0
            if progress:
                progress(f"rod, {n_elements} elements, P = {P:g} N: t = {te:.3f} s, tip "
                         f"amplitude {us[-1]:.5f} m, period spread "
                         f"{np.ptp(periods) / periods[-1]:.1e}, amplitude spread "
                         f"{np.ptp(us) / us[-1]:.1e}, tail {tail / us[-1]:.1e} "
                         f"(converged below {tol:g})"
                         + (f"; {lag} maxima per period" if lag > 1 else ""))
            if (found is not None and np.ptp(periods) <= tol * periods[-1]
                    and np.ptp(us) <= tol * us[-1] and tail <= tol * us[-1] and mu < 1):
                converged = True
                break
        y, t0 = sol.y[:, -1], sol.t[-1]
    if not converged:
        raise ConvergenceError(f"no rod limit cycle converged to {tol:g} within {t_max} s "
                               f"(P = {P} N; below the flutter load the motion decays)")
    T = crossings[-1][0] - crossings[-1 - lag][0]
    t_end = crossings[-1][0]
    wall = time.perf_counter() - t_begin

    ends = [float(c.t[-1]) for c in chunks]

    def state_at(t):
        # The first piece that holds t (a binary search over the pieces' ends: the scan over
        # every piece made the tip's history quadratic in the number of periods, ~200 s of a
        # long run's post-processing, measured by an outside audit).
        i = bisect.bisect_left(ends, t)
        if i < len(chunks) and chunks[i].t[0] <= t:
            return chunks[i].sol(t)
        return chunks[-1].sol(min(t, chunks[-1].t[-1]))

    def states_at(tt: NDArray) -> NDArray:
        # state_at at many instants: each piece's dense output called once on its instants
        tt = np.asarray(tt, dtype=float)
        piece = np.minimum(np.searchsorted(ends, tt, side="left"), len(chunks) - 1)
        out = np.empty((y.size, tt.size))
        for i in np.unique(piece):
            sel = piece == i
            out[:, sel] = chunks[i].sol(np.minimum(tt[sel], ends[i]))
        return out

    # Measures on the last period.
    tt = np.linspace(t_end - T, t_end, samples_per_period + 1)
    states = np.array([state_at(t) for t in tt])
    tips = np.array([tip_state(model, s) for s in states])
    u_max = max(c[1] for c in crossings[-lag:])  # the section's maxima, exact
    u_min = -_refined_peak(lambda t: -tip_state(model, state_at(t))[1], tt, -tips[:, 1])
    rot = np.abs(states[:, n - 1])
    rotation = _refined_peak(lambda t: abs(state_at(t)[n - 1]), tt, rot)
    W_P, W_D = _works_over(model, states_at, t_end - T, T, P)
    # The rod's shape at 41 instants of the last period (for the animation only).
    shapes = []
    for s_ in states[:: max(1, samples_per_period // 40)]:
        theta = model.phi @ s_[:n]
        x_q, x_tip = model._cumint(np.stack([np.cos(theta), np.sin(theta)], axis=-1))
        shape = np.vstack([[0.0, 0.0], x_q, x_tip])
        shapes.append(shape.round(6).tolist())
    # History of the tip for the figures: the whole transient, 100 points per period.
    th = np.linspace(0.0, t_end, max(200, int(100 * t_end / T)))
    hist = np.array([tip_state(model, state_at(t)) for t in th])
    return RodLimitCycle(
        tip_amplitude_m=float(0.5 * (u_max - u_min)), period_s=float(T),
        tip_rotation_amplitude_rad=rotation,
        work_follower_J=W_P, work_dissipated_J=W_D,
        energy_balance_error=abs(W_P - W_D) / W_D, transient_s=t_end, wall_s=wall,
        n_rhs=counter["rhs"],
        section=[[c[0], c[1]] for c in crossings],
        history={"t": th.tolist(), "u1": hist[:, 0].tolist(), "u2": hist[:, 1].tolist(),
                 "u1_dot": hist[:, 2].tolist(), "u2_dot": hist[:, 3].tolist()},
        final_state=state_at(t_end).tolist(), shapes=shapes)


def generalized_alpha(model: NonlinearRod, P: float, y0: NDArray, t_end: float, dt: float,
                      rho_inf: float = 0.8, newton_tol: float = 1e-8,
                      sample_every: int = 1) -> tuple[NDArray, NDArray, int]:
    """Generalized-alpha integration (Chung–Hulbert's parameters, the ABAQUS-style structural
    choice: second order, high-frequency dissipation set by ``rho_inf``) of
    ``M(q) q_ddot + g(q, v) = 0`` (``g = h(q, v) + K q + C v - F(q)``, ``h`` the centripetal
    term), in the form of Arnold & Brüls (2007) for nonlinear problems: the equation of motion
    holds at every step with the true acceleration ``q_ddot_{n+1}``, and the Newmark updates
    use the auxiliary acceleration ``a``,

        (1 - am) a_{n+1} + am a_n = (1 - af) q_ddot_{n+1} + af q_ddot_n,   a_0 = q_ddot_0,

    ``gamma = 1/2 - am + af``, ``beta = (1 - am + af)^2 / 4``. Newton on ``q_ddot_{n+1}``
    with a finite-difference Jacobian reused across steps while Newton converges. Returns
    sampled times, states and the number of model evaluations.

    Why this form: Chung and Hulbert's own, ``(1 - am) M(q_{n+1}) a_{n+1} + am M(q_n) a_n +
    (1 - af) g_{n+1} + af g_n = 0``, is second order for a constant mass matrix only: ``a_n``
    approximates the acceleration at ``t_n + (am - af) dt`` but multiplies ``M(q_n)``, an
    O(dt) inconsistency when the mass matrix depends on the configuration, as the
    geometrically exact rod's does. Measured (4 elements, list 119, 5.5 N, 0.1 s from a large
    bend, against DOP853 at rtol 1e-12): that form converged at first order for rho_inf < 1
    (errors halving with dt; second order only at rho_inf = 1, the trapezoidal rule); this
    one at second order (``tests/test_rod_nonlinear.py``)."""
    n = model.n_dof
    # (an outside audit: dt = 0 and rho_inf = -1 divided by zero, dt = NaN raised numpy's
    # ValueError, dt > t_end returned the initial state alone)
    check_real("P", P)
    y0 = check_finite_array("y0", y0, (2 * n,), f"a finite state of {2 * n} values (q, v)")
    t_end = check_positive("t_end", t_end, "s")
    dt = check_positive("dt", dt, "s")
    if dt > t_end:
        raise ParameterError(f"dt must be in (0, t_end] = (0, {t_end:g}] s, got {dt:g}")
    if not 0.0 <= check_real("rho_inf", rho_inf) <= 1.0:
        raise ParameterError(f"rho_inf must be in [0, 1] (high-frequency spectral radius), "
                             f"got {rho_inf:g}")
    check_positive("newton_tol", newton_tol)
    check_integer("sample_every", sample_every, 1)
    am = (2 * rho_inf - 1) / (rho_inf + 1)
    af = rho_inf / (rho_inf + 1)
    gamma = 0.5 - am + af
    beta = 0.25 * (1 - am + af) ** 2
    count = {"n": 0}

    q, v = y0[:n].copy(), y0[n:].copy()
    acc = model.accelerations(q, v, P)  # the true acceleration q_ddot_n
    a = acc.copy()  # the auxiliary acceleration of the Newmark updates
    count["n"] += 1
    steps = int(round(t_end / dt))
    times, states = [0.0], [np.concatenate([q, v])]
    J = None

    def advance(acc_new):
        a_new = ((1 - af) * acc_new + af * acc - am * a) / (1 - am)
        qn = q + dt * v + dt**2 * ((0.5 - beta) * a + beta * a_new)
        vn = v + dt * ((1 - gamma) * a + gamma * a_new)
        return a_new, qn, vn

    terms = model.dynamic_terms_at(P)  # compiled, as the scipy integrators' right-hand side

    def residual(acc_new):
        _, qn, vn = advance(acc_new)
        count["n"] += 1
        M, g = terms(qn, vn)
        return M @ acc_new + g

    for k in range(1, steps + 1):
        acc_new = acc.copy()
        R = residual(acc_new)
        refresh = J is None
        for _it in range(40):
            if refresh:  # the Jacobian is reused across steps until Newton stops contracting
                eps = 1e-6 * max(1.0, np.abs(acc_new).max())
                J = np.column_stack([(residual(acc_new + eps * e) - R) / eps
                                     for e in np.eye(n)])
            step = np.linalg.solve(J, -R)
            acc_new = acc_new + step
            R_prev, R = R, residual(acc_new)
            refresh = np.linalg.norm(R) > 0.5 * np.linalg.norm(R_prev)
            # Converged when the update, or the residual, is at the level of round-off.
            if np.linalg.norm(step) <= newton_tol * max(1.0, np.linalg.norm(acc_new)) or \
                    np.linalg.norm(R) <= 1e-12 * max(1.0, np.linalg.norm(R_prev)):
                break
        else:
            raise ConvergenceError(f"generalized-alpha Newton did not converge at step {k}")
        a, q, v = advance(acc_new)
        acc = acc_new
        if k % sample_every == 0 or k == steps:  # the final state is always returned
            times.append(k * dt)
            states.append(np.concatenate([q, v]))
    return np.array(times), np.array(states), count["n"]


# ------------------------------------------------------------------ the cycle by shooting
@dataclass
class ShootingCycle:
    """A cycle converged by shooting on one mesh: section state ``y`` (lateral tip velocity 0,
    the tip at its positive lateral extreme), period ``T``, the orbit over one period (dense
    output of the last integration, from ``y``), the Newton corrections (relative, the largest
    over state and period) and, where the exact monodromy was computed, its Floquet data."""

    model: NonlinearRod
    y: NDArray
    T: float
    orbit: Any
    corrections: list
    integrations: int
    monodromy: NDArray | None = None  # exact, where computed
    floquet: Floquet | None = None
    secant: NDArray | None = None  # the secant-updated monodromy of the last iterate


def _period(model: NonlinearRod, y: NDArray, T: float, P: float, method: str, rtol: float,
            counter: dict | None = None):
    """One period of the orbit from ``y`` (dense output; implicit methods get the exact
    Jacobian)."""
    one_state = model.rhs_at(P)  # the compiled kernel, its arguments bound once

    def rhs(t, z):
        if counter is not None:
            counter["rhs"] += 1
        return one_state(t, z)

    sol = solve_ivp(rhs, (0.0, T), y, method=method, rtol=rtol, atol=rtol * 1e-2,
                    dense_output=True, **exact_jacobian(model, P, method))
    if not sol.success:
        raise ConvergenceError(f"rod integration over one period failed: {sol.message}")
    return sol


def _relative_correction(model: NonlinearRod, y: NDArray, T: float, dz: NDArray) -> float:
    """The Newton correction relative to the scale of each unknown (the rotations' size; the
    velocities' size or ``2 pi / T`` times it; the period), as in
    :class:`~flutterfriction.analysis.rod_cycles.PeriodicOrbitNewton`."""
    n, N = model.n_dof, y.size
    q_scale = max(np.abs(y[:n]).max(), 1e-12)
    v_scale = max(np.abs(y[n:]).max(), 2 * np.pi / T * q_scale)
    return float(max(np.abs(dz[:n]).max() / q_scale, np.abs(dz[n:N]).max() / v_scale,
                     abs(dz[N]) / T))


def _newton_step(Phi: NDArray, f_T: NDArray, section_gradient: NDArray, R: NDArray
                 ) -> NDArray:
    """The correction ``(dy, dT)`` of the periodic-orbit equations with the monodromy
    ``Phi``."""
    N = Phi.shape[0]
    J = np.zeros((N + 1, N + 1))
    J[:N, :N] = Phi - np.eye(N)
    J[:N, N] = f_T
    J[N, :N] = section_gradient
    return np.linalg.solve(J, -R)


def shoot_cycle(model: NonlinearRod, y: NDArray, T: float, P: float,
                monodromy: NDArray | None = None, method: str = "BDF", rtol: float = 1e-8,
                tol: float = 1e-6, max_iterations: int = 12, variational_rtol: float = 1e-6,
                loose_rtol: float = 1e-6, counter: dict | None = None) -> ShootingCycle:
    """Newton's method for the cycle at the load ``P``: ``phi_T(y) - y = 0`` and
    ``section(y) = 0`` for the section state ``y`` and the period ``T``.

    Every residual comes from the orbit integrated over ``T`` (``method`` at ``rtol``;
    implicit methods get the exact Jacobian of the right-hand side). The Jacobian's block
    ``d phi_T / d y`` is the expensive part. With ``monodromy=None`` it is exact: the
    variational equations (:func:`~flutterfriction.analysis.rod_cycles.variational_flow`,
    DOP853 at ``variational_rtol``: the monodromy to ~1e-7, measured at 4 elements) are
    integrated at the start and again at the iterate whose correction passes the test, which
    is then recomputed with it; so the accepted cycle has its exact monodromy and Floquet
    multipliers. In between, Broyden's secant rule updates the monodromy. Explicit DOP853 is
    limited by the Kelvin–Voigt modes' stability (their decay rate grows like ``N^4``), so
    on fine meshes pass ``monodromy``: an approximation (the coarse mesh's, prolongated) that
    starts the same secant iteration; the strongly damped modes the coarse mesh lacks have
    multipliers ~0 and are iterated like a plain period map.

    Accepted when the correction is below ``tol`` relative to each unknown's scale (the
    iterate whose residual was computed, and its orbit, are returned)."""
    n = model.n_dof
    # (an outside audit: T = -0.1 integrated backwards for minutes, T = 0 ended in a bare
    # LinAlgError)
    y = check_finite_array("y", y, (2 * n,), f"a finite state of {2 * n} values (q, v)").copy()
    N = y.size
    check_positive("T", T, "s")
    check_real("P", P)
    for name, value in (("rtol", rtol), ("tol", tol), ("variational_rtol", variational_rtol),
                        ("loose_rtol", loose_rtol)):
        check_positive(name, value)
    check_integer("max_iterations", max_iterations, 1)
    corrections: list[float] = []
    exact = monodromy is None
    Phi = None if exact else np.array(monodromy, dtype=float)
    prev = None  # (y, T, y_T, f_T) of the previous iterate, for the secant update
    for it in range(1, max_iterations + 1):
        # Inexact Newton: far from the cycle (the first iterate, or a last correction above
        # 1e-3, well above the loose integration's noise in the correction: ~1e-5 for BDF at
        # 1e-6, measured) the residual is integrated at loose_rtol; an iterate is accepted
        # only on a residual integrated at rtol.
        loose = not corrections or corrections[-1] > 1e-3
        orbit = _period(model, y, T, P, method, max(rtol, loose_rtol) if loose else rtol,
                        counter)
        y_T = orbit.y[:, -1]
        f_T = model.rhs(0.0, y_T, P)
        R = np.concatenate([y_T - y, [section_value(model, y)]])
        section_gradient = _gradient(lambda z: section_value(model, z), y)
        # The exact monodromy at the start, and again where the secant iteration stalls
        # (a correction above 0.3 times the one before).
        stalled = len(corrections) >= 2 and corrections[-1] > 0.3 * corrections[-2]
        if Phi is None or (exact and stalled):
            Phi = variational_flow(model, y, T, P, variational_rtol).Phi
        elif prev is not None and corrections[-1] > 1e-4:
            # Broyden: Phi dy ~ d(y_T) - f_T dT, in scaled states; only on steps well above
            # the integration noise (smaller ones would write the noise into Phi).
            dy, dT, dyT = y - prev[0], T - prev[1], y_T - prev[2]
            q_scale = max(np.abs(y[:n]).max(), 1e-12)
            v_scale = max(np.abs(y[n:]).max(), 2 * np.pi / T * q_scale)
            w = np.concatenate([np.full(n, q_scale), np.full(N - n, v_scale)]) ** -2
            Phi = Phi + np.outer(dyT - prev[3] * dT - Phi @ dy, w * dy) / (dy @ (w * dy))
        dz = _newton_step(Phi, f_T, section_gradient, R)
        corrections.append(_relative_correction(model, y, T, dz))
        Phi_exact = None
        if exact and corrections[-1] <= tol and not (loose and loose_rtol > rtol):
            # verify with the exact monodromy here
            Phi = Phi_exact = variational_flow(model, y, T, P, variational_rtol).Phi
            dz = _newton_step(Phi, f_T, section_gradient, R)
            corrections[-1] = _relative_correction(model, y, T, dz)
        if corrections[-1] <= tol and loose and loose_rtol > rtol:
            continue  # passed on a loose residual: integrate again at rtol, here
        if corrections[-1] <= tol:
            return ShootingCycle(model=model, y=y, T=float(T), orbit=orbit,
                                 corrections=corrections, integrations=it,
                                 monodromy=Phi_exact, secant=Phi,
                                 floquet=None if Phi_exact is None
                                 else floquet(model, y, P, Phi_exact))
        prev = (y, T, y_T, f_T)
        # Damp wild first steps: at most 5% in T.
        scale = min(1.0, 0.05 * T / max(abs(dz[N]), 1e-300))
        y, T = y + scale * dz[:N], T + scale * dz[N]
    raise ConvergenceError(f"shooting did not converge in {max_iterations} iterations "
                           f"({model.n_elements} elements, P = {P:g} N; corrections "
                           f"{', '.join(f'{c:.1e}' for c in corrections)})")


def section_crossings(model: NonlinearRod, sol) -> tuple[NDArray, NDArray]:
    """Times and states of the section crossings on the positive side (``sol`` integrated
    with ``section_value`` as its first event, direction -1)."""
    keep = [k for k, ye in enumerate(sol.y_events[0]) if tip_lateral(model, ye) > 0]
    return sol.t_events[0][keep], sol.y_events[0][keep]


def tip_states(model: NonlinearRod, Y: NDArray, batch: int = 512) -> NDArray:
    """``(u1, u2, u1_dot, u2_dot)`` of the tip for states ``Y`` of shape ``(2 n, m)``:
    ``(m, 4)``, evaluated in batches."""
    n, out = model.n_dof, []
    for k in range(0, Y.shape[1], batch):
        q, v = Y[:n, k:k + batch], Y[n:, k:k + batch]
        x_tip = model.tip_position(q)
        G_tip = model.kinematics(q)[3]
        out.append(np.column_stack([x_tip[:, 0] - model.rod.length, x_tip[:, 1],
                                    np.einsum("mcn,nm->mc", G_tip, v)]))
    return np.vstack(out)


@dataclass
class CycleMeasures:
    """What the scene reports of a converged cycle on one mesh."""

    n_elements: int
    tip_amplitude_m: float  # half the peak-to-peak lateral tip displacement
    period_s: float
    tip_rotation_amplitude_rad: float
    work_follower_J: float  # per period
    work_dissipated_J: float
    energy_balance_error: float  # |W_P - W_D| / W_D
    newton_corrections: list  # relative, per iteration
    integrations: int  # periods integrated (with the variational equations or without)
    n_rhs: int  # right-hand sides of the orbit-only integrations
    wall_s: float
    cpu_s: float
    floquet_multipliers: list | None = None  # [re, im] by decreasing modulus (exact monodromy)
    max_floquet_modulus: float | None = None

    def as_dict(self) -> dict:
        return asdict(self)


def cycle_measures(cycle: ShootingCycle, P: float, samples: int = 512,
                   wall_s: float = 0.0, cpu_s: float = 0.0, n_rhs: int = 0) -> CycleMeasures:
    """Amplitudes, period and the energy balance over one period of a converged cycle: the
    orbit's dense output at ``samples`` instants, the extremes by parabolas; the works by
    adaptive quadrature (:func:`_works_over`: the periodic trapezoid rule on the samples is
    spectrally accurate only while the powers are smooth on the sampling's scale, and an
    impulsive dissipation is not)."""
    model, T = cycle.model, cycle.T
    n = model.n_dof
    tt = np.arange(samples) * (T / samples)
    Y = cycle.orbit.sol(tt)
    tips = tip_states(model, Y)
    W_P, W_D = _works_over(model, cycle.orbit.sol, 0.0, T, P)
    fl = cycle.floquet
    mus = None if fl is None else sorted(fl.nontrivial, key=lambda z: -abs(z))
    return CycleMeasures(
        n_elements=int(model.n_elements),
        tip_amplitude_m=0.5 * (sampled_peak(tips[:, 1]) + sampled_peak(-tips[:, 1])),
        period_s=T,
        tip_rotation_amplitude_rad=max(sampled_peak(Y[n - 1]), sampled_peak(-Y[n - 1])),
        work_follower_J=W_P, work_dissipated_J=W_D, energy_balance_error=abs(W_P - W_D) / W_D,
        newton_corrections=[float(c) for c in cycle.corrections],
        integrations=int(cycle.integrations), n_rhs=int(n_rhs), wall_s=wall_s, cpu_s=cpu_s,
        floquet_multipliers=None if mus is None else [[float(z.real), float(z.imag)]
                                                      for z in mus[:8]],
        max_floquet_modulus=None if fl is None else fl.max_modulus)


def rod_shapes(model: NonlinearRod, orbit, T: float, frames: int = 41) -> list:
    """The rod's centre line at ``frames`` instants of one period (the animation)."""
    shapes = []
    for t in np.linspace(0.0, T, frames):
        q = orbit.sol(t)[: model.n_dof]
        theta = model.phi @ q
        x_q, x_tip = model._cumint(np.stack([np.cos(theta), np.sin(theta)], axis=-1))
        shapes.append(np.vstack([[0.0, 0.0], x_q, x_tip]).round(6).tolist())
    return shapes


def check_cycle_load(rod: Rod, P: float, n_elements: int, name: str = "P",
                     P_flu: float | None = None) -> float:
    """The damped flutter load ``P_flu`` [N] of the rod linearised on ``n_elements``, after
    refusing (:class:`ParameterError`, naming ``name``) a load ``P`` outside
    ``(P_flu, CYCLE_LOAD_MAX P_flu]``: below, the straight rod is stable and no cycle exists;
    far above, the stiff integrations run for minutes (outside audits: 1e6 N, 30 N). The one
    check of the cycle solvers, the beck_limit_cycle scene and the command line (which passes
    ``P_flu``, computed already)."""
    if P_flu is None:
        P_flu = linearised_flutter_load(rod, n_elements)
    P_top = CYCLE_LOAD_MAX * P_flu
    if not P_flu < P <= P_top:
        raise ParameterError(
            f"{name} must be in ({P_flu:.6g}, {P_top:.6g}] N: above the damped flutter load "
            f"P_flu = {P_flu:.6g} N of the rod linearised on {n_elements} elements (below it the "
            f"straight rod is stable and small motions decay) and at most {CYCLE_LOAD_MAX:g} "
            f"P_flu, got {P!r}")
    return P_flu


def flutter_mode_start(model: NonlinearRod, P: float, amplitude: float) -> NDArray:
    """The straight rod perturbed by its linear flutter mode (the eigenvector of the growing
    eigenvalue at ``P``, real part), scaled to a lateral tip displacement ``amplitude``."""
    from flutterfriction.analysis.stability import first_order_matrix

    P = check_real("P", P)
    amplitude = check_positive("amplitude", amplitude, "m")  # (NaN returned a NaN state)
    M0, C, K, K1 = model.linear_matrices()
    ev, V = np.linalg.eig(first_order_matrix(M0, K + P * K1, C))
    k = int(np.argmax(ev.real))
    if not ev[k].real > 0:
        raise ConvergenceError(f"the straight rod is stable at P = {P:g} N: no flutter to grow")
    w = V[:, k].real
    return w * amplitude / tip_lateral(model, w)


@dataclass
class RodTransient:
    """Flutter growing from a small perturbation of the straight rod into the cycle."""

    n_elements: int
    initial_amplitude_m: float
    growth_rate: float  # of the linear flutter mode [1/s]
    t_end: float  # the transient's last section crossing
    crossings_t: list  # section crossings (positive side): time, tip amplitude
    crossings_A: list
    section_states: list = field(repr=False, default_factory=list)
    n_rhs: int = 0
    wall_s: float = 0.0
    cpu_s: float = 0.0
    chunks: list = field(repr=False, default_factory=list)

    def state_at(self, t: NDArray) -> NDArray:
        t = np.atleast_1d(t)
        out = np.empty((self.chunks[0].sol(0.0).size, t.size))
        for c in self.chunks:
            sel = (t >= c.t[0]) & (t <= c.t[-1])
            if sel.any():
                out[:, sel] = c.sol(t[sel])
        return out


#: :func:`grow_into_cycle`'s default bound on simulated time and its solver chunk, in time
#: scales ``l^2 sqrt(rho/B)`` (62.8 s and 1.0 s for list 119).
TRANSIENT_T_MAX_SCALES, TRANSIENT_CHUNK_SCALES = 400.0, 6.4


def grow_into_cycle(model: NonlinearRod, P: float, amplitude: float = 1e-3,
                    method: str = "LSODA", rtol: float = 1e-6, tol: float = 1e-3,
                    t_max: float | None = None) -> RodTransient:
    """Integrate from the straight rod perturbed by the linear flutter mode (lateral tip
    displacement ``amplitude``) until the tip amplitude on the section changes by less than
    ``tol`` (relative) from one period to the next (with the slow Floquet multiplier ``mu``
    the distance from the cycle is then about ``tol / (1 - mu)``). Deterministic: bounded by
    ``t_max`` [s] of simulated time (default :data:`TRANSIENT_T_MAX_SCALES` time scales
    ``l^2 sqrt(rho/B)``, 63 s for list 119), never by the clock; the solver is called every
    :data:`TRANSIENT_CHUNK_SCALES` time scales. Both in the rod's own time: in seconds, the
    same rod ten times slower (rho x 100, D x 10: the same groups) was refused (an outside
    audit)."""
    from flutterfriction.analysis.stability import first_order_matrix

    y = flutter_mode_start(model, P, amplitude)
    M0, C, K, K1 = model.linear_matrices()
    sigma = float(np.linalg.eigvals(first_order_matrix(M0, K + P * K1, C)).real.max())
    counter = {"rhs": 0}

    one_state = model.rhs_at(P)  # the compiled kernel, its arguments bound once

    def rhs(t, z):
        counter["rhs"] += 1
        return one_state(t, z)

    def section(t, z):
        return section_value(model, z)

    section.direction = -1.0
    options = exact_jacobian(model, P, method)
    t_begin, c_begin = time.perf_counter(), time.process_time()
    t0, chunks, ts, states = 0.0, [], [], []
    # ~7 periods of list 119 per solve_ivp call; the test runs per crossing
    chunk = TRANSIENT_CHUNK_SCALES * model.rod.time_scale
    if t_max is None:
        t_max = TRANSIENT_T_MAX_SCALES * model.rod.time_scale
    if not check_real("t_max", t_max) > 0:
        raise ParameterError(f"t_max must be > 0, got {t_max!r}")
    while t0 < t_max:
        sol = solve_ivp(rhs, (t0, min(t0 + chunk, t_max)), y, method=method, rtol=rtol,
                        atol=rtol * 1e-2, events=section, dense_output=True, **options)
        if not sol.success:
            raise ConvergenceError(f"rod transient failed after t = {t0:.4g} s: {sol.message}")
        chunks.append(sol)
        for te, ye in zip(*section_crossings(model, sol), strict=True):
            ts.append(float(te))
            states.append(ye.copy())
            if len(ts) >= 2:
                A_now, A_before = tip_lateral(model, states[-1]), tip_lateral(model, states[-2])
                if abs(A_now - A_before) <= tol * A_now:
                    return RodTransient(
                        n_elements=int(model.n_elements), initial_amplitude_m=amplitude,
                        growth_rate=sigma, t_end=float(te), crossings_t=ts,
                        crossings_A=[float(tip_lateral(model, s)) for s in states],
                        section_states=states, n_rhs=counter["rhs"],
                        wall_s=time.perf_counter() - t_begin,
                        cpu_s=time.process_time() - c_begin, chunks=chunks)
        y, t0 = sol.y[:, -1], sol.t[-1]
    raise ConvergenceError(f"the transient did not settle to {tol:g} per period within "
                           f"{t_max:.4g} s (P = {P} N)")


@dataclass
class CycleChain:
    """The cycle on every mesh of the chain, and the transient that grows into it."""

    meshes: list
    cycles: list  # CycleMeasures per mesh
    transient: RodTransient
    transient_cycle: ShootingCycle  # the cycle on the transient's mesh (exact monodromy)
    primary: ShootingCycle  # the cycle on the second-last mesh (shapes; the only one if one)
    section_distance: list  # of the transient's crossings from the cycle (scaled max norm)


def section_distance(model: NonlinearRod, y: NDArray, cycle: ShootingCycle) -> float:
    """Distance of a section state from the cycle's, relative to each part's scale (the
    rotations' size; the velocities' or ``2 pi / T`` times the rotations')."""
    dz = np.concatenate([y - cycle.y, [0.0]])
    return _relative_correction(model, cycle.y, cycle.T, dz)


def beck_cycle_chain(rod: Rod, P: float, meshes: list[int], method: str = "LSODA",
                     fine_method: str = "BDF", rtol: float = 1e-8, tol: float = 1e-5,
                     transient_rtol: float = 1e-5, transient_tol: float = 1e-3,
                     initial_amplitude: float = 1e-3, variational_rtol: float = 1e-6,
                     progress: Callable[[str], None] | None = None) -> CycleChain:
    """The limit cycle at ``P`` on each mesh of ``meshes`` by shooting (periodic-orbit
    Newton), and the transient on the first mesh from a small perturbation of the straight
    rod (the linear flutter mode, tip amplitude ``initial_amplitude``) into it.

    First mesh: the transient (``method``, ``transient_rtol``) until the tip amplitude on the
    section changes by less than ``transient_tol`` per period; from its last section state,
    Newton with the exact monodromy (variational equations by DOP853 at ``variational_rtol``,
    orbits by DOP853 at ``rtol``), which gives the Floquet multipliers too. Each finer mesh
    starts from the previous cycle interpolated and iterates with the previous mesh's
    (secant-updated) monodromy prolongated as the Jacobian (orbits by ``fine_method`` with
    the exact right-hand-side Jacobian). Every mesh is converged to a Newton correction below
    ``tol``."""
    if not check_real("P", P) > 0:
        raise ParameterError(f"P must be > 0, got {P}")
    if not meshes:
        raise ParameterError("meshes must list at least one number of elements")
    say = progress or (lambda message: None)
    models = [NonlinearRod(rod, n) for n in meshes]
    base = models[0]
    transient = grow_into_cycle(base, P, initial_amplitude, method, transient_rtol,
                                transient_tol)
    say(f"transient on {meshes[0]} elements: {transient.t_end:.3f} s simulated, "
        f"{len(transient.crossings_t)} section crossings, CPU {transient.cpu_s:.1f} s")
    cycles, shot = [], []
    prev = None
    for k, model in enumerate(models):
        t_begin, c_begin = time.perf_counter(), time.process_time()
        counter = {"rhs": 0}
        if k == 0:
            y = transient.section_states[-1]
            T = transient.crossings_t[-1] - transient.crossings_t[-2]
            cyc = shoot_cycle(model, y, T, P, None, "DOP853", rtol, tol,
                              variational_rtol=variational_rtol, counter=counter)
        else:
            Pm = prolongation(prev.model, model)
            Phi = Pm @ prev.secant @ np.linalg.pinv(Pm)
            cyc = shoot_cycle(model, Pm @ prev.y, prev.T, P, Phi, fine_method, rtol, tol,
                              counter=counter)
        shot.append(cyc)
        cycles.append(cycle_measures(cyc, P, wall_s=time.perf_counter() - t_begin,
                                     cpu_s=time.process_time() - c_begin,
                                     n_rhs=counter["rhs"]))
        say(f"cycle on {meshes[k]} elements: amplitude {cycles[-1].tip_amplitude_m:.6f} m, "
            f"period {cyc.T:.7f} s, corrections "
            f"{', '.join(f'{c:.1e}' for c in cyc.corrections)}, CPU {cycles[-1].cpu_s:.1f} s")
        prev = cyc
    return CycleChain(meshes=[int(n) for n in meshes], cycles=cycles, transient=transient,
                      transient_cycle=shot[0], primary=shot[max(len(shot) - 2, 0)],
                      section_distance=[section_distance(base, s, shot[0])
                                        for s in transient.section_states])
