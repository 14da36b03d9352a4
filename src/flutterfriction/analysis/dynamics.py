"""Nonlinear dynamics of the Ziegler pendulum (chapter §2.9–2.11): time integration of eq. (10)
with hinge viscosity, limit-cycle detection on a Poincaré section, and a periodic-orbit solve
by shooting as the independent check.

The right-hand side is :meth:`~flutterfriction.models.ziegler.ZieglerPendulum.equations_of_motion`;
its Jacobian is derived once with sympy from the same equations (analytic, exact) and compiled.
"""

from __future__ import annotations

import functools
from dataclasses import asdict, dataclass

import numpy as np
import sympy as sp
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import root

from flutterfriction.errors import ConvergenceError, ParameterError, check_real
from flutterfriction.models.ziegler import ZieglerPendulum

_PARAMS = sp.symbols("l1 l2 d h m1 m2 m3 k1 k2 c1 c2 P H")


@functools.cache
def _jacobian_function():
    """Compiled d(state')/d(state) of eq. (10) with viscosity, as a function of (state, params)."""
    l1, l2, d, h, m1, m2, m3, k1, k2, c1, c2, P, H = _PARAMS
    a1, a2, w1, w2 = sp.symbols("a1 a2 w1 w2")
    s, c = sp.sin(a1 - a2), sp.cos(a1 - a2)
    w = (m2 * l2 + m3 * h) * l1
    I1 = m1 * d**2 + (m2 + m3) * l1**2
    I2 = m2 * l2**2 + m3 * h**2
    f1 = (-w * w2**2 * s - k1 * a1 - k2 * (a1 - a2) - c1 * w1 - c2 * (w1 - w2) + P * l1 * s
          + H * l1 * sp.sin(a1))
    f2 = w * w1**2 * s + k2 * (a1 - a2) - c2 * (w2 - w1) + H * l2 * sp.sin(a2)
    det = I1 * I2 - (w * c) ** 2
    rhs = sp.Matrix([w1, w2, (I2 * f1 - w * c * f2) / det, (I1 * f2 - w * c * f1) / det])
    J = rhs.jacobian([a1, a2, w1, w2])
    return sp.lambdify(((a1, a2, w1, w2), _PARAMS), J, "numpy")


def jacobian(pendulum: ZieglerPendulum, state: ArrayLike, P: float, H: float = 0.0) -> NDArray:
    """Analytic Jacobian of the nonlinear equations of motion (eq. 10) at ``state``."""
    p = pendulum
    params = (p.l1, p.l2, p.d, p.h, p.m1, p.m2, p.m3, p.k1, p.k2, p.c1, p.c2, P, H)
    return np.array(_jacobian_function()(tuple(np.asarray(state, dtype=float)), params),
                    dtype=float)


def simulate(pendulum: ZieglerPendulum, P: float, state0: ArrayLike, t_end: float,
             t_eval: ArrayLike | None = None, H: float = 0.0, method: str = "DOP853",
             rtol: float = 1e-10, atol: float = 1e-12, **kwargs):
    """Integrate eq. (10) from ``state0 = [alpha1, alpha2, alpha1_dot, alpha2_dot]``."""
    P, H = check_real("P", P), check_real("H", H)
    x0 = np.asarray(state0, dtype=float)
    if x0.shape != (4,) or not np.all(np.isfinite(x0)):
        raise ParameterError("state0 must be 4 finite numbers [a1, a2, a1_dot, a2_dot]")
    if not t_end > 0:
        raise ParameterError(f"t_end must be > 0, got {t_end}")
    if method in ("Radau", "BDF", "LSODA"):  # implicit: give them the analytic Jacobian
        kwargs["jac"] = lambda t, x: jacobian(pendulum, x, P, H)
    sol = solve_ivp(lambda t, x: pendulum.equations_of_motion(x, P, H), (0.0, t_end), x0,
                    method=method, t_eval=t_eval, rtol=rtol, atol=atol, **kwargs)
    if not sol.success:
        raise ConvergenceError(f"time integration failed: {sol.message}")
    return sol


@dataclass(frozen=True)
class LimitCycle:
    """A periodic orbit: amplitudes [rad], period [s], the state where alpha1 is largest."""

    alpha1_amplitude_rad: float
    alpha2_amplitude_rad: float
    period_s: float
    section_state: tuple[float, float, float, float]
    transient_s: float  # time at which the cycle was declared converged
    n_crossings: int

    def as_dict(self) -> dict:
        return asdict(self)


