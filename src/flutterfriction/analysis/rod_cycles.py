"""Periodic orbits of the nonlinear Beck rod and their continuation from the Hopf point
(beyond the chapter's §2.9: the branch of limit cycles on which Figs. 15–17's cycle lies).

A cycle is a state ``y`` on the Poincaré section (lateral tip velocity 0, the tip at its
lateral maximum), a period ``T`` and a load ``P`` with ``phi_T(y; P) = y``. Newton's method on
these equations uses the *exact* Jacobian, from the variational equations integrated with the
orbit (the flow's derivatives ``Phi = d phi_T / d y`` and ``S = d phi_T / d P``; the right-hand
side's Jacobian by complex steps, exact to rounding), so it converges quadratically to the
integrator's accuracy instead of stalling at a finite-difference noise floor. The same ``Phi``
at the converged cycle gives the Floquet multipliers without another integration.

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

from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from flutterfriction.errors import ConvergenceError, ParameterError
from flutterfriction.models.rod import Rod
from flutterfriction.models.rod_nonlinear import NonlinearRod

_H = 1e-30  # complex step: h^2 is far below rounding, and no subtraction cancels


def rhs_derivatives(model: NonlinearRod, y: NDArray, P: float
                    ) -> tuple[NDArray, NDArray, NDArray]:
    """``(f, J, f_P)``: the first-order right-hand side at ``y``, its Jacobian ``df/dy`` and
    ``df/dP``, from ``N + 1`` complex steps evaluated as one batch (every operation of the
    equations of motion is analytic, so ``Im f(y + i h e) / h`` is exact to rounding)."""
    N = y.size
    Y = np.empty((N, N + 1), dtype=complex)
    Y[:] = y[:, None]
    Y[:, :N] += 1j * _H * np.eye(N)
    loads = np.full(N + 1, P, dtype=complex)
    loads[N] += 1j * _H
    F = model.rhs(0.0, Y, loads)
    return F[:, N].real, F[:, :N].imag / _H, F[:, N].imag / _H


def section_value(model: NonlinearRod, y: NDArray):
    """The section function: lateral tip velocity (zero at the lateral extremes of the tip)."""
    n = model.n_dof
    _, _, _, G_tip = model.kinematics(y[:n])
    return (G_tip @ y[n:])[1]


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


def variational_flow(model: NonlinearRod, y: NDArray, T: float, P: float,
                     rtol: float = 1e-10) -> VariationalFlow:
    """Integrate the orbit with its variational equations ``Phi' = J Phi``, ``Phi(0) = I`` and
    ``S' = J S + f_P``, ``S(0) = 0`` (DOP853; ``atol = 1e-3 rtol``)."""
    N = y.size

    def augmented(t, x):
        f, J, f_P = rhs_derivatives(model, x[:N], P)
        Phi = x[N:N + N * N].reshape(N, N)
        return np.concatenate([f, (J @ Phi).ravel(), J @ x[N + N * N:] + f_P])

    x0 = np.concatenate([y, np.eye(N).ravel(), np.zeros(N)])
    sol = solve_ivp(augmented, (0.0, T), x0, method="DOP853", rtol=rtol, atol=rtol * 1e-3)
    if not sol.success:
        raise ConvergenceError(f"variational integration failed at P = {P:g} N: {sol.message}")
    x = sol.y[:, -1]
    y_T = x[:N]
    return VariationalFlow(y_T=y_T, Phi=x[N:N + N * N].reshape(N, N), S=x[N + N * N:],
                           f_T=model.rhs(0.0, y_T, P))


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


class PeriodicOrbitNewton:
    """Newton's method for ``(y, T, P)``: ``phi_T(y; P) - y = 0``, ``section(y) = 0`` and one
    parametrising condition ``a . (A(y), P) = b`` (``a`` in the scaled ``(A / A_ref,
    P / P_ref)`` plane: fixed amplitude with ``a = (1, 0)``, pseudo-arclength with ``a`` the
    branch's tangent). Converged when the Newton correction is below ``tol`` relative to the
    scale of each unknown (state, period, load), or below ``30 rtol``, the integrator's noise
    floor (at 4 elements and rtol 1e-9 the correction stalls near 2e-8 relative); at most
    ``max_iterations``. Measured (2 and 4 elements, A = 1 cm): the slow multiplier's ``1 - mu``
    moves by 0.5% per 1e-6 of periodicity residual, so at the accepted residual (~1e-9) its
    error is ~1e-5 relative."""

    def __init__(self, model: NonlinearRod, A_ref: float, P_ref: float, rtol: float = 1e-10,
                 tol: float = 1e-8, max_iterations: int = 8) -> None:
        self.model, self.A_ref, self.P_ref = model, A_ref, P_ref
        self.rtol, self.max_iterations = rtol, max_iterations
        self.tol = max(tol, 30 * rtol)
        self.integrations = 0

    def solve(self, y: NDArray, T: float, P: float, direction: tuple[float, float],
              target: float) -> CyclePoint:
        model, N = self.model, y.size
        y = np.asarray(y, dtype=float).copy()
        a_A, a_P = direction[0] / self.A_ref, direction[1] / self.P_ref
        for it in range(1, self.max_iterations + 1):
            flow = variational_flow(model, y, T, P, self.rtol)
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
            small = (np.abs(dz[:n]).max() <= self.tol * q_scale
                     and np.abs(dz[n:N]).max() <= self.tol * v_scale
                     and abs(dz[N]) <= self.tol * T and abs(dz[N + 1]) <= self.tol * P)
            if small:
                # Accept this iterate: the monodromy was computed exactly here, and its
                # residual is the (tiny) predicted correction.
                return CyclePoint(y=y, T=float(T), P=float(P), A=A,
                                  floquet=floquet(model, y, P, flow.Phi),
                                  newton_iterations=it)
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

    def as_dict(self) -> dict:
        return asdict(self)


