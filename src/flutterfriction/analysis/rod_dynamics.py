"""Limit cycle of the nonlinear Beck/Pflüger rod (chapter §2.9, Figs. 15–17).

Time integration of :class:`~flutterfriction.models.rod_nonlinear.NonlinearRod` with an implicit
scipy integrator (the Kelvin–Voigt term makes the system stiff); the cycle is detected on the
Poincaré section "lateral tip velocity = 0, tip on the positive side", and accepted when the
tip amplitude and the period of successive crossings agree to ``tol``. On the converged cycle
the work of the follower force per period must equal the viscous dissipation (energy check).
Only the tip's history is stored (what the figures draw).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from flutterfriction.analysis.rod_cycles import section_value
from flutterfriction.errors import ConvergenceError, ParameterError
from flutterfriction.models.rod import Rod
from flutterfriction.models.rod_nonlinear import NonlinearRod


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


def _tip_state(model: NonlinearRod, y: NDArray) -> NDArray:
    n = model.n_dof
    q, v = y[:n], y[n:]
    _, _, _, G_tip = model.kinematics(q)
    x_tip = model.tip_position(q)
    return np.array([x_tip[0] - model.rod.length, x_tip[1], *(G_tip @ v)])


def beck_limit_cycle(rod: Rod, P: float, n_elements: int = 8, method: str = "BDF",
                     rtol: float = 1e-7, atol: float = 1e-9, tol: float = 1e-4,
                     t_max: float = 30.0, initial_tip_rotation: float = 0.05,
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
    the damped flutter load of list (119), so transients there last minutes).

    ``progress(message)``, if given, hears of every section crossing (simulated time, tip
    amplitude, the relative changes tested against ``tol``); it never changes the result."""
    if not P > 0:
        raise ParameterError(f"P must be > 0, got {P}")
    model = NonlinearRod(rod, n_elements)
    n = model.n_dof
    y = np.zeros(2 * n)
    y[:n] = initial_tip_rotation * np.linspace(0, 1, n + 1)[1:]
    if start is not None:
        coarse, yc = start
        nodes = np.linspace(0.0, rod.length, n + 1)[1:]
        y[:n] = coarse.nodal_values_at(yc[:coarse.n_dof], nodes)
        y[n:] = coarse.nodal_values_at(yc[coarse.n_dof:], nodes)
    counter = {"rhs": 0}

    def rhs(t, z):
        counter["rhs"] += 1
        return model.rhs(t, z, P)

    def section(t, z):  # lateral tip velocity; -1: at the maximum of the lateral displacement
        return section_value(model, z)

    section.direction = -1.0
    t_begin = time.perf_counter()
    t0, crossings, chunks = 0.0, [], []
    chunk = 6 * rod.time_scale  # several first-mode periods, until the period is measured
    converged = False
    while t0 < t_max and not converged:
        sol = solve_ivp(rhs, (t0, min(t0 + chunk, t_max)), y, method=method, rtol=rtol,
                        atol=atol, events=section, dense_output=True)
        if not sol.success:
            raise ConvergenceError(f"rod integration failed after t = {t0:.4g} s: "
                                   f"{sol.message}")
        chunks.append(sol)
        for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
            if _tip_state(model, ye)[1] <= 0:
                continue
            crossings.append((float(te), float(_tip_state(model, ye)[1]), ye.copy()))
            if len(crossings) < 4:
                continue
            # Four crossings: three periods and four amplitudes agree to tol (after a mesh
            # change the sequence beats, and two agreeing crossings can be a coincidence),
            # and the geometric tail of a steadily contracting sequence is below tol too.
            ts = np.array([c[0] for c in crossings[-4:]])
            us = np.array([c[1] for c in crossings[-4:]])
            periods = np.diff(ts)
            chunk = 4 * periods[-1]
            d_c, d_b = us[-1] - us[-2], us[-2] - us[-3]
            mu = d_c / d_b if d_b != 0 else 0.0
            tail = abs(d_c) * mu / (1 - mu) if 0 < mu < 1 else 0.0
            if progress:
                progress(f"rod, {n_elements} elements, P = {P:g} N: t = {te:.3f} s, tip "
                         f"amplitude {us[-1]:.5f} m, period spread "
                         f"{np.ptp(periods) / periods[-1]:.1e}, amplitude spread "
                         f"{np.ptp(us) / us[-1]:.1e}, tail {tail / us[-1]:.1e} "
                         f"(converged below {tol:g})")
            if (np.ptp(periods) <= tol * periods[-1] and np.ptp(us) <= tol * us[-1]
                    and tail <= tol * us[-1] and mu < 1):
                converged = True
                break
        y, t0 = sol.y[:, -1], sol.t[-1]
    if not converged:
        raise ConvergenceError(f"no rod limit cycle converged to {tol:g} within {t_max} s "
                               f"(P = {P} N; below the flutter load the motion decays)")
    T = crossings[-1][0] - crossings[-2][0]
    t_end = crossings[-1][0]
    wall = time.perf_counter() - t_begin

    def state_at(t):
        for c in chunks:
            if c.t[0] <= t <= c.t[-1]:
                return c.sol(t)
        return chunks[-1].sol(min(t, chunks[-1].t[-1]))

    # Measures on the last period, and the energy balance (trapezoid, fine sampling).
    tt = np.linspace(t_end - T, t_end, samples_per_period + 1)
    states = np.array([state_at(t) for t in tt])
    tips = np.array([_tip_state(model, s) for s in states])
    powers = np.array([model.power_balance(s[:n], s[n:], P) for s in states])
    W_P = float(np.trapezoid(powers[:, 0], tt))
    W_D = float(np.trapezoid(powers[:, 1], tt))
    # The rod's shape at 41 instants of the last period (for the animation only).
    shapes = []
    for s_ in states[:: max(1, samples_per_period // 40)]:
        theta = model.phi @ s_[:n]
        x_q, x_tip = model._cumint(np.stack([np.cos(theta), np.sin(theta)], axis=-1))
        shape = np.vstack([[0.0, 0.0], x_q, x_tip])
        shapes.append(shape.round(6).tolist())
    # History of the tip for the figures: the whole transient, 100 points per period.
    th = np.linspace(0.0, t_end, max(200, int(100 * t_end / T)))
    hist = np.array([_tip_state(model, state_at(t)) for t in th])
    return RodLimitCycle(
        tip_amplitude_m=float(0.5 * (tips[:, 1].max() - tips[:, 1].min())), period_s=float(T),
        tip_rotation_amplitude_rad=float(np.max(np.abs(states[:, n - 1]))),
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
    """Chung–Hulbert generalized-alpha integration (the ABAQUS-style structural choice: second
    order, high-frequency dissipation set by ``rho_inf``) of ``I(q, a) + g(q, v) = 0`` with
    the inertia ``I = M(q) a`` and ``g = h(q, v) + K q + C v - F(q)`` (``h`` the centripetal
    term):

        (1 - am) I_{n+1} + am I_n + (1 - af) g_{n+1} + af g_n = 0,

    Newmark updates with ``gamma = 1/2 - am + af``, ``beta = (1 - am + af)^2 / 4``; Newton on
    ``a_{n+1}`` with a finite-difference Jacobian reused across steps while Newton converges.
    Returns sampled times, states and the number of model evaluations."""
    n = model.n_dof
    am = (2 * rho_inf - 1) / (rho_inf + 1)
    af = rho_inf / (rho_inf + 1)
    gamma = 0.5 - am + af
    beta = 0.25 * (1 - am + af) ** 2
    count = {"n": 0}

    def parts(q, v, a):
        # The centripetal term h(q, v) in g does not involve a: it is weighted like the forces
        # (with it in the inertia group the scheme drops to first order when rho_inf < 1).
        count["n"] += 1
        M, g = model.dynamic_terms(q, v, P)
        return M @ a, g

    q, v = y0[:n].copy(), y0[n:].copy()
    a = model.accelerations(q, v, P)
    I_old, g_old = parts(q, v, a)
    steps = int(round(t_end / dt))
    times, states = [0.0], [np.concatenate([q, v])]
    J = None

    def residual(a_new):
        qn = q + dt * v + dt**2 * ((0.5 - beta) * a + beta * a_new)
        vn = v + dt * ((1 - gamma) * a + gamma * a_new)
        I_new, g_new = parts(qn, vn, a_new)
        return (1 - am) * I_new + am * I_old + (1 - af) * g_new + af * g_old

    for k in range(1, steps + 1):
        a_new = a.copy()
        R = residual(a_new)
        refresh = J is None
        for _it in range(40):
            if refresh:  # the Jacobian is reused across steps until Newton stops contracting
                eps = 1e-6 * max(1.0, np.abs(a_new).max())
                J = np.column_stack([(residual(a_new + eps * e) - R) / eps for e in np.eye(n)])
            step = np.linalg.solve(J, -R)
            a_new = a_new + step
            R_prev, R = R, residual(a_new)
            refresh = np.linalg.norm(R) > 0.5 * np.linalg.norm(R_prev)
            # Converged when the update, or the residual, is at the level of round-off.
            scale = max(1.0, np.linalg.norm(I_old) + np.linalg.norm(g_old))
            if np.linalg.norm(step) <= newton_tol * max(1.0, np.linalg.norm(a_new)) or \
                    np.linalg.norm(R) <= 1e-12 * scale:
                break
        else:
            raise ConvergenceError(f"generalized-alpha Newton did not converge at step {k}")
        q = q + dt * v + dt**2 * ((0.5 - beta) * a + beta * a_new)
        v = v + dt * ((1 - gamma) * a + gamma * a_new)
        a = a_new
        I_old, g_old = parts(q, v, a)
        if k % sample_every == 0 or k == steps:  # the final state is always returned
            times.append(k * dt)
            states.append(np.concatenate([q, v]))
    return np.array(times), np.array(states), count["n"]
