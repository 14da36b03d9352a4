"""The nonlinear rod's orbit by DOP853, compiled (:func:`flutterfriction.models.rod_kernel.
dop853_orbit`): what ``scipy.integrate.solve_ivp(model.rhs_at(P), (0, T), y,
method="DOP853", rtol=rtol, atol=atol, dense_output=...)`` returns, by the same method (the
first steps agree to the last digits; then round-off in the error estimate moves the step-size
control, so the step grids differ slightly: step and right-hand-side counts within a few %,
the same accuracy, tested), at about 40 % of the CPU time on the 4-element rod (measured in
the branch of limit cycles; the Python of scipy's steps, not the rod's equations, was most of
it)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from flutterfriction.errors import ConvergenceError, ParameterError
from flutterfriction.models.rod_nonlinear import _NOT_POSITIVE, NonlinearRod

_TOO_SMALL = "Required step size is less than spacing between numbers."
#: scipy's floor for rtol (validate_tol: 100 eps).
MIN_RTOL = 100 * np.finfo(float).eps


#: The orbits' largest rtol: the cycles' Newton and Floquet multipliers need the orbit to
#: better than 1e-3 (the scenes use 1e-7 ... 1e-10).
MAX_RTOL = 1e-3


def check_orbit_rtol(name: str, rtol: Any) -> float:
    """``rtol`` as a float in [:data:`MIN_RTOL`, :data:`MAX_RTOL`], else a
    :class:`ParameterError` naming ``name`` (a scene's parameter, refused before any work)."""
    try:
        value = float(rtol)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number, got {rtol!r}") from None
    if not MIN_RTOL <= value <= MAX_RTOL:
        raise ParameterError(f"{name} must be in [{MIN_RTOL:.3g}, {MAX_RTOL:g}] (the orbit "
                             f"integrator's range: 100 machine epsilons as scipy's solve_ivp, "
                             f"and the cycles' Newton), got {rtol!r}")
    return value


@dataclass
class DenseOrbit:
    """The orbit between its steps: DOP853's interpolant of order 7 on each step, evaluated
    as ``scipy.integrate.OdeSolution`` does (the step holding ``t``, the earlier one at a step
    boundary; ``t`` outside [0, T] extrapolates the first or last step)."""

    ts: NDArray  # (m + 1,) step boundaries
    y_old: NDArray  # (m, N) state at each step's start
    F: NDArray  # (m, 7, N) scipy's Dop853DenseOutput.F of each step

    def __call__(self, t) -> NDArray:
        t = np.asarray(t, dtype=float)
        if t.ndim > 1:
            raise ParameterError(f"t must be a number or a 1-D array of times [s], got shape "
                                 f"{t.shape}")
        seg = np.clip(np.searchsorted(self.ts, t, side="left") - 1, 0, len(self.F) - 1)
        h = self.ts[seg + 1] - self.ts[seg]
        x = ((t - self.ts[seg]) / h)[..., None]
        F = self.F[seg]  # (..., 7, N)
        y = np.zeros(F.shape[:-2] + F.shape[-1:])
        for i in range(F.shape[-2]):  # Dop853DenseOutput._call_impl's order
            y += F[..., F.shape[-2] - 1 - i, :]
            y *= x if i % 2 == 0 else 1 - x
        y += self.y_old[seg]
        return y.T


@dataclass
class Orbit:
    """``solve_ivp``'s answer: ``t`` (m + 1,), ``y`` (N, m + 1), ``sol`` (with
    ``dense_output``), ``success``, ``message``, ``nfev``."""

    t: NDArray
    y: NDArray
    sol: DenseOrbit | None
    success: bool
    message: str
    nfev: int


def integrate_orbit(model: NonlinearRod, y: NDArray, T: float, P: float, rtol: float,
                    atol: float, dense_output: bool = False) -> Orbit:
    """The rod's motion from the state ``y`` over ``[0, T]`` [s] under the follower load ``P``
    [N] by DOP853 with tolerances ``rtol``, ``atol`` (as ``solve_ivp``'s): steps, states and,
    with ``dense_output``, the interpolant. A mass matrix that stops being positive definite
    (a state far outside the model's range) raises :class:`ConvergenceError`, as
    :meth:`NonlinearRod.rhs_at` does."""
    # numba: imported where used
    from flutterfriction.models.rod_kernel import DOP853_COEFFICIENTS, dop853_orbit

    y = np.array(y, dtype=float).ravel()
    if y.shape != (2 * model.n_dof,):
        raise ParameterError(f"the state must have shape ({2 * model.n_dof},) (q and v of "
                             f"{model.n_dof} nodes), got {np.shape(y)}")
    if not np.all(np.isfinite(y)):
        raise ParameterError("the state must be finite (q [rad] and v [rad/s] of every node)")
    T = float(T)
    if not (T > 0 and np.isfinite(T)):
        raise ParameterError(f"T must be a finite positive time [s], got {T!r}")
    rtol, atol = float(rtol), float(atol)
    # scipy's validate_tol raises rtol to 100 eps; below it the steps (no step cap in DOP853)
    # grow without bound (rtol 1e-20 ran > 60 s and 400 MB; an outside review): refused.
    if not MIN_RTOL <= rtol < 1:
        raise ParameterError(f"rtol must be in [{MIN_RTOL:g}, 1) (100 machine epsilons, as "
                             f"scipy's solve_ivp), got {rtol!r}")
    if not (atol >= 0 and np.isfinite(atol)):
        raise ParameterError(f"atol must be a finite number >= 0, got {atol!r}")
    status, ts, ys, F, nfev = dop853_orbit(y, T, rtol, atol, bool(dense_output),
                                           *DOP853_COEFFICIENTS, *model.kernel_args(P))
    if status == 2:
        raise ConvergenceError(_NOT_POSITIVE)
    sol = DenseOrbit(ts, ys[:-1], F) if dense_output and status == 0 else None
    message = ("The solver successfully reached the end of the integration interval."
               if status == 0 else _TOO_SMALL)
    return Orbit(t=ts, y=ys.T, sol=sol, success=status == 0, message=message, nfev=int(nfev))
