"""Periodic orbits of the nonlinear Beck rod and their continuation from the Hopf point
(beyond the chapter's §2.9: the branch of limit cycles on which Figs. 15–17's cycle lies).

A cycle is a state ``y`` on the Poincaré section (lateral tip velocity 0, the tip at its
lateral maximum), a period ``T`` and a load ``P`` with ``phi_T(y; P) = y``. Newton's method on
these equations uses the *exact* Jacobian, from the variational equations integrated with the
orbit (the flow's derivatives ``Phi = d phi_T / d y`` and ``S = d phi_T / d P``; the right-hand
side's Jacobian differentiated by hand and compiled, equal to complex steps to rounding), so
it converges quadratically to the integrator's accuracy instead of stalling at a
finite-difference noise floor. The same ``Phi`` at the converged cycle gives the Floquet
multipliers without another integration.

The slow (amplitude) multiplier near the Hopf point is ``1 - mu ~ 1e-5``: as an eigenvalue of
``Phi`` it sits next to the trivial multiplier 1 and is ill-conditioned (a near-coalescence:
its error is the square root of ``Phi``'s). It is computed instead from the linearised return
map on the section, ``Pi = (I - f c^T / (c . f)) Phi`` restricted to ``c . dy = 0`` (``c`` the
section's gradient, ``f`` the flow direction), whose eigenvalues are the non-trivial
multipliers; ``mu - 1`` are then the eigenvalues of ``Q^T (Pi - I) Q`` (``Q`` an orthonormal
basis of the section), free of the cancellation in ``1 - mu``.

Every loop is bounded by iteration and point counts, never by the wall clock; running out of
a budget is recorded (``CycleBranch.stopped_by``) and the callers check it.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import ODEintWarning, odeint

from flutterfriction.analysis.damped import flutter_onset, polish_flutter_crossing
from flutterfriction.analysis.rod_orbit import check_orbit_rtol, integrate_orbit
from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_integer,
    check_positive,
    check_real,
)
from flutterfriction.models.rod import Rod
from flutterfriction.models.rod_nonlinear import NonlinearRod, prolongation

_H = 1e-30  # complex step: h^2 is far below rounding, and no subtraction cancels


def _stepped_rhs(model: NonlinearRod, Y: NDArray, P: float) -> NDArray:
    """The right-hand side at the ``m`` states ``Y`` (N, m), each with its ``N + 1`` complex
    steps (one per state component, one in the load), as one batch: shape (N, m, N + 1)."""
    N, m = Y.shape
    Z = np.empty((N, m, N + 1), dtype=complex)
    Z[:] = Y[:, :, None]
    Z[:, :, :N] += 1j * _H * np.eye(N)[:, None, :]
    loads = np.full((m, N + 1), P, dtype=complex)
    loads[:, N] += 1j * _H
    return model.rhs(0.0, Z.reshape(N, -1), loads.ravel()).reshape(N, m, N + 1)


def rhs_derivatives(model: NonlinearRod, y: NDArray, P: float
                    ) -> tuple[NDArray, NDArray, NDArray]:
    """``(f, J, f_P)``: the first-order right-hand side at ``y``, its Jacobian ``df/dy`` and
    ``df/dP``, from ``N + 1`` complex steps evaluated as one batch (every operation of the
    equations of motion is analytic, so ``Im f(y + i h e) / h`` is exact to rounding)."""
    N = y.size
    F = _stepped_rhs(model, y[:, None], P)[:, 0]
    return F[:, N].real, F[:, :N].imag / _H, F[:, N].imag / _H


def section_value(model: NonlinearRod, y: NDArray):
    """The section function: lateral tip velocity (zero at the lateral extremes of the tip)."""
    n = model.n_dof
    return model.tip_lateral_velocity(y[:n], y[n:])


def tip_lateral(model: NonlinearRod, y: NDArray):
    """Lateral tip displacement [m] (the cycle's amplitude when ``y`` is on the section)."""
    return model.tip_position(y[: model.n_dof])[1]


def _gradient(fun: Callable[[NDArray], complex], y: NDArray) -> NDArray:
    """Exact gradient of a real-analytic scalar function by complex steps."""
    return np.array([fun(y + 1j * _H * e).imag / _H for e in np.eye(y.size)])


@dataclass
class VariationalFlow:
    """The flow over ``T`` from ``y`` at load ``P`` and its derivatives."""

    y_T: NDArray  # phi_T(y; P)
    Phi: NDArray  # d phi_T / d y (the monodromy matrix on a cycle)
    S: NDArray  # d phi_T / d P
    f_T: NDArray  # f(phi_T(y)) = d phi_T / d T
    orbit: Callable | None = None  # t -> state on [0, T] (dense output), when asked for


def radau_iia(stages: int) -> tuple[NDArray, NDArray]:
    """Nodes ``c`` and matrix ``A`` of the ``stages``-stage Radau IIA collocation method
    (order ``2 stages - 1``, L-stable, stiffly accurate: the last stage is the step's end).
    Nodes: the roots of ``P_s(2x - 1) - P_{s-1}(2x - 1)``; ``A[i, j] = int_0^{c_i} l_j``."""
    coef = np.zeros(stages + 1)
    coef[stages], coef[stages - 1] = 1.0, -1.0
    c = (np.sort(np.polynomial.legendre.legroots(coef).real) + 1) / 2
    c[-1] = 1.0
    A = np.zeros((stages, stages))
    for j in range(stages):
        others = np.delete(c, j)
        primitive = np.polyint(np.poly(others) / np.prod(c[j] - others))
        A[:, j] = np.polyval(primitive, c) - np.polyval(primitive, 0.0)
    return c, A


_STAGES = 5  # Radau IIA order 9 on the orbit's own steps: measured below
_RADAU = radau_iia(_STAGES)


def jacobians_along(model: NonlinearRod, Y: NDArray, P: float) -> tuple[NDArray, NDArray]:
    """``J`` (m, N, N) and ``f_P`` (m, N) at the ``m`` states ``Y`` (N, m): the compiled
    hand-differentiated Jacobian (:meth:`NonlinearRod.jacobians`; equal to the complex steps of
    :func:`rhs_derivatives` to rounding, tested)."""
    return model.jacobians(Y, P)


def variational_flow(model: NonlinearRod, y: NDArray, T: float, P: float,
                     rtol: float = 1e-10, dense_output: bool = False) -> VariationalFlow:
    """The orbit over ``T`` (DOP853 compiled, :func:`~flutterfriction.analysis.rod_orbit.
    integrate_orbit`, ``atol = 1e-3 rtol``, dense output) with the solutions of
    its variational equations ``Phi' = J Phi``, ``Phi(0) = I`` and ``S' = J S + f_P``,
    ``S(0) = 0``.

    The variational equations are linear along the known orbit, so they are solved after it,
    by 5-stage Radau IIA collocation on the orbit's own steps: ``J`` and ``f_P`` at every stage
    point at once (the compiled Jacobian on the dense output), each step's transfer matrix
    from one small linear solve (all steps batched), then their product. Radau IIA is
    L-stable, so the Kelvin–Voigt modes, which limit an explicit integrator's step, cost
    nothing here. Measured at 4 elements, P = 5.5 N, against DOP853 on the coupled system at
    rtol 1e-12: relative error of ``Phi`` 8e-11 (rtol 1e-9 orbit), 1e-8 (rtol 1e-7); 3 stages
    5e-6, 4 stages 9e-9; CPU 1.5 s against 2.9 s for DOP853 on the coupled 16 + 16^2 + 16
    equations at rtol 1e-9 (whose every stage needed a Jacobian)."""
    N = y.size
    sol = integrate_orbit(model, y, T, P, rtol, rtol * 1e-3, dense_output=True)
    if not sol.success:
        raise ConvergenceError(f"orbit integration failed at P = {P:g} N: {sol.message}")
    c, A = _RADAU
    s = c.size
    # The orbit's steps follow the orbit; Phi also carries the modes the orbit does not excite
    # (at the straight rod DOP853 crosses the period in one step). Each step is therefore cut
    # to at most 1 / |lambda| for every eigenvalue of J (at both ends) whose mode survives the
    # interval (|Re lambda| T < 30, i.e. decays by less than e^-30 ~ 1e-13): Radau IIA's
    # local error there is ~1e-8 |hλ|^10. On a cycle the orbit's steps are already finer.
    rates = np.concatenate([np.linalg.eigvals(rhs_derivatives(model, z, P)[1])
                            for z in (y, sol.y[:, -1])])
    surviving = np.abs(rates[np.abs(rates.real) * T < 30.0])
    h_max = 1.0 / surviving.max() if surviving.size and surviving.max() > 0 else T
    cuts = np.maximum(1, np.ceil(np.diff(sol.t) / h_max).astype(int))
    pieces = zip(sol.t[:-1], sol.t[1:], cuts, strict=True)
    t = np.concatenate([np.linspace(a, b, k, endpoint=False) for a, b, k in pieces]
                       + [sol.t[-1:]])
    h = np.diff(t)
    n = h.size
    J, f_P = jacobians_along(model, sol.sol((t[:-1, None] + c * h[:, None]).ravel()), P)
    J, f_P = J.reshape(n, s, N, N), f_P.reshape(n, s, N)
    # Stage values Y_i = X_k + h sum_j A_ij (J_j Y_j + F_j); stiffly accurate: X_k+1 = Y_s.
    M = -(h[:, None, None, None, None] * A[None, :, :, None, None] * J[:, None])
    M = M.transpose(0, 1, 3, 2, 4).reshape(n, s * N, s * N) + np.eye(s * N)
    rhs = np.zeros((n, s, N, N + 1))
    rhs[..., :N] = np.eye(N)
    rhs[..., N] = h[:, None, None] * np.einsum("ij,kjm->kim", A, f_P)
    X = np.linalg.solve(M, rhs.reshape(n, s * N, N + 1))[:, (s - 1) * N:]
    Phi, S = np.eye(N), np.zeros(N)
    for k in range(n):
        S = X[k, :, :N] @ S + X[k, :, N]
        Phi = X[k, :, :N] @ Phi
    y_T = sol.y[:, -1]
    orbit = (lambda tt: sol.sol(tt)) if dense_output else None
    return VariationalFlow(y_T=y_T, Phi=Phi, S=S, f_T=model.rhs(0.0, y_T, P), orbit=orbit)


#: Samples a period for :func:`tip_rotation_amplitude`.
AMPLITUDE_SAMPLES = 256


def tip_rotation_amplitude(model: NonlinearRod, orbit: Callable, T: float,
                           samples: int = AMPLITUDE_SAMPLES) -> float:
    """``max |theta(l, t)|`` over one period [rad], from the orbit's interpolant ``orbit(t)``
    (an array of times in, states (N, times) out): sampled, then refined by the parabola
    through the largest sample and its neighbours (relative error ~1e-7 at 256 samples
    instead of ~1e-4 for the sample alone)."""
    t = np.linspace(0.0, T, samples, endpoint=False)
    return sampled_peak(np.abs(orbit(t)[model.n_dof - 1]))  # (N, samples): one call


def sampled_peak(theta: NDArray) -> float:
    """The maximum of a smooth periodic signal from equally spaced samples over one period
    (the end point excluded): the largest sample refined by the parabola through it and its
    neighbours."""
    samples = len(theta)
    k = int(np.argmax(theta))
    a, b, c = theta[k - 1], theta[k], theta[(k + 1) % samples]
    curv = a - 2 * b + c
    return float(b - 0.125 * (c - a) ** 2 / curv) if curv < 0 else float(b)


@dataclass
class Floquet:
    """Floquet multipliers of a cycle from its monodromy ``Phi``."""

    nontrivial: NDArray  # the multipliers of the return map (all but the trivial 1)
    slow_decay: float  # 1 - mu of the multiplier closest to 1 (the amplitude mode near onset)
    trivial_defect: float  # |Phi f - f| / |f|: how well Phi maps the flow direction to itself

    @property
    def max_modulus(self) -> float:
        return float(np.abs(self.nontrivial).max())


def floquet(model: NonlinearRod, y: NDArray, P: float, Phi: NDArray) -> Floquet:
    """Non-trivial Floquet multipliers from the linearised return map on the section (see the
    module docstring: the slow one as ``mu - 1`` directly, well conditioned)."""
    N = y.size
    f = model.rhs(0.0, y, P)
    c = _gradient(lambda z: section_value(model, z), y)
    D = Phi - np.eye(N)
    Pi_minus_I = D - np.outer(f, c @ Phi) / (c @ f)  # (I - f c^T / c.f) Phi - I
    Q = np.linalg.svd(c[None, :])[2][1:].T  # orthonormal basis of {c . dy = 0}
    lam = np.linalg.eigvals(Q.T @ Pi_minus_I @ Q)  # mu - 1
    k = int(np.argmin(np.abs(lam)))
    return Floquet(nontrivial=1.0 + lam, slow_decay=float(-lam[k].real),
                   trivial_defect=float(np.linalg.norm(D @ f) / np.linalg.norm(f)))


@dataclass
class CyclePoint:
    """A converged cycle: section state, period, load, its monodromy's Floquet data."""

    y: NDArray
    T: float
    P: float
    A: float
    floquet: Floquet
    newton_iterations: int
    first_correction: float = float("nan")  # scaled size of Newton's first correction
    tip_rotation_amplitude: float = float("nan")  # [rad], when measured (dense orbit or samples)
    flow_jacobian: NDArray | None = field(default=None, repr=False)  # [Phi - I, f_T, S]


class PeriodicOrbitNewton:
    """Newton's method for ``(y, T, P)``: ``phi_T(y; P) - y = 0``, ``section(y) = 0`` and one
    parametrising condition ``a . (A(y), P) = b`` (``a`` in the scaled ``(A / A_ref,
    P / P_ref)`` plane: fixed amplitude with ``a = (1, 0)``, pseudo-arclength with ``a`` the
    branch's tangent). Converged when the Newton correction is below ``tol`` relative to the
    scale of each unknown (state, period, load), or below ``30 rtol``, the integrator's noise
    floor (at 4 elements and rtol 1e-9 the correction stalls near 2e-8 relative); at most
    ``max_iterations``. Measured (2 and 4 elements, A = 1 cm): the slow multiplier's ``1 - mu``
    moves by 0.5% per 1e-6 of periodicity residual, so at the accepted residual (~1e-9) its
    error is ~1e-5 relative.

    ``max_contraction`` (off by default): give up as soon as a correction is not at most this
    fraction of the previous one (Newton is not converging from this guess; the continuation
    then shortens its step instead of spending all ``max_iterations`` integrations).
    ``dense``: keep the accepted cycle's orbit to measure its tip rotation amplitude."""

    def __init__(self, model: NonlinearRod, A_ref: float, P_ref: float, rtol: float = 1e-10,
                 tol: float = 1e-8, max_iterations: int = 8,
                 max_contraction: float | None = None, dense: bool = False) -> None:
        self.model, self.A_ref, self.P_ref = model, A_ref, P_ref
        self.rtol, self.max_iterations = rtol, max_iterations
        self.tol = max(tol, 30 * rtol)
        self.max_contraction, self.dense = max_contraction, dense
        self.integrations = 0
        self.orbit_integrations = 0  # orbit alone (chord corrections), cheaper

    def _scaled(self, dz: NDArray, y: NDArray, T: float, P: float) -> float:
        """The largest component of a correction relative to its unknown's scale: the
        rotations' size, and for the velocities the same times 2 pi / T (on the section, at
        the tip's extreme, the velocities themselves are near zero)."""
        n, N = self.model.n_dof, y.size
        q_scale = max(np.abs(y[:n]).max(), 1e-12)
        v_scale = max(np.abs(y[n:]).max(), 2 * np.pi / T * q_scale)
        return float(max(np.abs(dz[:n]).max() / q_scale, np.abs(dz[n:N]).max() / v_scale,
                         abs(dz[N]) / T, abs(dz[N + 1]) / P))

    def chord(self, y: NDArray, T: float, P: float, direction: tuple[float, float],
              target: float, flow_jacobian: NDArray, until: float, max_steps: int = 4
              ) -> tuple[NDArray, float, float, float]:
        """Cheap corrections before the exact Newton: the orbit alone is integrated (no
        variational equations: ~4x cheaper at 4 elements) and the flow's derivatives are those
        of a nearby converged cycle (``flow_jacobian = [Phi - I, f_T, S]``), improved by
        Broyden's rank-one updates; stops when the correction falls below ``until``, stops
        contracting, or after ``max_steps``. Returns ``(y, T, P, size of the first
        correction)``; :meth:`solve` then finishes with the exact Jacobian (which alone
        decides acceptance and gives the Floquet multipliers)."""
        model, N = self.model, y.size
        y = np.asarray(y, dtype=float).copy()
        a_A, a_P = direction[0] / self.A_ref, direction[1] / self.P_ref
        B = flow_jacobian.copy()
        first, previous, R_prev, dz_prev = float("nan"), float("inf"), None, None
        for k in range(max_steps):
            sol = integrate_orbit(model, y, T, P, self.rtol, self.rtol * 1e-3)
            self.orbit_integrations += 1
            if not sol.success:
                break
            R_flow = sol.y[:, -1] - y
            if R_prev is not None:  # Broyden: the secant condition on the flow's block
                B += np.outer((R_flow - R_prev) - B @ dz_prev, dz_prev) / (dz_prev @ dz_prev)
            J = np.zeros((N + 2, N + 2))
            J[:N] = B
            J[N, :N] = _gradient(lambda z: section_value(model, z), y)
            J[N + 1, :N] = a_A * _gradient(lambda z: tip_lateral(model, z), y)
            J[N + 1, N + 1] = a_P
            R = np.concatenate([R_flow, [section_value(model, y),
                                         a_A * float(tip_lateral(model, y)) + a_P * P - target]])
            dz = np.linalg.solve(J, -R)
            size = self._scaled(dz, y, T, P) if np.all(np.isfinite(dz)) else float("inf")
            if k == 0:
                first = size
            if size > 0.5 * previous or size > 0.05:
                break  # not contracting, or too far for a linear model: leave it to Newton
            y, T, P = y + dz[:N], T + dz[N], P + dz[N + 1]
            R_prev, dz_prev, previous = R_flow, dz, size
            if size <= until:
                break
        return y, T, P, first

    def solve(self, y: NDArray, T: float, P: float, direction: tuple[float, float],
              target: float, flow_jacobian: NDArray | None = None) -> CyclePoint:
        model, N = self.model, y.size
        y = np.asarray(y, dtype=float).copy()
        a_A, a_P = direction[0] / self.A_ref, direction[1] / self.P_ref
        first, previous = float("nan"), float("inf")
        if flow_jacobian is not None:
            y, T, P, first = self.chord(y, T, P, direction, target, flow_jacobian,
                                        until=self.tol)
        for it in range(1, self.max_iterations + 1):
            flow = variational_flow(model, y, T, P, self.rtol, dense_output=self.dense)
            self.integrations += 1
            A = float(tip_lateral(model, y))
            R = np.concatenate([flow.y_T - y, [section_value(model, y),
                                               a_A * A + a_P * P - target]])
            J = np.zeros((N + 2, N + 2))
            J[:N, :N] = flow.Phi - np.eye(N)
            J[:N, N] = flow.f_T
            J[:N, N + 1] = flow.S
            J[N, :N] = _gradient(lambda z: section_value(model, z), y)
            J[N + 1, :N] = a_A * _gradient(lambda z: tip_lateral(model, z), y)
            J[N + 1, N + 1] = a_P
            dz = np.linalg.solve(J, -R)
            if not np.all(np.isfinite(dz)):
                raise ConvergenceError("periodic-orbit Newton: singular Jacobian")
            n = model.n_dof
            # Scales: the rotations' size, and for the velocities the same times 2 pi / T (on
            # the section, at the tip's extreme, the velocities themselves are near zero).
            q_scale = max(np.abs(y[:n]).max(), 1e-12)
            v_scale = max(np.abs(y[n:]).max(), 2 * np.pi / T * q_scale)
            size = max(np.abs(dz[:n]).max() / q_scale, np.abs(dz[n:N]).max() / v_scale,
                       abs(dz[N]) / T, abs(dz[N + 1]) / P)  # the correction, scaled
            small = size <= self.tol
            if it == 1 and flow_jacobian is None:
                first = float(size)
            if small:
                # Accept this iterate: the monodromy was computed exactly here, and its
                # residual is the (tiny) predicted correction.
                rot = (tip_rotation_amplitude(model, flow.orbit, T) if flow.orbit is not None
                       else float("nan"))
                return CyclePoint(y=y, T=float(T), P=float(P), A=A,
                                  floquet=floquet(model, y, P, flow.Phi),
                                  newton_iterations=it, first_correction=first,
                                  tip_rotation_amplitude=rot, flow_jacobian=J[:N].copy())
            if self.max_contraction is not None and size > self.max_contraction * previous:
                raise ConvergenceError(
                    f"Newton not contracting (correction {size:.1e} after {previous:.1e}, "
                    f"iteration {it})")
            previous = size
            # Damp wild first steps (far from the cycle): at most 5% in T and P.
            scale = min(1.0, 0.05 * T / max(abs(dz[N]), 1e-300),
                        0.05 * P / max(abs(dz[N + 1]), 1e-300))
            y, T, P = y + scale * dz[:N], T + scale * dz[N], P + scale * dz[N + 1]
            if not (T > 0 and P > 0):
                raise ConvergenceError("periodic-orbit Newton left the physical range "
                                       f"(T = {T:g} s, P = {P:g} N)")
        raise ConvergenceError(f"periodic-orbit Newton did not converge in "
                               f"{self.max_iterations} iterations (last correction "
                               f"{np.abs(dz).max():.2e})")


@dataclass
class CycleBranch:
    """Limit cycles of the rod continued from the Hopf point: tip amplitude ``A`` [m] (the
    lateral tip displacement at the section), load ``P`` [N], period ``T`` [s], and at every
    point the Floquet data of its monodromy (largest non-trivial modulus, ``1 - mu`` of the
    slow multiplier, the trivial multiplier's defect)."""

    P_flu: float
    omega_flu: float
    n_elements: int
    A: list
    P: list
    T: list
    max_floquet_modulus: list
    slow_decay: list
    trivial_defect: list
    newton_iterations: list
    integrations: int
    rejected_steps: int
    stopped_by: str  # "A_max" when the branch reached its end; else the budget that ran out
    log: list = field(default_factory=list)
    states: list = field(default_factory=list, repr=False)
    tip_rotation_amplitude: list = field(default_factory=list)  # [rad] (nan: not measured)
    first_correction: list = field(default_factory=list)  # Newton's first, scaled
    landed: list = field(default_factory=list)  # indices of the points landed on a load
    orbit_integrations: int = 0  # of the orbit alone (chord corrections)

    def as_dict(self) -> dict:
        return asdict(self)


def linearised_flutter_load(rod: Rod, n_elements: int) -> float:
    """The damped flutter load [N] of the rod linearised about the straight configuration on
    ``n_elements`` P2 elements (where a cycle can start); refused
    (:class:`ParameterError`) if the rod does not flutter below ``40 * 2^8`` load units."""
    M, C, K, K1 = NonlinearRod(rod, n_elements).linear_matrices()
    try:
        P = float(flutter_onset(M, C, K, K1, load_max=40 * rod.load_unit, max_doublings=8))
    except ConvergenceError:
        raise ParameterError(f"the linearised rod does not flutter below "
                             f"{40 * 2**8 * rod.load_unit:.4g} N, so no cycle is sought") from None
    # The scan's load carries the first-order spectrum's round-off, eps max|s| (the stiff
    # Kelvin-Voigt modes): on list 119's rod its error against eq. (118)'s exact load is 8e-10
    # at 32 elements, 1.1e-8 at 48, 3.6e-7 at 64 (finer is worse), while polished by Newton
    # on the quadratic eigenproblem (as the FE twin's boundaries, analysis.rod_scan._fe_boundary)
    # it converges at h^4: 3.1e-9, 5.8e-10, 1.8e-10. Accepted within 1e-3 of the scan's load
    # (the scan's error reached 3.9e-5 on rods with D ~ 1e-10 and a tip mass, a review; the
    # polished load was right there to ~1e-12), else the scan's load stands.
    try:
        return float(polish_flutter_crossing(M, C, K, K1, P, rtol=1e-3)[0])
    except ConvergenceError:
        return P


class CycleContinuation:
    """Pseudo-arclength continuation of the cycles in the scaled ``(A / A_max, P / P_flu)``
    plane, started from the linear flutter mode at the model's damped flutter load.

    Steps grow by 1.5 after a success up to ``ds_max`` and halve after a Newton failure (each
    rejection logged with its reason), down to ``ds_min``."""

    def __init__(self, rod: Rod, n_elements: int = 4, A_max: float = 0.26,
                 rtol: float = 1e-10, newton_tol: float = 1e-8, ds_first: float = 0.02,
                 ds_max: float = 0.08, ds_min: float = 1e-4,
                 max_contraction: float | None = None, dense: bool = False) -> None:
        from flutterfriction.analysis.stability import first_order_matrix

        if not A_max > 0:
            raise ParameterError(f"A_max must be > 0 m, got {A_max}")
        self.model = NonlinearRod(rod, n_elements)
        self.rod, self.A_max = rod, A_max
        self.ds, self.ds_max, self.ds_min = ds_first, ds_max, ds_min
        model = self.model
        M0, C, K, K1 = model.linear_matrices()
        self.P_flu = linearised_flutter_load(rod, n_elements)  # (polished; one definition)
        ev, V = np.linalg.eig(first_order_matrix(M0, K + self.P_flu * K1, C))
        k = int(np.argmax(ev.real))
        self.omega_flu = float(abs(ev[k].imag))
        self.mode = V[:, k]
        self.newton = PeriodicOrbitNewton(model, A_max, self.P_flu, rtol=rtol, tol=newton_tol,
                                          max_contraction=max_contraction, dense=dense)
        self.points: list[CyclePoint] = []
        self.landed: list[int] = []  # indices of the points landed exactly on a requested load
        self.rejected = 0
        self.log: list[str] = []

    def _say(self, message: str, log: Callable[[str], None] | None) -> None:
        self.log.append(message)
        if log:
            log(message)

    def _reject(self, message: str, log: Callable[[str], None] | None) -> None:
        """A rejected step: counted, its reason logged, the step halved (no cycle added)."""
        self.rejected += 1
        self._say(message, log)
        self.ds /= 2

    def first(self, A_first: float) -> CyclePoint:
        """The cycle of amplitude ``A_first`` from the linear mode at the flutter load (on the
        section: the mode's phase with zero lateral tip velocity and positive displacement)."""
        model = self.model
        # Rotate the complex mode so that the lateral tip velocity vanishes (linear in y).
        c_v = _gradient(lambda z: section_value(model, z), np.zeros(self.mode.size))
        c_u = _gradient(lambda z: tip_lateral(model, z), np.zeros(self.mode.size))
        phase = np.angle(c_v @ self.mode)
        w = self.mode * np.exp(1j * (np.pi / 2 - phase))  # c_v . w is now imaginary
        y0 = w.real * A_first / (c_u @ w.real)
        point = self.newton.solve(y0, 2 * np.pi / self.omega_flu, self.P_flu, (1.0, 0.0),
                                  A_first / self.A_max)
        self.points.append(point)
        return point

    def step(self, log: Callable[[str], None] | None = None,
             chord: bool = False) -> CyclePoint | None:
        """One pseudo-arclength step of length ``ds``; ``None`` (and ``ds`` halved) on failure.
        ``chord``: Newton starts with chord corrections on the previous cycle's flow
        derivatives (:meth:`PeriodicOrbitNewton.chord`)."""
        pts = self.points
        a, b = pts[-1], pts[-2] if len(pts) > 1 else None
        if b is None:  # second point: step in amplitude at the first one's load
            tangent = (1.0, 0.0)
            y_guess = a.y * (a.A + self.ds * self.A_max) / a.A
            T_guess, P_guess = a.T, a.P
        else:
            dA, dP = (a.A - b.A) / self.A_max, (a.P - b.P) / self.P_flu
            norm = float(np.hypot(dA, dP))
            tangent = (dA / norm, dP / norm)
            r = self.ds / norm
            y_guess = a.y + r * (a.y - b.y)
            T_guess, P_guess = a.T + r * (a.T - b.T), a.P + r * (a.P - b.P)
        target = tangent[0] * a.A / self.A_max + tangent[1] * a.P / self.P_flu + self.ds
        try:
            point = self.newton.solve(y_guess, T_guess, P_guess, tangent, target,
                                      flow_jacobian=a.flow_jacobian if chord else None)
        except ConvergenceError as exc:
            return self._reject(f"step ds = {self.ds:.3g} from A = {a.A:.5f} m rejected "
                                f"({exc}): halved", log)
        pts.append(point)
        self._say(f"cycle {len(pts) - 1}: A = {point.A:.5f} m, P = {point.P:.5f} N, "
                  f"T = {point.T:.6f} s, max |mu| = {point.floquet.max_modulus:.6f}, "
                  f"Newton iterations {point.newton_iterations}, ds = {self.ds:.3g}", log)
        self.ds = min(1.5 * self.ds, self.ds_max)
        return point

    # ------------------------------------------------------------------ adaptive stepping
    def _X(self, p: CyclePoint) -> NDArray:
        """A point in the scaled plane ``(A / A_max, P / P_flu)``."""
        return np.array([p.A / self.A_max, p.P / self.P_flu])

    def _interpolant(self):
        """The branch through its last (up to) three points as polynomials in the chord length
        ``s`` of the scaled plane (``s = 0`` at the last point): ``z(s)`` for ``(y, T, P)``,
        ``X(s)`` and ``X'(0)``."""
        pts = self.points[-3:]
        X = np.array([self._X(p) for p in pts])
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(X, axis=0), axis=1))])
        s = s - s[-1]
        Z = np.array([[*p.y, p.T, p.P] for p in pts])

        def lagrange(x: float, derivative: bool = False) -> NDArray:
            w = np.zeros(len(s))
            for i in range(len(s)):
                others = [j for j in range(len(s)) if j != i]
                den = np.prod([s[i] - s[j] for j in others])
                if derivative:
                    w[i] = sum(np.prod([x - s[j] for j in others if j != k])
                               for k in others) / den
                else:
                    w[i] = np.prod([x - s[j] for j in others]) / den
            return w

        def z(x: float) -> NDArray:
            return lagrange(x) @ Z

        def Xs(x: float) -> NDArray:
            return lagrange(x) @ X

        tangent = lagrange(0.0, derivative=True) @ X
        return z, Xs, tangent / np.linalg.norm(tangent)

    def advance(self, parametrisation: str = "local", land_at: tuple[float, ...] = (),
                error_target: float = 1e-3, log: Callable[[str], None] | None = None,
                chord: bool = False) -> CyclePoint | None:
        """One adaptive step (``None``, ``ds`` halved and the reason logged, on failure).

        Predictor: the polynomial through the last three points (two: the secant; one: a step
        in amplitude) extrapolated by ``ds`` in chord length of the scaled plane. Corrector:
        Newton with the condition ``parametrisation`` picks: ``"arclength"`` (the plane through
        the predicted point normal to the branch's tangent) or ``"local"`` (the scaled
        coordinate, A or P, that changes most along the tangent held at its predicted value:
        natural continuation in P wherever the branch is steeper in P than in A, in A near the
        Hopf point; never singular at a turning point of the other coordinate). A load in
        ``land_at`` that the step would pass is landed on exactly (the condition P = load).
        After a success the step changes by ``(error_target / e)^(1/order)`` (``e`` the
        scaled size of Newton's first correction, i.e. the predictor's error; ``order`` 3 for
        the quadratic predictor, 2 for the secant), between halving and doubling, up to
        ``ds_max``. With ``chord``, Newton starts with cheap chord corrections (the orbit
        alone, the previous cycle's flow derivatives: :meth:`PeriodicOrbitNewton.chord`)."""
        if parametrisation not in ("local", "arclength"):
            raise ParameterError(f"parametrisation must be 'local' or 'arclength', got "
                                 f"{parametrisation!r}")
        a = self.points[-1]
        ds, landing = self.ds, None
        if len(self.points) == 1:  # second point: step in amplitude at the first one's load
            y_g, T_g, P_g = a.y * (a.A + ds * self.A_max) / a.A, a.T, a.P
            direction, target, order = (1.0, 0.0), a.A / self.A_max + ds, 2
        else:
            z, Xs, tangent = self._interpolant()
            order = 3 if len(self.points) >= 3 else 2
            X_pred = Xs(ds)
            P_pred = X_pred[1] * self.P_flu
            ahead = sorted(L for L in land_at
                           if a.P < L * (1 - 1e-9) and L <= P_pred and tangent[1] > 0)
            if ahead:  # land exactly: the chord length where the interpolant reaches the load
                landing = ahead[0]
                x = ds * (landing - a.P) / (P_pred - a.P)
                for _ in range(20):
                    dPx = (Xs(x + 1e-7)[1] - Xs(x - 1e-7)[1]) / 2e-7 * self.P_flu
                    step = (Xs(x)[1] * self.P_flu - landing) / dPx
                    x -= step
                    if abs(step) < 1e-14:
                        break
                ds, X_pred = x, Xs(x)
                direction, target = (0.0, 1.0), landing / self.P_flu
            elif parametrisation == "arclength":
                direction, target = tuple(tangent), float(tangent @ X_pred)
            else:
                k = int(np.argmax(np.abs(tangent)))
                direction = (1.0, 0.0) if k == 0 else (0.0, 1.0)
                target = float(X_pred[k])
            zg = z(ds)
            y_g, T_g, P_g = zg[:-2], zg[-2], zg[-1]
        try:
            point = self.newton.solve(y_g, T_g, P_g, direction, target,
                                      flow_jacobian=a.flow_jacobian if chord else None)
        except ConvergenceError as exc:
            return self._reject(f"step ds = {ds:.3g} from A = {a.A:.5f} m, P = {a.P:.5f} N "
                                f"rejected ({exc}): halved", log)
        passed = sorted(L for L in land_at if a.P < L * (1 - 1e-9) and point.P > L * (1 + 1e-9))
        if landing is None and passed:
            # The corrector held the amplitude and the cycle overshot a requested load: land on
            # it from the two converged cycles around it (interpolated in P: a close guess).
            landing = passed[0]
            r = (landing - a.P) / (point.P - a.P)
            y_g, T_g = a.y + r * (point.y - a.y), a.T + r * (point.T - a.T)
            try:
                point = self.newton.solve(y_g, T_g, landing, (0.0, 1.0), landing / self.P_flu,
                                          flow_jacobian=a.flow_jacobian if chord else None)
            except ConvergenceError as exc:
                return self._reject(f"landing on {landing:g} N between P = {a.P:.5f} N and the "
                                    f"step's cycle rejected ({exc}): step halved", log)
        self.points.append(point)
        if landing is not None:
            self.landed.append(len(self.points) - 1)
        self._say(f"cycle {len(self.points) - 1}: A = {point.A:.5f} m, P = {point.P:.5f} N, "
                  f"T = {point.T:.6f} s, max |mu| = {point.floquet.max_modulus:.6f}, Newton "
                  f"iterations {point.newton_iterations} (first correction "
                  f"{point.first_correction:.1e}), ds = {ds:.3g}"
                  + (f", landed on {landing:g} N" if landing is not None else ""), log)
        if landing is None:  # a landing step is shortened on purpose: it says nothing of ds
            e = point.first_correction
            e = max(e, 1e-12) if np.isfinite(e) else error_target
            factor = min(2.0, max(0.5, (error_target / e) ** (1.0 / order)))
            self.ds = min(factor * self.ds, self.ds_max)
        return point

    def branch(self, stopped_by: str) -> CycleBranch:
        pts = self.points
        return CycleBranch(
            P_flu=self.P_flu, omega_flu=self.omega_flu, n_elements=int(self.model.n_elements),
            A=[p.A for p in pts], P=[p.P for p in pts], T=[p.T for p in pts],
            max_floquet_modulus=[p.floquet.max_modulus for p in pts],
            slow_decay=[p.floquet.slow_decay for p in pts],
            trivial_defect=[p.floquet.trivial_defect for p in pts],
            newton_iterations=[p.newton_iterations for p in pts],
            integrations=self.newton.integrations, rejected_steps=self.rejected,
            stopped_by=stopped_by, log=list(self.log),
            states=[[*p.y.tolist(), p.T, p.P] for p in pts],
            tip_rotation_amplitude=[p.tip_rotation_amplitude for p in pts],
            first_correction=[p.first_correction for p in pts], landed=list(self.landed),
            orbit_integrations=self.newton.orbit_integrations)