def _amplitudes(pendulum, P, H, x0, T, method, rtol, atol, n=2001):
    sol = simulate(pendulum, P, x0, T, t_eval=np.linspace(0, T, n), H=H, method=method,
                   rtol=rtol, atol=atol)
    return float(np.max(np.abs(sol.y[0]))), float(np.max(np.abs(sol.y[1])))


def limit_cycle(pendulum: ZieglerPendulum, P: float, state0: ArrayLike, H: float = 0.0,
                tol: float = 1e-8, t_max: float = 600.0, method: str = "DOP853",
                rtol: float = 1e-11, atol: float = 1e-13) -> LimitCycle:
    """Integrate until successive crossings of the Poincaré section ``alpha1_dot = 0``
    (downwards: ``alpha1`` at a maximum) agree to ``tol`` (relative) in ``alpha1``, ``alpha2``,
    ``alpha2_dot`` and in the time between crossings (the period)."""
    def section(t, x):
        return x[2]

    section.direction = -1.0
    x, t0 = np.asarray(state0, dtype=float), 0.0
    crossings: list[tuple[float, NDArray]] = []
    chunk = 20.0
    while t0 < t_max:
        sol = solve_ivp(lambda t, y: pendulum.equations_of_motion(y, P, H), (t0, t0 + chunk), x,
                        method=method, events=section, rtol=rtol, atol=atol)
        if not sol.success:
            raise ConvergenceError(f"time integration failed: {sol.message}")
        if np.max(np.abs(sol.y[:2])) > 50 * np.pi:
            raise ConvergenceError("the motion runs away (no limit cycle: divergence?)")
        for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
            if ye[0] > 0:  # maxima of alpha1 only
                crossings.append((float(te), ye.copy()))
        if len(crossings) >= 3:
            (ta, ya), (tb, yb), (tc, yc) = crossings[-3:]
            T1, T2 = tb - ta, tc - tb
            scale = np.maximum(np.abs(yc), 1e-3 * np.max(np.abs(yc)))
            if abs(T2 - T1) <= tol * T2 and np.all(np.abs(yc - yb) <= tol * scale):
                a1, a2 = _amplitudes(pendulum, P, H, yc, T2, method, rtol, atol)
                return LimitCycle(a1, a2, T2, tuple(float(v) for v in yc), tc, len(crossings))
        x, t0 = sol.y[:, -1], sol.t[-1]
    raise ConvergenceError(f"no limit cycle converged to {tol:g} within t = {t_max} s")


def shoot_periodic_orbit(pendulum: ZieglerPendulum, P: float, guess: LimitCycle,
                         H: float = 0.0, rtol: float = 1e-12, atol: float = 1e-14) -> LimitCycle:
    """Periodic orbit by shooting (independent of the transient): unknowns ``(alpha1, alpha2,
    alpha2_dot, T)`` with ``alpha1_dot = 0`` on the section; residual ``phi_T(x0) - x0``."""
    x_guess = np.asarray(guess.section_state, dtype=float)

    def residual(z):
        x0 = np.array([z[0], z[1], 0.0, z[2]])
        sol = simulate(pendulum, P, x0, z[3], H=H, rtol=rtol, atol=atol)
        return sol.y[:, -1] - x0

    z0 = np.array([x_guess[0], x_guess[1], x_guess[3], guess.period_s])
    res = root(residual, z0, method="hybr", options={"xtol": 1e-13})
    if not res.success or np.max(np.abs(res.fun)) > 1e-9:
        raise ConvergenceError(f"shooting did not converge: {res.message}")
    x0 = np.array([res.x[0], res.x[1], 0.0, res.x[2]])
    a1, a2 = _amplitudes(pendulum, P, H, x0, res.x[3], "DOP853", rtol, atol)
    return LimitCycle(a1, a2, float(res.x[3]), tuple(float(v) for v in x0), 0.0, 0)


def tip_acceleration(pendulum: ZieglerPendulum, states: NDArray, P: float,
                     H: float = 0.0) -> NDArray:
    """Acceleration of the loaded end C [m/s^2], shape (n, 2), from states (n, 4) of eq. (10)."""
    x = np.asarray(states, dtype=float).T
    dx = pendulum.equations_of_motion(x, P, H)
    a1, a2, w1, w2 = x
    acc1, acc2 = dx[2], dx[3]
    l1, l2 = pendulum.l1, pendulum.l2
    ax = (-l1 * (acc1 * np.sin(a1) + w1**2 * np.cos(a1))
          - l2 * (acc2 * np.sin(a2) + w2**2 * np.cos(a2)))
    ay = (l1 * (acc1 * np.cos(a1) - w1**2 * np.sin(a1))
          + l2 * (acc2 * np.cos(a2) - w2**2 * np.sin(a2)))
    return np.stack([ax, ay], axis=-1)