class CycleContinuation:
    """Pseudo-arclength continuation of the cycles in the scaled ``(A / A_max, P / P_flu)``
    plane, started from the linear flutter mode at the model's damped flutter load.

    Steps grow by 1.5 after a success up to ``ds_max`` and halve after a Newton failure (each
    rejection logged with its reason), down to ``ds_min``."""

    def __init__(self, rod: Rod, n_elements: int = 4, A_max: float = 0.26,
                 rtol: float = 1e-10, newton_tol: float = 1e-8, ds_first: float = 0.02,
                 ds_max: float = 0.08, ds_min: float = 1e-4) -> None:
        from flutterfriction.analysis.damped import flutter_onset
        from flutterfriction.analysis.stability import first_order_matrix

        if not A_max > 0:
            raise ParameterError(f"A_max must be > 0 m, got {A_max}")
        self.model = NonlinearRod(rod, n_elements)
        self.rod, self.A_max = rod, A_max
        self.ds, self.ds_max, self.ds_min = ds_first, ds_max, ds_min
        model = self.model
        M0, C, K, K1 = model.linear_matrices()
        self.P_flu = float(flutter_onset(M0, C, K, K1, load_max=40 * rod.load_unit,
                                         n_scan=64))
        ev, V = np.linalg.eig(first_order_matrix(M0, K + self.P_flu * K1, C))
        k = int(np.argmax(ev.real))
        self.omega_flu = float(abs(ev[k].imag))
        self.mode = V[:, k]
        self.newton = PeriodicOrbitNewton(model, A_max, self.P_flu, rtol=rtol, tol=newton_tol)
        self.points: list[CyclePoint] = []
        self.rejected = 0
        self.log: list[str] = []

    def _say(self, message: str, log: Callable[[str], None] | None) -> None:
        self.log.append(message)
        if log:
            log(message)

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

    def step(self, log: Callable[[str], None] | None = None) -> CyclePoint | None:
        """One pseudo-arclength step of length ``ds``; ``None`` (and ``ds`` halved) on failure."""
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
            point = self.newton.solve(y_guess, T_guess, P_guess, tangent, target)
        except ConvergenceError as exc:
            self.rejected += 1
            self._say(f"step ds = {self.ds:.3g} from A = {a.A:.5f} m rejected ({exc}): "
                      "halved", log)
            self.ds /= 2
            return None
        pts.append(point)
        self._say(f"cycle {len(pts) - 1}: A = {point.A:.5f} m, P = {point.P:.5f} N, "
                  f"T = {point.T:.6f} s, max |mu| = {point.floquet.max_modulus:.6f}, "
                  f"Newton iterations {point.newton_iterations}, ds = {self.ds:.3g}", log)
        self.ds = min(1.5 * self.ds, self.ds_max)
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
            states=[[*p.y.tolist(), p.T, p.P] for p in pts])


def cycle_branch(rod: Rod, n_elements: int = 4, A_first: float = 0.01, A_max: float = 0.26,
                 ds_max: float = 0.08, rtol: float = 1e-10, max_points: int = 60,
                 log: Callable[[str], None] | None = None) -> CycleBranch:
    """The branch of limit cycles born at the (damped) flutter load, from amplitude
    ``A_first`` until the amplitude passes ``A_max`` (``stopped_by = "A_max"``), or until
    ``max_points`` cycles (``"max_points"``) or a step below ``ds_min`` (``"min_step"``): the
    caller decides whether a shorter branch is acceptable. Deterministic: no clock."""
    if not 0 < A_first < A_max:
        raise ParameterError(f"A_first must be in (0, A_max = {A_max}) m, got {A_first}")
    if int(max_points) < 2:
        raise ParameterError(f"max_points must be >= 2, got {max_points}")
    cont = CycleContinuation(rod, n_elements=n_elements, A_max=A_max, rtol=rtol, ds_max=ds_max)
    point = cont.first(A_first)
    cont._say(f"cycle 0: A = {point.A:.5f} m, P = {point.P:.5f} N, T = {point.T:.6f} s "
              f"(from the flutter mode at P_flu = {cont.P_flu:.5f} N)", log)
    while True:
        if cont.points[-1].A >= A_max:
            return cont.branch("A_max")
        if len(cont.points) >= max_points:
            return cont.branch("max_points")
        if cont.ds < cont.ds_min:
            return cont.branch("min_step")
        cont.step(log)
