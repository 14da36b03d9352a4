"""Nonlinear dynamics of the Ziegler pendulum (chapter §2.9–2.11): time integration of eq. (10)
with hinge viscosity, limit-cycle detection on a Poincaré section, and a periodic-orbit solve
by shooting as the independent check.

The right-hand side is :meth:`~flutterfriction.models.ziegler.ZieglerPendulum.equations_of_motion`
(bound once per integration: :meth:`~flutterfriction.models.ziegler.ZieglerPendulum.motion_at`);
its Jacobian is the same equations differentiated by hand (exact; the tests check it against
sympy's derivative and central differences).
"""

from __future__ import annotations

import contextlib
import contextvars
import math
import warnings
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import ODEintWarning, odeint, solve_ivp
from scipy.optimize import root

from flutterfriction.analysis.events import from_the_section
from flutterfriction.errors import (
    NORMAL_MIN,
    ConvergenceError,
    ParameterError,
    check_finite_array,
    check_finite_reals,
    check_integer,
    check_positive,
    check_real,
    shown_beside,
)
from flutterfriction.models.ziegler import ZieglerPendulum, check_pendulum


def jacobian(pendulum: ZieglerPendulum, state: ArrayLike, P: float, H: float = 0.0) -> NDArray:
    """Analytic Jacobian of the nonlinear equations of motion (eq. 10) at ``state``; a state or
    load whose Jacobian leaves the double range is refused (:class:`ParameterError`), as
    :meth:`~flutterfriction.models.ziegler.ZieglerPendulum.equations_of_motion` refuses it (an
    outside review: velocities of 1e160 rad/s raised Python's OverflowError)."""
    P, H, x = _checked_start(P, H, state, "state")
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            J = jacobian_at(pendulum, P, H)(0.0, x)
    except OverflowError:
        J = np.full((4, 4), np.inf)
    if not np.all(np.isfinite(J)):
        raise ParameterError(f"state, P = {P!r}, H = {H!r}: the Jacobian of the equations of "
                             f"motion leaves the double range")
    return J


def jacobian_at(pendulum: ZieglerPendulum, P: float, H: float = 0.0
                ) -> Callable[[float, NDArray], NDArray]:
    """``jac(t, x)``: :func:`jacobian` at the loads ``P``, ``H`` [N], checked once, for an
    implicit integrator's many calls (unchecked per call, as :meth:`ZieglerPendulum.motion_at`:
    the work-precision study times them)."""
    p = check_pendulum(pendulum)
    fn = p._motion_jacobian(check_real("P", P), check_real("H", H))
    array = np.array
    return lambda t, x: array(fn(*x.tolist()))


def _checked_start(P: float, H: float, state0: ArrayLike, name: str = "state0"
                   ) -> tuple[float, float, NDArray]:
    """The loads and the start state, refused (one line naming them) unless finite; the
    integrations then call the equations of motion unchecked."""
    P, H = check_real("P", P), check_real("H", H)
    return P, H, check_finite_array(name, state0, (4,),
                                    "4 finite numbers [a1, a2, a1_dot, a2_dot]")


#: The integrators :func:`simulate` and :func:`limit_cycle` accept (scipy's ``solve_ivp``).
METHODS = ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA")
#: Relative tolerances of an integration: below ~100 machine epsilons scipy raises them
#: itself (with a warning), at 1 and above nothing is resolved.
RTOL_RANGE = (1e-14, 0.1)


def _check_integration(method: object, rtol: object, atol: object) -> tuple[float, float]:
    """The integrator and its tolerances, refused in one line naming them (an outside audit:
    an unknown method came back as scipy's own error; see :func:`_check_tolerances`)."""
    if method not in METHODS:
        raise ParameterError(f"method must be one of {list(METHODS)}, got {method!r}")
    return _check_tolerances(rtol, atol)


def _check_tolerances(rtol: object, atol: object) -> tuple[float, float]:
    """An integration's tolerances (an outside audit: ``rtol = nan`` integrated without end,
    ``-1`` ran with a warning, a string came back as numpy's own error)."""
    rtol, atol = check_real("rtol", rtol), check_real("atol", atol)
    if not RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]:
        raise ParameterError(f"rtol must be in [{RTOL_RANGE[0]:g}, {RTOL_RANGE[1]:g}], got "
                             f"{rtol!r}")
    if not atol > 0:
        raise ParameterError(f"atol must be > 0, got {atol!r}")
    return rtol, atol


def _check_solver_options(kwargs: dict, t_end: float) -> dict:
    """``solve_ivp``'s step options (``first_step``, ``max_step``: positive and finite) and
    ``t_eval`` (finite instants in [0, t_end]) refused in one line where bad."""
    for name in ("first_step", "max_step"):
        if name in kwargs:
            kwargs[name] = check_positive(name, kwargs[name], "s")
    if kwargs.get("t_eval") is not None:
        t = np.atleast_1d(check_finite_reals("t_eval", kwargs["t_eval"]))
        if t.ndim != 1 or np.any(t < 0) or np.any(t > t_end):
            raise ParameterError(f"t_eval must be instants in [0, t_end = {t_end:g}] s, got "
                                 f"{t.size} values in [{t.min():g}, {t.max():g}]")
        kwargs["t_eval"] = t
    return kwargs

#: The longest motion :func:`simulate` integrates, in the pendulum's time unit tau =
#: l2 sqrt(m2/k2) (eq. 17): 1e4 tau take ~10 s of work (§2.9's cycle, DOP853 at rtol 1e-10),
#: so this bounds one call to minutes; the §2.9 scenes stay within 1e4.
SIMULATE_MAX_TIME_UNITS = 1e5

#: Evaluations of eq. (10) that each phase of :func:`ziegler_limit_cycle` (the transient and
#: its shooting check; the continuation and its section check) may spend: counted, never
#: timed, so the answer does not depend on the machine. About 7 s a phase here (5 us an
#: evaluation with the integrator's work). The workflow's cycles take at most 0.12 M, a viscous
#: pendulum of c = 10 N m s on unit bars 1.13 M (measured);
#: a stiff pendulum (hinge viscosity 30 N m s on unit bars, 180x the flutter frequency)
#: integrated for minutes with no bound (an outside audit).
LIMIT_CYCLE_EVALUATIONS = 1_500_000