def cycle_branch(rod: Rod, n_elements: int = 4, A_first: float = 0.01, A_max: float = 0.26,
                 ds_max: float = 0.08, rtol: float = 1e-10, max_points: int = 60,
                 log: Callable[[str], None] | None = None, *, P_max: float | None = None,
                 land_at: tuple[float, ...] = (), parametrisation: str = "arclength",
                 newton_tol: float = 1e-8, ds_first: float = 0.02,
                 error_target: float = 1e-3, max_contraction: float = 0.5,
                 chord: bool = False) -> CycleBranch:
    """The branch of limit cycles born at the (damped) flutter load, from amplitude
    ``A_first`` until the amplitude passes ``A_max`` (``stopped_by = "A_max"``), or until
    ``max_points`` cycles (``"max_points"``) or a step below ``ds_min`` (``"min_step"``): the
    caller decides whether a shorter branch is acceptable. Deterministic: no clock.

    Without ``P_max`` this is the original pseudo-arclength stepping (secant predictor, steps
    growing by 1.5 and halved on failure; ``beck_hopf``'s settings and results). With
    ``P_max`` [N] the branch is followed by :meth:`CycleContinuation.advance` (quadratic
    predictor, step from the predictor's measured error, Newton abandoned when it stops
    contracting by ``max_contraction``, every cycle's tip rotation amplitude) until it lands
    exactly on ``P_max`` (``stopped_by = "P_max"``), landing on every load of ``land_at`` on
    the way; ``A_max`` is then only the amplitude scale of the step norm.

    Choices, measured (list 119; CPU seconds on a shared, loaded 2-core machine):

    - parametrisation: along the whole branch to 7 N the load increases at every step
      (smallest step 0.004 N, 4 elements) while the amplitude turns twice (3.2 N, 3.43 N), so
      both ``"local"`` (natural continuation in P there, in A at the onset) and
      ``"arclength"`` (the default) pass the turns. Measured with chord corrections, Newton tol
      1e-5, error target 5e-3: 4 elements to 7 N, arclength 82 variational + 151 orbit
      integrations, 7 rejected steps, 240 CPU-s; local 86 + 149, 7 rejected, 297 CPU-s
      (load-dependent timing; the counts are deterministic); 2 elements to 3.6 N: arclength
      51 + 106, 6 rejected; local 58 + 113, 7 rejected. Arclength is the slightly cheaper.
    - ``newton_tol`` 1e-5 on the scaled correction (``beck_hopf``: 1e-8): the cycle at 5.5 N
      moves by 2e-7 (amplitude) and 1e-7 (period) when re-solved at rtol 1e-10, tol 1e-9; the
      first cycle's load by 2.6e-6. rtol stays 1e-9: one variational period at 4 elements
      costs 1.4 CPU-s at rtol 1e-9 and 0.8 at 1e-7 (orbit by DOP853, variational equations
      by Radau IIA on its steps; DOP853 on the coupled system took 2.9 s), and the whole
      branch (same 82 + 151 integrations, cycles equal to 1e-9) 133 CPU-s against 273.
    - ``chord``: at 4 elements to 7 N, 42 cycles, 82-86 variational and ~150 orbit-only
      integrations, 7 rejected steps, 240-300 CPU-s (without chord corrections: ~3 variational
      integrations per cycle, then 1.7 s each; on 2 elements to 4 N without them: 135 variational
      integrations for 49 cycles, 164 CPU-s). With the Radau-collocated variational
      equations (a variational period ~2x an orbit-only one, not ~6x) chord still pays: 79 CPU-s
      against 96 without; ``beck_hopf`` (secant stepping) 45 -> 21 variational integrations,
      25 -> 18 CPU-s, the same cycles to 1e-7.
    - ``error_target`` 5e-3: larger first corrections leave Newton's basin in the amplitude's
      dip (rejections there: "Newton not contracting" at first corrections of 1-7e-2)."""
    # (an outside audit: A_max = inf ended in a bare LinAlgError, max_points = 2.5 passed)
    A_max = check_positive("A_max", A_max, "m")
    if not 0 < check_real("A_first", A_first) < A_max:
        raise ParameterError(f"A_first must be in (0, A_max = {A_max}) m, got {A_first}")
    check_integer("max_points", max_points, 2)
    if P_max is not None:
        check_positive("P_max", P_max, "N")
    adaptive = P_max is not None
    cont = CycleContinuation(rod, n_elements=n_elements, A_max=A_max, rtol=rtol, ds_max=ds_max,
                             newton_tol=newton_tol, ds_first=ds_first,
                             max_contraction=max_contraction if adaptive else None,
                             dense=adaptive)
    if adaptive and not P_max > cont.P_flu:
        raise ParameterError(f"P_max must exceed the flutter load {cont.P_flu:.5f} N, got "
                             f"{P_max}")
    cont.newton.max_contraction = None  # the first cycle's Newton starts far (damped steps)
    point = cont.first(A_first)
    cont.newton.max_contraction = max_contraction if adaptive else None
    cont._say(f"cycle 0: A = {point.A:.5f} m, P = {point.P:.5f} N, T = {point.T:.6f} s "
              f"(from the flutter mode at P_flu = {cont.P_flu:.5f} N)", log)
    if adaptive:
        loads = tuple(sorted({float(x) for x in land_at if x < P_max} | {float(P_max)}))
        while True:
            if cont.points[-1].P >= P_max * (1 - 1e-9):
                return cont.branch("P_max")
            if len(cont.points) >= max_points:
                return cont.branch("max_points")
            if cont.ds < cont.ds_min:
                return cont.branch("min_step")
            cont.advance(parametrisation, loads, error_target, log, chord=chord)
    while True:
        if cont.points[-1].A >= A_max:
            return cont.branch("A_max")
        if len(cont.points) >= max_points:
            return cont.branch("max_points")
        if cont.ds < cont.ds_min:
            return cont.branch("min_step")
        cont.step(log, chord=chord)