#: The torque scale k2 [N m] :func:`ziegler_limit_cycle` accepts (k1 is within 1e6 of it by
#: the model's range): squares of torques stay normal doubles (1e+-300).
DYNAMICS_TORQUE_RANGE = (1e-140, 1e140)

_budget: contextvars.ContextVar[tuple[list[int], int] | None] = contextvars.ContextVar(
    "limit_cycle_budget", default=None)


class BudgetExhausted(ConvergenceError):
    """The evaluations of :data:`LIMIT_CYCLE_EVALUATIONS` are spent."""


@contextlib.contextmanager
def _evaluation_budget(n: int) -> Iterator[None]:
    """Integrations in this context stop with :class:`BudgetExhausted` after ``n``
    evaluations of their right-hand side (all of them together)."""
    token = _budget.set(([n], n))
    try:
        yield
    finally:
        _budget.reset(token)


def _counted(f: Callable[[float, NDArray], NDArray]) -> Callable[[float, NDArray], NDArray]:
    """``f`` counted against the evaluation budget in force, if any."""
    budget = _budget.get()
    if budget is None:
        return f
    box, total = budget

    def g(t: float, x: NDArray) -> NDArray:
        box[0] -= 1
        if box[0] < 0:
            raise BudgetExhausted(f"the integrations spent their {total:,} "
                                  "evaluations of eq. (10) (a stiff or slowly settling "
                                  "pendulum)")
        return f(t, x)
    return g


@contextlib.contextmanager
def _overflow_refused() -> Iterator[None]:
    """An integration whose equations of motion overflow the doubles (eq. 10's torques and
    velocities squared: a load or a start far beyond the pendulum's scale, e.g. P = 1e150 N on
    the §2.9 pendulum) ends in a :class:`ConvergenceError` saying so, not Python's
    OverflowError (an outside audit). Around the call, not in the right-hand side: no cost
    per evaluation."""
    try:
        yield
    except OverflowError:
        raise ConvergenceError("the motion left the double range (eq. 10 overflowed): a load "
                               "or a start state far beyond the pendulum's own scale") from None


def simulate(pendulum: ZieglerPendulum, P: float, state0: ArrayLike, t_end: float,
             t_eval: ArrayLike | None = None, H: float = 0.0, method: str = "DOP853",
             rtol: float = 1e-10, atol: float = 1e-12, **kwargs):
    """Integrate eq. (10) from ``state0 = [alpha1, alpha2, alpha1_dot, alpha2_dot]`` over
    ``(0, t_end]``, ``t_end`` [s] at most :data:`SIMULATE_MAX_TIME_UNITS` time units of the
    pendulum (refused beyond, and infinite: an outside audit's ``t_end = inf`` ran until
    killed)."""
    check_pendulum(pendulum)
    P, H, x0 = _checked_start(P, H, state0)
    t_end = check_positive("t_end", t_end, "s")
    rtol, atol = _check_integration(method, rtol, atol)
    kwargs = _check_solver_options({**kwargs, "t_eval": t_eval}, t_end)
    limit = SIMULATE_MAX_TIME_UNITS * time_unit(pendulum)
    if t_end > limit:
        raise ParameterError(f"t_end must be in (0, {limit:.4g}] s ({SIMULATE_MAX_TIME_UNITS:g} "
                             f"time units l2 sqrt(m2/k2) of this pendulum), got {t_end:g}")
    if method in ("Radau", "BDF", "LSODA"):  # implicit: give them the analytic Jacobian
        kwargs["jac"] = jacobian_at(pendulum, P, H)
    with _overflow_refused():
        sol = solve_ivp(_counted(pendulum.motion_at(P, H)),
                        (0.0, t_end), x0, method=method, rtol=rtol, atol=atol, **kwargs)
    if not sol.success:
        raise ConvergenceError(f"time integration failed: {sol.message}")
    return sol


#: :func:`sampled_motion`'s bound on LSODA's steps between two outputs, which are at most one
#: time unit apart: ~45x the most the workflow's motions take in one time unit (measured with
#: outputs one unit apart: 81-111 for Fig. 21's start at 0.5 rad/s, 80-100 for Figs. 13, 20
#: and the decay test; between their own, denser samples 16-34), so that a pendulum moving
#: tens of times faster than its time unit (a load far above its flutter load) is still
#: answered, while a motion no step size resolves ends in a ConvergenceError.
_SAMPLED_MXSTEP = 5000


def sampled_motion(pendulum: ZieglerPendulum, P: float, state0: ArrayLike, t: ArrayLike,
                   H: float = 0.0, rtol: float = 1e-11, atol: float = 1e-13) -> NDArray:
    """States of eq. (10) at the instants ``t`` [s] (increasing, from 0), shape ``(len(t), 4)``:
    a motion that is only sampled (a figure's transient, a decay test), by LSODA (scipy's
    ``odeint``: Fortran steps, a C loop over the outputs, Python only for the right-hand
    side), ~5x cheaper than :func:`simulate`'s ``solve_ivp``, which returns to Python at every
    step. The default tolerances make it the more accurate of the
    two at their defaults (measured against DOP853 at rtol 1e-13 on the motions of Figs.
    13/14, 20 and 21: 5.3e-9, 1.3e-8, 4.1e-9 against simulate's 1.7e-8, 2.1e-8, 2.2e-8; at a
    fifth to a seventh of its time). No events: where the extrema or crossings matter,
    :func:`simulate` or :func:`limit_cycle`.

    Integrated in the pendulum's time unit (:func:`in_time_unit`; ``rtol``, ``atol`` apply
    there, as in :func:`limit_cycle`), with an output at least every time unit, so that
    LSODA's bound on the steps between two outputs (``mxstep``, :data:`_SAMPLED_MXSTEP`)
    bounds the work per time unit; bounded in time by :data:`SIMULATE_MAX_TIME_UNITS` as
    :func:`simulate` is. A failure or a non-finite state (which odeint reports as a success)
    raises :class:`ConvergenceError`."""
    check_pendulum(pendulum)
    P, H, x0 = _checked_start(P, H, state0)
    rtol, atol = _check_tolerances(rtol, atol)
    t = np.atleast_1d(check_finite_reals("t", t))
    tau = time_unit(pendulum)
    limit = SIMULATE_MAX_TIME_UNITS * tau
    if t.ndim != 1 or t.size < 2:
        wrong = f"shape {t.shape}"
    elif t[0] != 0.0:
        wrong = f"t[0] = {t[0]:g}"
    elif np.any(np.diff(t) <= 0):
        k = int(np.argmax(np.diff(t) <= 0)) + 1
        wrong = f"t[{k}] = {t[k]:g} after t[{k - 1}] = {t[k - 1]:g}"
    elif t[-1] > limit:
        wrong = f"t[-1] = {t[-1]:g} s"
    else:
        wrong = ""
    if wrong:
        raise ParameterError(f"t must be at least two increasing instants from 0 to at most "
                             f"{limit:.4g} s ({SIMULATE_MAX_TIME_UNITS:g} time units l2 "
                             f"sqrt(m2/k2) of this pendulum), got {wrong}")
    s = t / tau
    grid = np.union1d(s, np.arange(0.0, s[-1], 1.0))  # an output at least every time unit
    scale = np.array([1.0, 1.0, tau, tau])
    rhs = _counted(in_time_unit(pendulum).motion_at(P, H))
    with warnings.catch_warnings(), _overflow_refused():
        warnings.simplefilter("ignore", ODEintWarning)  # reported below, as an error
        Y, info = odeint(rhs, x0 * scale, grid, tfirst=True, rtol=rtol, atol=atol,
                         mxstep=_SAMPLED_MXSTEP, full_output=True)
    message = info["message"]
    if message != "Integration successful." or not np.all(np.isfinite(Y)):
        # odeint's own words name its internals (a Dfun never given, an "internal error")
        raise ConvergenceError("time integration (LSODA) failed: " + (
            "the state became non-finite" if message == "Integration successful." else
            f"more than {_SAMPLED_MXSTEP} steps within one time unit (a motion far faster "
            f"than the pendulum's own)" if message.startswith("Excess work") else
            "LSODA refused its start (eq. 10 beyond the double range there, or instants "
            "closer than its first step can resolve)" if message.startswith("Illegal input")
            else message))
    return Y[np.searchsorted(grid, s)] / scale


@dataclass(frozen=True)
class LimitCycle:
    """A periodic orbit: amplitudes [rad], period [s], the state where alpha1 is largest."""

    alpha1_amplitude_rad: float
    alpha2_amplitude_rad: float
    period_s: float
    section_state: tuple[float, float, float, float]
    # time of the last section crossing of the integration chunk in which the cycle was
    # found converged: convergence is tested once per chunk (400 time units in
    # ziegler_limit_cycle), so this bounds the settling time from above, it is not it
    transient_s: float
    n_crossings: int

    def as_dict(self) -> dict:
        return asdict(self)

    def in_time_scale(self, s: float) -> LimitCycle:
        """The same orbit with time measured in units of ``s`` seconds (times / s, angular
        velocities x s; angles unchanged): ``s = tau`` to, ``1/tau`` from the time unit of
        :func:`in_time_unit`."""
        a1, a2, v1, v2 = self.section_state
        return replace(self, period_s=self.period_s / s, transient_s=self.transient_s / s,
                       section_state=(a1, a2, v1 * s, v2 * s))


def _amplitudes(pendulum, P, H, x0, T, method, rtol, atol, n=2001):
    """Largest ``|alpha1|``, ``|alpha2|`` over one period from ``x0``: at the samples and at the
    extrema themselves (events ``alpha_i_dot = 0``: the samples alone were up to 1e-6 rad low
    for alpha2, measured by an outside audit)."""
    sol = simulate(pendulum, P, x0, T, t_eval=np.linspace(0, T, n), H=H, method=method,
                   rtol=rtol, atol=atol, events=(lambda t, x: x[2], lambda t, x: x[3]))
    a1 = max(float(np.max(np.abs(sol.y[0]))), *(abs(float(y[0])) for y in sol.y_events[0]))
    a2 = max(float(np.max(np.abs(sol.y[1]))), *(abs(float(y[1])) for y in sol.y_events[1]))
    return a1, a2