def cycle_on_finer_mesh(coarse: NonlinearRod, y: NDArray, T: float, P: float,
                        fine: NonlinearRod, rtol: float = 1e-10, tol: float = 1e-7,
                        max_iterations: int = 40) -> CyclePoint:
    """The cycle at the same load ``P`` on a finer mesh, from a converged coarse cycle
    ``(y, T)``: unknowns the fine section state and the period; residual from the fine orbit
    alone (LSODA, scipy's odeint: explicit methods pay for the finer mesh's stiffer
    Kelvin–Voigt modes, 43000 right-hand sides per period at 8 elements against 7500; the tip
    rotation's amplitude from its :data:`AMPLITUDE_SAMPLES` outputs); Jacobian the coarse cycle's
    exact monodromy carried over by interpolation (the modes the coarse mesh lacks are the
    strongly damped ones, whose multipliers are ~0), improved by Broyden's rank-one updates.
    Converged when the scaled correction is below ``tol``; the Floquet data are then those of
    the coarse monodromy (``floquet`` of the result: an estimate, not the fine mesh's).
    At most ``max_iterations`` (measured: the paper's 4 -> 8 elements 6-7; the quick preset's
    2 -> 3 elements 18, its periodicity defect wandering near 1 for ten iterations before
    Broyden's updates take hold, too near the former bound of 20 to hold on every CPU)."""
    rtol = check_orbit_rtol("rtol", rtol)  # (odeint's own refusal: "Illegal input")
    N, n = 2 * fine.n_dof, fine.n_dof
    Pr = prolongation(coarse, fine)
    R_s = np.linalg.pinv(Pr)
    coarse_flow = variational_flow(coarse, y, T, P, rtol=max(rtol, 1e-10))
    Phi = Pr @ coarse_flow.Phi @ R_s
    z = np.concatenate([Pr @ y, [T]])

    f = fine.rhs_at(P)

    def jac(t, x):
        return fine.jacobians(x[:, None], P)[0][0]

    def residual(z):
        # odeint: LSODA's own loop, outputs interpolated by it at the samples of the tip's
        # amplitude and at the end (solve_ivp's LSODA returned to Python at each of ~2300
        # steps a period and built a dense output at each: ~40% of this function's time)
        yy, TT = z[:N], z[N]
        # a Newton step may try any period: only (T/2, 2T) of the coarse cycle's is integrated
        # (as the pendulum's shooting does), never a runaway one
        if not (0.5 * T < TT < 2.0 * T and np.all(np.isfinite(yy))):
            raise ConvergenceError(f"fine-mesh cycle at P = {P:g} N: Newton left the coarse "
                                   f"cycle (period {TT:.4g} s against {T:.4g} s, or a "
                                   f"non-finite state)")
        t = np.append(np.linspace(0.0, TT, AMPLITUDE_SAMPLES, endpoint=False), TT)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ODEintWarning)  # reported below, as an error
            # (odeint's default bound, 500 steps between two outputs, is 30-40x the most the
            # meshes take, measured: 13 on 3 elements, 15 on 8; it ends a diverging orbit)
            Y, info = odeint(f, yy, t, Dfun=jac, tfirst=True, rtol=rtol, atol=rtol * 1e-3,
                             full_output=True)
        if info["message"] != "Integration successful." or not np.all(np.isfinite(Y)):
            # (odeint reports success for an orbit that turned NaN: checked here)
            raise ConvergenceError(f"fine-mesh orbit failed at P = {P:g} N: "
                                   + ("the state became non-finite" if info["message"] ==
                                      "Integration successful." else info["message"]))
        y_T = Y[-1]
        return np.concatenate([y_T - yy, [section_value(fine, yy)]]), y_T, Y[:-1]

    R, y_T, samples = residual(z)
    J = np.zeros((N + 1, N + 1))
    J[:N, :N] = Phi - np.eye(N)
    J[:N, N] = fine.rhs(0.0, y_T, P)
    J[N, :N] = _gradient(lambda w: section_value(fine, w), z[:N])
    first = float("nan")
    for it in range(1, max_iterations + 1):
        dz = np.linalg.solve(J, -R)
        q_scale = max(np.abs(z[:n]).max(), 1e-12)
        v_scale = max(np.abs(z[n:N]).max(), 2 * np.pi / z[N] * q_scale)
        size = max(np.abs(dz[:n]).max() / q_scale, np.abs(dz[n:N]).max() / v_scale,
                   abs(dz[N]) / z[N])
        if it == 1:
            first = float(size)
        if size <= tol:
            yy = z[:N]
            return CyclePoint(y=yy, T=float(z[N]), P=float(P),
                              A=float(tip_lateral(fine, yy)),
                              floquet=floquet(coarse, y, P, coarse_flow.Phi),
                              newton_iterations=it, first_correction=first,
                              tip_rotation_amplitude=sampled_peak(np.abs(samples[:, n - 1])))
        z = z + dz
        R_new, y_T, samples = residual(z)
        J += np.outer((R_new - R) - J @ dz, dz) / (dz @ dz)  # Broyden's good update
        R = R_new
    raise ConvergenceError(f"fine-mesh cycle at P = {P:g} N: no convergence in "
                           f"{max_iterations} iterations (last correction {size:.1e})")