def limit_cycle(pendulum: ZieglerPendulum, P: float, state0: ArrayLike, H: float = 0.0,
                tol: float = 1e-8, t_max: float | None = None, method: str = "DOP853",
                rtol: float = 1e-11, atol: float = 1e-13,
                max_steps: int = 2_000_000, chunk: float | None = None) -> LimitCycle:
    """Integrate until successive crossings of the Poincaré section ``alpha1_dot = 0``
    (downwards: ``alpha1`` at a maximum) agree to ``tol`` (relative) in ``alpha1``, ``alpha2``,
    ``alpha2_dot`` and in the time between crossings (the period).

    Bounded by simulated time (``t_max`` [s], default :data:`TRANSIENT_T_MAX` time units
    ``tau``, 588 s for the §2.9 pendulum) and by the number of integration steps
    (``max_steps``, counted per ``chunk`` [s] of simulated time, default
    :data:`TRANSIENT_CHUNK` ``tau``), never by the wall clock; a rotation beyond ``50 pi``
    stops the integration at once (terminal event: the motion runs away). The integration
    runs in the pendulum's time unit (:func:`in_time_unit`; ``rtol``, ``atol`` apply there), so
    that the work does not depend on the unit of time: with a chunk fixed in seconds, a
    pendulum of 1e-8 kg integrated 27000 periods between two checks of the step bound (an
    outside audit). Times and velocities in the result are in seconds."""
    def section(t, x):
        return x[2]

    def runaway(t, x):
        return 50 * np.pi - max(abs(x[0]), abs(x[1]))

    section.direction = -1.0
    runaway.terminal = True
    check_pendulum(pendulum)
    P, H, x = _checked_start(P, H, state0)
    rtol, atol = _check_integration(method, rtol, atol)
    tol = _check_cycle_tol(tol)
    max_steps = check_integer("max_steps", max_steps, 1, LIMIT_CYCLE_MAX_STEPS)
    tau = time_unit(pendulum)
    # bounded in simulated time as simulate is (an outside audit: t_max = 1e300 and chunks
    # of 1e-300 s integrated for minutes)
    for name, value, low, high in (("t_max", t_max, 0.0, SIMULATE_MAX_TIME_UNITS),
                                   ("chunk", chunk, 1e-3, SIMULATE_MAX_TIME_UNITS)):
        if value is not None and not low * tau < check_real(name, value) <= high * tau:
            raise ParameterError(f"{name} must be in ({low * tau:.4g}, {high * tau:.4g}] s "
                                 f"({low:g} to {high:g} time units l2 sqrt(m2/k2) of this "
                                 f"pendulum), got {value!r}")
    unit = in_time_unit(pendulum)
    x = x * np.array([1.0, 1.0, tau, tau])
    t_end = TRANSIENT_T_MAX if t_max is None else t_max / tau
    step = TRANSIENT_CHUNK if chunk is None else chunk / tau
    t0 = 0.0
    crossings: list[tuple[float, NDArray]] = []
    steps = 0
    while t0 < t_end:
        with _overflow_refused():
            sol = solve_ivp(_counted(unit.motion_at(P, H)),
                            (t0, t0 + step), x,
                            method=method, events=(section, runaway), rtol=rtol, atol=atol)
        if not sol.success:
            raise ConvergenceError(f"time integration failed: {sol.message}")
        if sol.status == 1 or np.max(np.abs(sol.y[:2])) > 50 * np.pi:
            raise ConvergenceError(f"the motion runs away (|alpha| > 50 pi at t = "
                                   f"{sol.t[-1] * tau:.4g} s): no limit cycle (divergence?)")
        steps += sol.t.size
        if steps > max_steps:
            raise ConvergenceError(f"no limit cycle within {max_steps} integration steps "
                                   f"(t = {sol.t[-1] * tau:.4g} s simulated)")
        for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
            if ye[0] > 0:  # maxima of alpha1 only
                crossings.append((float(te), ye.copy()))
        found = _converged_cycle(crossings, tol)
        if found is not None:
            tc, yc, T = found
            a1, a2 = _amplitudes(unit, P, H, yc, T, method, rtol, atol)
            cycle = LimitCycle(a1, a2, T, tuple(float(v) for v in yc), tc, len(crossings))
            return cycle.in_time_scale(1.0 / tau)
        x, t0 = sol.y[:, -1], sol.t[-1]
    last = ""
    if len(crossings) >= 2:
        gap = float(np.max(np.abs(crossings[-1][1] - crossings[-2][1])))
        last = (f"; last two section crossings differ by {gap:.2g} "
                f"(alpha1 = {crossings[-1][1][0]:.4g} rad)")
    raise ConvergenceError(f"no limit cycle converged to {tol:g} within t = {t_end * tau:g} s "
                           f"simulated{last}")


#: Most integration steps :func:`limit_cycle` may be given (``max_steps``; its default 2e6).
LIMIT_CYCLE_MAX_STEPS = 10**8
#: Tolerances of a converged cycle (relative agreement of two section crossings, or of a
#: continued orbit's load): below 1e-13 two crossings differ by their own rounding and the
#: test is never met (an outside audit: 1e-20 integrated to the time bound); above 1e-2 it
#: accepts a transient as a cycle.
CYCLE_TOL_RANGE = (1e-13, 1e-2)


def _check_cycle_tol(tol: object, name: str = "tol") -> float:
    tol = check_real(name, tol)
    if not CYCLE_TOL_RANGE[0] <= tol <= CYCLE_TOL_RANGE[1]:
        raise ParameterError(f"{name} must be in [{CYCLE_TOL_RANGE[0]:g}, "
                             f"{CYCLE_TOL_RANGE[1]:g}] (relative), got {tol!r}")
    return tol


#: Largest number of maxima of alpha1 per period that :func:`limit_cycle` recognises (an
#: outside audit found stable cycles with two and three, e.g. c1/c2 = 10 at 2.3 P_flu).
MAX_MAXIMA_PER_PERIOD = 4


def _converged_cycle(crossings: list[tuple[float, NDArray]], tol: float
                     ) -> tuple[float, NDArray, float] | None:
    """``(t, state, period)`` if the last section crossings repeat with ``k`` maxima of
    alpha1 per period (the smallest ``k <= MAX_MAXIMA_PER_PERIOD``), else None.

    The crossings of one phase, ``y_j`` every ``k``-th, approach the cycle geometrically,
    ``|y_j - y*| ~ r^j``; the distance of the last one from the cycle is estimated as
    ``d r/(1 - r)`` from the last two differences ``d = |y_j - y_j-1|``,
    ``r = d/|y_j-1 - y_j-2|``, and must be below ``tol`` (relative), as the change of the
    period. Near the Hopf point ``r -> 1`` (the cycle attracts at ``2 Re s``): the last
    difference alone would stop ``r/(1 - r)`` times too early (60x at r = 0.983, measured by an
    outside audit as a 4.6e-6 amplitude error at tol 1e-7)."""
    def differences(k: int) -> tuple[float, float, float, float, NDArray]:
        (ta, ya), (tb, yb), (tc, yc) = crossings[-1 - 2 * k], crossings[-1 - k], crossings[-1]
        scale = np.maximum(np.abs(yc), 1e-3 * np.max(np.abs(yc)))
        return (float(np.max(np.abs(yc - yb) / scale)), float(np.max(np.abs(yb - ya) / scale)),
                tc - tb, tb - ta, yc)

    # The number of maxima per period: the smallest lag at which the crossings nearly repeat
    # (1e-3), then the convergence test on that lag only, so that a simple cycle whose last
    # differences are at round-off is never taken for one of twice its period.
    for k in range(1, MAX_MAXIMA_PER_PERIOD + 1):
        if len(crossings) < 2 * k + 1:  # three crossings of one phase
            return None
        d, d_prev, T2, T1, yc = differences(k)
        if d <= 1e-3:
            break
    else:
        return None
    if d > tol or abs(T2 - T1) > tol * T2:
        return None
    r = d / d_prev if d_prev > 0 else 0.0
    # contracting: the distance left d r/(1 - r); not contracting: only round-off is accepted
    if (r < 1 and d * r / (1 - r) <= tol) or d <= 1e-2 * tol:
        return crossings[-1][0], yc, T2
    return None


#: Shooting's residual bound |phi_T(x0) - x0| (states in the pendulum's time unit), and the
#: round-off level below which a stalled solve counts as converged (the integrations' rtol is
#: 1e-12; measured residuals at the solution 5e-16).
_SHOOTING_RESIDUAL, _SHOOTING_ROUND_OFF = 1e-9, 1e-12


def shoot_periodic_orbit(pendulum: ZieglerPendulum, P: float, guess: LimitCycle,
                         H: float = 0.0, rtol: float = 1e-12, atol: float = 1e-14) -> LimitCycle:
    """Periodic orbit by shooting (independent of the transient): unknowns ``(alpha1, alpha2,
    alpha2_dot, T)`` with ``alpha1_dot = 0`` on the section; residual ``phi_T(x0) - x0``.

    Solved in the pendulum's time unit (:func:`in_time_unit`: the residual's bound and
    ``atol`` then mean the same for any unit of time); ``guess`` and the result in seconds."""
    tau = time_unit(pendulum)
    pendulum, guess = in_time_unit(pendulum), guess.in_time_scale(tau)
    x_guess = np.asarray(guess.section_state, dtype=float)

    def residual(z):
        # Newton may try any period: only (T/2, 2T) of the guess is integrated, so a wild step
        # costs one rejected evaluation, never an unbounded integration.
        if not (0.5 * guess.period_s < z[3] < 2.0 * guess.period_s and np.isfinite(z).all()):
            return np.full(4, 1e3)
        x0 = np.array([z[0], z[1], 0.0, z[2]])
        sol = simulate(pendulum, P, x0, z[3], H=H, rtol=rtol, atol=atol)
        return sol.y[:, -1] - x0

    z0 = np.array([x_guess[0], x_guess[1], x_guess[3], guess.period_s])
    res = root(residual, z0, method="hybr", options={"xtol": 1e-13})
    worst = float(np.max(np.abs(res.fun)))
    # MINPACK's "not making good progress" also ends a solve that sits at the integration's
    # round-off, its steps below xtol out of reach: a residual there is a solution (an outside
    # audit's own pendulum: residual 5e-16 reported as failed, at 1.2 and 1.5 P_flu)
    if not (worst <= _SHOOTING_RESIDUAL and (res.success or worst <= _SHOOTING_ROUND_OFF)):
        raise ConvergenceError(f"shooting did not converge: {res.message.strip()} "
                               f"(residual {worst:.3g}, bound {_SHOOTING_RESIDUAL:g})")
    x0 = np.array([res.x[0], res.x[1], 0.0, res.x[2]])
    a1, a2 = _amplitudes(pendulum, P, H, x0, res.x[3], "DOP853", rtol, atol)
    cycle = LimitCycle(a1, a2, float(res.x[3]), tuple(float(v) for v in x0), 0.0, 0)
    return cycle.in_time_scale(1.0 / tau)


def tip_acceleration(pendulum: ZieglerPendulum, states: NDArray, P: float,
                     H: float = 0.0) -> NDArray:
    """Acceleration of the loaded end C [m/s^2], shape (n, 2), from states (n, 4) of eq. (10)."""
    check_pendulum(pendulum)
    P, H = check_real("P", P), check_real("H", H)
    x = np.atleast_2d(check_finite_reals("states", states))
    if x.ndim != 2 or x.shape[1] != 4:
        raise ParameterError(f"states must have shape (n, 4) ([a1, a2, a1_dot, a2_dot] rows), "
                             f"got {np.shape(states)}")
    x = x.T
    dx = pendulum.equations_of_motion(x, P, H)
    a1, a2, w1, w2 = x
    acc1, acc2 = dx[2], dx[3]
    l1, l2 = pendulum.l1, pendulum.l2
    ax = (-l1 * (acc1 * np.sin(a1) + w1**2 * np.cos(a1))
          - l2 * (acc2 * np.sin(a2) + w2**2 * np.cos(a2)))
    ay = (l1 * (acc1 * np.cos(a1) - w1**2 * np.sin(a1))
          + l2 * (acc2 * np.cos(a2) - w2**2 * np.sin(a2)))
    return np.stack([ax, ay], axis=-1)


# ---------------------------------------------------------------------- near the Hopf point
def linear_flutter_mode(pendulum: ZieglerPendulum, P_flu: float) -> tuple[float, NDArray]:
    """Pulsation ``Omega`` [rad/s] and real section state of the linear flutter mode at the
    damped flutter load ``P_flu`` [N]: the eigenvector of the eigenvalue ``s = i Omega`` of the
    first-order form, phased so that ``alpha1`` is at a maximum (``alpha1_dot = 0``) and scaled
    to ``alpha1 = 1``: ``[1, alpha2, 0, alpha2_dot]``."""
    from flutterfriction.analysis.stability import first_order_matrix

    A = first_order_matrix(pendulum.mass_matrix(),
                           pendulum.stiffness_matrix() + pendulum.geometric_matrix(P_flu),
                           pendulum.viscosity_matrix())
    s, V = np.linalg.eig(A)
    i = int(np.argmax(s.real + 1e-300 * (s.imag > 0)))  # the critical pair; either member
    v = V[:, i] / V[0, i]  # alpha1 component real, = 1
    return float(abs(s[i].imag)), np.array([1.0, v[1].real, 0.0, v[3].real])


def _amplitude_orbit(pendulum: ZieglerPendulum, A: float, z0: NDArray, rtol: float,
                     atol: float, T_max: float, P_max: float) -> NDArray:
    """Periodic orbit through the section point ``alpha1 = A``, ``alpha1_dot = 0``: solves for
    ``z = (alpha2, alpha2_dot, T, P)`` with ``phi_T(x0; P) = x0`` (Newton, ``hybr``). Fixing the
    amplitude instead of the load keeps Newton away from the trivial orbit x = 0 (a solution
    for every T and P) that a load-parametrised shooting meets near the Hopf point."""
    def residual(z: NDArray) -> NDArray:
        # Only periods in (0, T_max) and loads in (0, P_max) are integrated: each evaluation
        # is bounded (a huge trial load would make one period arbitrarily stiff).
        # And no trial state of wild size (|alpha2|, its rate > 1e3: minutes of integration)
        # And no period below T_max/32 (1/8 of the linear flutter period; the §2.9 cycles
        # stay above 0.75 of it): the residual vanishes with T, so a period shrinking to 0 is
        # a spurious solution (a review found 6.7e-18 T0 accepted from a poor guess).
        if not (T_max / 32 < z[2] < T_max and 0 < z[3] < P_max and np.isfinite(z).all()
                and abs(z[0]) < 1e3 and abs(z[1]) < 1e3):
            return np.full(4, 1e3)
        x0 = np.array([A, z[0], 0.0, z[1]])
        sol = simulate(pendulum, float(z[3]), x0, float(z[2]), rtol=rtol, atol=atol)
        return (sol.y[:, -1] - x0) / A

    res = root(residual, z0, method="hybr", options={"xtol": 1e-12, "maxfev": 200})
    # The residual is relative to the amplitude; 1e-8 is far above the integration error
    # (rtol 1e-12 per period) and far below the 1e-6 agreement asked of the check. It alone
    # decides: hybr reports "not making good progress" when its steps stall on a residual
    # already at round-off (an outside audit: 6e-16 at 1.05 P_flu of the §2.9 pendulum was
    # refused), and its success flag says nothing about a residual of that size.
    if not (np.max(np.abs(res.fun)) <= 1e-8 and T_max / 32 < res.x[2] < T_max):
        raise ConvergenceError(f"amplitude-parametrised shooting did not converge at "
                               f"alpha1 = {A:.3g} rad: {res.message}")
    return res.x


def limit_cycle_by_continuation(pendulum: ZieglerPendulum, P: float, P_flu: float, *,
                                A_start: float = 1e-3, tol: float = 1e-10,
                                max_steps: int = 40, rtol: float = 1e-12,
                                atol: float = 1e-14) -> LimitCycle:
    """The limit cycle at load ``P`` > ``P_flu`` by continuation from the linear flutter mode.

    The orbit at the small amplitude ``A_start`` (rad) is found by amplitude-parametrised
    shooting started from the linear flutter mode at ``P_flu`` (period ``2 pi/Omega``); the
    amplitude is then adjusted by secant steps on ``A^2`` against the load (the Hopf normal
    form ``P - P_flu ~ A^2``), each step's orbit started from the previous one scaled, with the
    amplitude at most doubled per step, until the orbit's load matches ``P`` to ``tol``
    (relative). At most ``max_steps`` shooting solves: otherwise :class:`ConvergenceError`.
    Works arbitrarily close above ``P_flu``, where the transient of :func:`limit_cycle` decays
    like ``exp(-Re s t)`` with ``Re s ~ P - P_flu``. Shooting integrates periods below
    ``4 (2 pi / Omega)`` and trial loads below ``4 max(P, P_flu)`` only (the cycles of the
    §2.9 pendulum shorten with amplitude)."""
    check_pendulum(pendulum)
    tol = _check_cycle_tol(tol)
    _check_tolerances(rtol, atol)
    max_steps = check_integer("max_steps", max_steps, 1, 10_000)
    A_start = check_positive("A_start", A_start, "rad")
    omega, mode = linear_flutter_mode(pendulum, P_flu)
    if not np.all(np.abs(mode) < 1e6):
        # the flutter mode hardly moves alpha1 (an outside audit: c2 = 0 gave alpha2/alpha1
        # ~ 2e12 and a start state that integrated for minutes): alpha1's amplitude cannot
        # parametrise its cycle
        raise ConvergenceError(f"the flutter mode barely moves alpha1 (|alpha2/alpha1| = "
                               f"{abs(mode[1]):.3g}): the continuation in alpha1's amplitude "
                               "cannot follow its cycle")
    T_max = 4 * 2 * np.pi / omega
    P_max = 4 * max(P, P_flu)
    A = A_start
    z = _amplitude_orbit(pendulum, A, np.array([A * mode[1], A * mode[3], 2 * np.pi / omega,
                                                P_flu]), rtol, atol, T_max, P_max)
    history = [(A, z)]
    for _ in range(max_steps):
        A_cur, z_cur = history[-1]
        err = z_cur[3] - P
        if abs(err) <= tol * P:
            x0 = np.array([A_cur, z_cur[0], 0.0, z_cur[1]])
            a1, a2 = _amplitudes(pendulum, z_cur[3], 0.0, x0, z_cur[2], "DOP853", rtol, atol)
            return LimitCycle(a1, a2, float(z_cur[2]), tuple(float(v) for v in x0), 0.0, 0)
        if len(history) >= 2:  # secant on A^2 against P
            (A0, z0), (A1, z1) = history[-2], history[-1]
            slope = (A1**2 - A0**2) / (z1[3] - z0[3])
            A2sq = A1**2 + (P - z1[3]) * slope
        else:  # normal form from the first orbit: A^2 proportional to P - P_flu
            A2sq = A_cur**2 * (P - P_flu) / (z_cur[3] - P_flu)
        A_new = float(np.sqrt(A2sq)) if A2sq > 0 else 0.5 * A_cur
        A_new = min(max(A_new, 0.5 * A_cur), 2.0 * A_cur)
        guess = np.array([z_cur[0] * A_new / A_cur, z_cur[1] * A_new / A_cur, z_cur[2],
                          z_cur[3]])
        history.append((A_new, _amplitude_orbit(pendulum, A_new, guess, rtol, atol, T_max,
                                                        P_max)))
    # (10 digits, and how near P_flu: "did not reach P = 2.61 N ... last orbit at P = 2.61 N"
    # said nothing, one ulp above P_flu = 2.61; an outside audit)
    raise ConvergenceError(f"continuation from the flutter mode did not reach P = {P:.10g} N "
                           f"in {max_steps} steps (last orbit at P = {history[-1][1][3]:.10g} "
                           f"N; P - P_flu = {P - P_flu:.3g} N)")


def section_return(pendulum: ZieglerPendulum, P: float, state: ArrayLike, period: float,
                   method: str = "Radau", rtol: float = 1e-10,
                   atol: float = 1e-12) -> tuple[float, NDArray]:
    """Time and state of the return to ``state`` on the section ``alpha1_dot = 0``
    (downwards, ``alpha1 > 0``) between half and one and a half ``period`` [s], with another
    integrator (Radau, analytic Jacobian) than the shooting: an independent check of a periodic
    orbit. Of the crossings in that window, the one nearest ``state`` (a cycle may have two or
    three maxima of alpha1 per period: the first crossing after half a period was 27 % short
    on one, found by an outside audit)."""
    check_pendulum(pendulum)
    period = check_positive("period", period, "s")  # (not simulate's t_end: an audit)
    limit = SIMULATE_MAX_TIME_UNITS * time_unit(pendulum) / 1.5  # 1.5 periods are simulated
    if period > limit:
        raise ParameterError(f"period must be in (0, {limit:.4g}] s (1.5 periods within the "
                             f"{SIMULATE_MAX_TIME_UNITS:g} time units l2 sqrt(m2/k2) simulate "
                             f"allows), got {period:g}")
    section = from_the_section(lambda t, x: x[2])  # ``state`` is on the section
    x0 = np.asarray(state, dtype=float)
    sol = simulate(pendulum, P, x0, 1.5 * period, method=method, rtol=rtol, atol=atol,
                   events=section)
    hits = [(float(t), y) for t, y in zip(sol.t_events[0], sol.y_events[0], strict=True)
            if t > 0.5 * period and y[0] > 0]
    if not hits:
        raise ConvergenceError("the orbit does not return to the Poincare section within "
                               f"1.5 periods ({1.5 * period:.4g} s)")
    return min(hits, key=lambda h: float(np.max(np.abs(h[1] - x0))))


#: Simulated-time budget, in the pendulum's time unit ``tau = l2 sqrt(m2/k2)``, above which
#: the transient is not attempted (the continuation from the flutter mode is used instead):
#: the transient needs about ``(ln(1/alpha0) + ln(1/tol)/2) / Re s(P)`` to grow from
#: ``alpha0`` and settle (the cycle attracts at about ``2 Re s`` near the Hopf point);
#: measured on the §2.9 pendulum (tau = 0.049 s) at 1.5 P*_flu: estimate 13 s = 264 tau,
#: actual 39 s, 4 s wall. 2000 tau (100 s there) keeps the transient under about a minute of
#: wall time on this machine; nearer onset the continuation takes 3-10 s. In units of tau, so
#: that the work does not depend on the unit of time: in seconds, a pendulum of 1e-8 kg
#: (tau = 1e-4 s) integrated 20 s chunks of 27000 periods each and never returned (an
#: outside audit), and one of 100 kg was refused what the same pendulum in grams answers.
TRANSIENT_BUDGET = 2000.0
#: The transient's bound and the chunk between convergence checks, in units of tau (600 s and
#: 20 s on the §2.9 pendulum).
TRANSIENT_T_MAX, TRANSIENT_CHUNK = 12000.0, 400.0


def time_unit(pendulum: ZieglerPendulum) -> float:
    """``tau = l2 sqrt(m2/k2)`` [s]: the time unit of eq. (17), ``omega^2 = m2 l2^2 Omega^2/k2``."""
    return pendulum.l2 * math.sqrt(pendulum.m2 / pendulum.k2)


def in_time_unit(pendulum: ZieglerPendulum) -> ZieglerPendulum:
    """The same pendulum with time measured in ``tau`` (masses / tau^2, viscosities / tau):
    eq. (10) is ``M a_tt + C a_t + F(a, P) = 0`` with every inertial term linear in the masses
    and quadratic in d/dt, so its motions are the original's at ``t = tau t'``; loads and
    angles are unchanged, times and periods are divided by ``tau``."""
    tau = time_unit(pendulum)
    return replace(pendulum, m1=pendulum.m1 / tau**2, m2=pendulum.m2 / tau**2,
                   m3=pendulum.m3 / tau**2, c1=pendulum.c1 / tau, c2=pendulum.c2 / tau)


def ziegler_limit_cycle(pendulum: ZieglerPendulum, P: float, alpha0: float, *,
                        tol: float = 1e-8, P_name: str = "P",
                        alpha0_name: str = "alpha0", check: bool = True) -> dict:
    """The limit cycle of the viscous pendulum (eq. 10 with hinge viscosity) at follower load
    ``P`` [N], in the flutter interval of the damped pendulum, from ``alpha1 = alpha2 =
    alpha0`` [rad].

    Refused (:class:`ParameterError`, naming ``P_name``/``alpha0_name``): a pendulum outside
    the model's numerical range, no viscosity, ``alpha0`` zero or beyond half a turn, ``P``
    outside ``(P_flu, P_div)`` (below the damped flutter load the equilibrium is stable: no
    cycle; above the damped divergence load the motion is not a flutter cycle).

    Far enough above ``P_flu`` the transient from ``alpha0`` is integrated until the Poincaré
    section converges (:func:`limit_cycle`; the cycle attracts) and checked by shooting. Near
    ``P_flu`` (estimated transient longer than :data:`TRANSIENT_BUDGET` time units) or if the
    transient does not converge, the cycle is continued from the linear flutter mode
    (:func:`limit_cycle_by_continuation`) and checked by a section return with Radau. All
    integrations are bounded by simulated time or step counts, and run in the pendulum's time
    unit (:func:`in_time_unit`): the work and the answer do not depend on the unit of time.
    Times in the result are in seconds. ``check=False`` leaves out the independent check
    (shooting or section return): for callers that check the cycle otherwise.

    Raises
    ------
    ParameterError
        As above, before any integration.
    ConvergenceError
        Neither the transient nor the continuation converged (the message gives both).
    """
    from flutterfriction.analysis.ziegler import (
        damped_divergence_load,
        damped_flutter_load,
        is_damped,
        spectrum,
    )

    check_pendulum(pendulum)
    P = check_real(P_name, P)
    alpha0 = check_real(alpha0_name, alpha0)
    tol = _check_cycle_tol(tol)
    if not 0 < abs(alpha0) <= np.pi:
        raise ParameterError(f"{alpha0_name} must be non-zero and within half a turn "
                             f"(0 < |alpha0| <= 180 deg), got {np.degrees(alpha0):g} deg")
    if abs(alpha0) < NORMAL_MIN:  # (1e-320 deg was taken, its digits lost; an outside audit)
        raise ParameterError(f"{alpha0_name} must be at least {NORMAL_MIN:.3g} rad "
                             f"({math.degrees(NORMAL_MIN):.3g} deg) in magnitude (a subnormal "
                             f"double has lost digits), got {math.degrees(alpha0):.3g} deg")
    pendulum.check_numerical_range()
    # Eq. (10) in the time unit tau multiplies two torques (the mass matrix's determinant is
    # ~ k2^2 there): k2 = 1e-170 N m underflowed it to 0 (a ZeroDivisionError), 1e-160 to
    # subnormals that integrated for minutes (an outside audit); the linear analyses, on the
    # groups of eq. (17), are not limited so.
    lo, hi = DYNAMICS_TORQUE_RANGE
    if not math.log10(lo) <= math.log10(pendulum.k2) <= math.log10(hi):
        raise ParameterError(
            f"k2 must be in [{lo:g}, {hi:g}] N m for the nonlinear dynamics (eq. 10 forms "
            f"products of two torques, which leave the doubles beyond), got {pendulum.k2:g}")
    if not is_damped(pendulum):
        raise ParameterError("c1, c2: a limit cycle needs hinge viscosity (c1 or c2 > 0)")
    P_flu = damped_flutter_load(pendulum, "routh")
    P_div = damped_divergence_load(pendulum)
    if not P_flu < P < P_div:
        # all the digits where the short forms would read alike (an outside audit: "must lie
        # in (2.61, 9.91) N, got 2.61" for the flutter load 2.6100000004)
        lo, hi = (shown_beside(b, (P,), ".10g") for b in (P_flu, P_div))
        raise ParameterError(
            f"{P_name} must lie in the damped flutter interval ({lo}, {hi}) N "
            f"(flutter load P_flu, divergence load P_div), got "
            f"{shown_beside(P, (P_flu, P_div), '.10g')}")
    tau = time_unit(pendulum)
    unit = in_time_unit(pendulum)  # every integration below in units of tau
    growth = float(spectrum(unit, P).real.max())
    # (Re s may round to 0 just above P_flu at tiny viscosity: an infinite estimate, no
    # RuntimeWarning on stderr; an outside audit)
    with np.errstate(divide="ignore"):
        estimate = float(np.float64(np.log(1 / abs(alpha0)) + 0.5 * np.log(1 / tol)) / growth)
    notes = []
    if estimate <= TRANSIENT_BUDGET:
        try:
            # each phase (transient and its check; continuation and its check) within
            # LIMIT_CYCLE_EVALUATIONS evaluations of eq. (10): never an unbounded run
            with _evaluation_budget(LIMIT_CYCLE_EVALUATIONS):
                return _by_transient(pendulum, P, alpha0, tol, check, P_flu, P_div)
        except ConvergenceError as exc:
            notes.append(f"transient: {exc} (times in units of tau = {tau:.4g} s)")
    else:
        notes.append(f"transient skipped: estimated {estimate * tau:.3g} s simulated "
                     f"> {TRANSIENT_BUDGET * tau:.3g} s = {TRANSIENT_BUDGET:g} tau "
                     f"(tau = l2 sqrt(m2/k2) = {tau:.3g} s; Re s = {growth / tau:.3g} 1/s)")
    try:
        with _evaluation_budget(LIMIT_CYCLE_EVALUATIONS):
            cycle = limit_cycle_by_continuation(unit, P, P_flu)
            section = (section_return(unit, P, cycle.section_state, cycle.period_s)
                       if check else None)
    except ConvergenceError as exc:
        raise ConvergenceError("; ".join([*notes, f"continuation: {exc}"])) from None
    out = {"method": "continuation from the linear flutter mode (amplitude-parametrised "
                     "shooting)",
           "alpha1_amplitude_rad": cycle.alpha1_amplitude_rad,
           "alpha2_amplitude_rad": cycle.alpha2_amplitude_rad,
           "period_s": cycle.period_s * tau,
           "transient_s": None, "P_flu": P_flu, "P_div": P_div, "notes": notes}
    if section is not None:
        t_ret, x_ret = section
        out["section_check"] = {"period_s": t_ret * tau, "alpha1_rad": float(x_ret[0]),
                                "method": "one return to the section (Radau, rtol 1e-10)"}
    return out


def _by_transient(pendulum: ZieglerPendulum, P: float, alpha0: float, tol: float,
                  check: bool, P_flu: float, P_div: float) -> dict:
    """:func:`ziegler_limit_cycle` by the transient on the Poincaré section (and shooting)."""
    cycle = limit_cycle(pendulum, P, [alpha0, alpha0, 0.0, 0.0], tol=tol)  # in tau
    out = {"method": "transient on the Poincare section (DOP853)",
           "alpha1_amplitude_rad": cycle.alpha1_amplitude_rad,
           "alpha2_amplitude_rad": cycle.alpha2_amplitude_rad,
           "period_s": cycle.period_s, "transient_s": cycle.transient_s,
           "P_flu": P_flu, "P_div": P_div}
    if check:
        shot = shoot_periodic_orbit(pendulum, P, cycle)
        out["shooting_check"] = {"period_s": shot.period_s,
                                 "alpha1_amplitude_rad": shot.alpha1_amplitude_rad}
    return out
