"""A geometrically exact, inextensible planar rod with a tangential follower force at the tip
(chapter §2.5–2.6, §2.9): the nonlinear Beck/Pflüger rod.

The unknown is the rotation field ``theta(s, t)`` (``theta(0) = 0`` at the clamp), discretised
with continuous P2 (quadratic Lagrange) elements; the position follows from inextensibility,
``x(s) = int_0^s (cos theta, sin theta) ds'`` (eq. 64), so no axial stiffness makes the problem
stiff and no membrane locking can occur. With ``t = (cos theta, sin theta)`` and
``t_perp = (-sin theta, cos theta)``, ``x_dot(s) = sum_j G_j(s) q_dot_j`` with
``G_j(s) = int_0^s t_perp phi_j``, and ``x_ddot = sum_j G_j q_ddot_j - int_0^s t theta_dot^2``.
Virtual work then gives

    M(q) q_ddot + h(q, q_dot) + K q + C q_dot = F(q)

with ``M = rho int G^T G + M_tip G(l)^T G(l)``, the bending stiffness ``K = B int phi' phi'``,
the Kelvin–Voigt viscosity ``C = D int phi' phi'`` (eq. 83: moment ``B theta' + D theta_dot'``),
the follower force ``F_i = -P int sin(theta(l) - theta) phi_i`` (the load ``-P t(l)`` at the tip)
and external damping ``-kappa x_dot`` per length. Linearised about the straight rod this is the
Euler–Bernoulli beam of eq. (105) in the variable ``theta = v'``, so it converges to the exact
theory of :mod:`flutterfriction.analysis.rod`.

Cumulative integrals along ``s`` use, in each element, Gauss–Legendre points and a spectral
integration matrix (exact for polynomials of the rule's degree).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre
from numpy.typing import NDArray

from flutterfriction.errors import (
    ConvergenceError,
    ParameterError,
    check_integer,
    check_real,
    named_parameters,
)
from flutterfriction.models.rod import Rod


def _integration_matrix(x: NDArray) -> NDArray:
    """``S[q, r]``: ``int_{-1}^{x_q} f = sum_r S[q, r] f(x_r)`` for polynomials of degree < n."""
    n = len(x)
    S = np.zeros((n, n))
    for r in range(n):
        c = np.zeros(n)
        c[r] = 1.0
        # Lagrange basis polynomial l_r in monomial coefficients, then integrate from -1.
        others = np.delete(x, r)
        poly = np.poly(others) / np.prod(x[r] - others)
        integral = np.polyint(poly)
        S[:, r] = np.polyval(integral, x) - np.polyval(integral, -1.0)
    return S


def _cos_sin(theta: NDArray) -> tuple[NDArray, NDArray]:
    """``(cos theta, sin theta)``; for complex ``theta = a + i b`` (the complex steps of a
    Jacobian) from real functions, ``cos = cos a cosh b - i sin a sinh b`` and
    ``sin = sin a cosh b + i cos a sinh b`` (exact identities, ~4x cheaper than numpy's
    complex trigonometry on these small arrays)."""
    if not np.iscomplexobj(theta):
        return np.cos(theta), np.sin(theta)
    a, b = theta.real, theta.imag
    ca, sa, chb, shb = np.cos(a), np.sin(a), np.cosh(b), np.sinh(b)
    return ca * chb - 1j * (sa * shb), sa * chb + 1j * (ca * shb)


#: Largest mesh of the nonlinear rod (the chapter's figures use 16, the linearisation study
#: 32): the state has 2 x 2N unknowns and the implicit integrators' Jacobians grow as N^2.
MAX_ELEMENTS = 128

_NOT_POSITIVE = ("the rod's mass matrix is not positive definite at this state (the Cholesky "
                 "factorisation failed)")


@named_parameters
@dataclass
class NonlinearRod:
    """The discretised rod: ``rod`` (SI), ``n_elements`` P2 elements, ``n_gauss`` points each."""

    rod: Rod
    n_elements: int
    n_gauss: int = 5

    def __post_init__(self) -> None:
        if not isinstance(self.rod, Rod):
            raise ParameterError(f"rod must be a Rod (SI parameters), got "
                                 f"{type(self.rod).__name__}")
        check_integer("n_elements", self.n_elements, 1, MAX_ELEMENTS)
        check_integer("n_gauss", self.n_gauss, 1, 20)
        N, ng = int(self.n_elements), int(self.n_gauss)
        L = self.rod.length
        h = L / N
        xg, wg = legendre.leggauss(ng)
        self.h = h
        self.n_dof = 2 * N  # nodes 1..2N (node 0 is clamped)
        e = np.repeat(np.arange(N), ng)
        xi = np.tile(xg, N)
        self.s = (e + (xi + 1) / 2) * h  # quadrature points along the rod
        self.w = np.tile(wg, N) * h / 2
        self.elem = e
        # P2 shape functions on [-1, 1] at the Gauss points: nodes -1, 0, 1.
        N0, N1, N2 = xi * (xi - 1) / 2, 1 - xi**2, xi * (xi + 1) / 2
        dN0, dN1, dN2 = (xi - 0.5), -2 * xi, (xi + 0.5)
        phi = np.zeros((N * ng, 2 * N + 1))
        dphi = np.zeros_like(phi)
        rows = np.arange(N * ng)
        for k, (f, df) in enumerate(((N0, dN0), (N1, dN1), (N2, dN2))):
            cols = 2 * e + k
            phi[rows, cols] = f
            dphi[rows, cols] = df * 2 / h
        self.phi = phi[:, 1:]  # drop the clamped node
        self.dphi = dphi[:, 1:]
        self.S = _integration_matrix(xg) * h / 2  # within-element cumulative integral
        self.wg = wg * h / 2
        self.sqrt_w = np.sqrt(self.w)
        stiff = np.einsum("q,qi,qj->ij", self.w, self.dphi, self.dphi)
        self.K = self.rod.B * stiff
        self.C = self.rod.D * stiff
        self.int_phi = self.w @ self.phi  # int phi_i
        self.int_phiphi = np.einsum("q,qi,qj->ij", self.w, self.phi, self.phi)

    def nodal_values_at(self, q: NDArray, s: NDArray) -> NDArray:
        """The P2 field with nodal values ``q`` evaluated at the abscissae ``s`` (e.g. the nodes
        of a finer mesh: mesh continuation)."""
        s = np.asarray(s, dtype=float)
        length = self.rod.length
        if not (np.all(np.isfinite(s)) and np.all(s >= -1e-12 * length)
                and np.all(s <= length * (1 + 1e-12))):
            # (it extrapolated the end elements' parabolas silently; an outside audit)
            raise ParameterError(f"s must be finite abscissae in [0, l] = [0, {length:g}] m")
        full = np.concatenate([[0.0], np.asarray(q, dtype=float)])
        e = np.clip((s // self.h).astype(int), 0, int(self.n_elements) - 1)
        xi = 2 * (s - e * self.h) / self.h - 1
        N0, N1, N2 = xi * (xi - 1) / 2, 1 - xi**2, xi * (xi + 1) / 2
        return N0 * full[2 * e] + N1 * full[2 * e + 1] + N2 * full[2 * e + 2]

    # ------------------------------------------------------------------ cumulative integrals
    def _cumint(self, f: NDArray) -> tuple[NDArray, NDArray]:
        """``int_0^{s_q} f`` at every quadrature point and ``int_0^l f``; ``f`` (n_q, ...)."""
        N, ng = int(self.n_elements), int(self.n_gauss)
        # matmul, not einsum: this runs on every right-hand side and BLAS is ~5x faster here.
        fe = f.reshape(N, ng, -1)
        within = self.S @ fe
        full = self.wg @ fe
        before = np.cumsum(full, axis=0) - full
        return ((before[:, None] + within).reshape(f.shape),
                full.sum(axis=0).reshape(f.shape[1:]))

    def kinematics(self, q: NDArray):
        """``(theta, t, G, G_tip)`` at the quadrature points for nodal rotations ``q`` of shape
        ``(n_dof,)`` or ``(n_dof, m)`` (``m`` states at once, e.g. the complex steps of a
        Jacobian): shapes ``(n_q, *b)``, ``(n_q, *b, 2)``, ``(n_q, *b, 2, n_dof)``,
        ``(*b, 2, n_dof)`` with ``b = q.shape[1:]``."""
        theta = self.phi @ q
        c, s = _cos_sin(theta)
        t = np.stack([c, s], axis=-1)
        tp = np.stack([-s, c], axis=-1)
        phi = self.phi.reshape(self.phi.shape[0], *([1] * (q.ndim - 1)), 1, self.n_dof)
        G, G_tip = self._cumint(tp[..., None] * phi)
        return theta, t, G, G_tip

    def tip_lateral_velocity(self, q: NDArray, v: NDArray):
        """The tip's lateral velocity ``int_0^l cos(theta) theta_dot ds`` (the second row of
        ``G_tip v``) without the cumulative integrals of :meth:`kinematics`: the Poincaré
        section's function, which the integrators evaluate at every step (~10x cheaper)."""
        return self.w @ (_cos_sin(self.phi @ q)[0] * (self.phi @ v))

    def tip_position(self, q: NDArray) -> NDArray:
        theta = self.phi @ q
        _, x_tip = self._cumint(np.stack([np.cos(theta), np.sin(theta)], axis=-1))
        return x_tip

    # ------------------------------------------------------------------ equations of motion
    def _flat(self, G: NDArray, weights: NDArray) -> NDArray:
        """``G`` (n_q, *b, 2, n) weighted by ``weights`` (n_q,) as ``(*b, 2 n_q, n)``."""
        Gw = G * weights.reshape(-1, *([1] * (G.ndim - 1)))
        if G.ndim > 3:  # moveaxis costs ~10 us of Python: only where there is a batch axis
            Gw = np.moveaxis(Gw, 0, -3)
        return Gw.reshape(*Gw.shape[:-3], -1, self.n_dof)

    def mass_matrix(self, G: NDArray, G_tip: NDArray) -> NDArray:
        r = self.rod
        A = self._flat(G, self.sqrt_w)
        return r.rho * (np.swapaxes(A, -1, -2) @ A) + r.tip_mass * (
            np.swapaxes(G_tip, -1, -2) @ G_tip)

    def dynamic_terms(self, q: NDArray, v: NDArray, P) -> tuple[NDArray, NDArray]:
        """``(M(q), g(q, v))`` with ``M(q) q_ddot + g = 0``: ``g = h + K q + C v - F``.

        ``q``, ``v`` of shape ``(n_dof,)`` or ``(n_dof, m)`` (``m`` states at once; ``P`` a
        number or ``m`` loads); ``M`` has shape ``(*b, n, n)`` and ``g`` ``(*b, n)``."""
        r = self.rod
        theta, t, G, G_tip = self.kinematics(q)
        M = self.mass_matrix(G, G_tip)
        theta_dot = self.phi @ v
        a_c, a_c_tip = self._cumint(-t * theta_dot[..., None] ** 2)
        Gw = self._flat(G, self.w)
        GwT = np.swapaxes(Gw, -1, -2)
        batched = q.ndim > 1
        a_flat = (np.moveaxis(a_c, 0, -2) if batched else a_c).reshape(*a_c.shape[1:-1], -1)
        h = r.rho * (GwT @ a_flat[..., None])[..., 0]
        if r.tip_mass > 0:
            h = h + r.tip_mass * (np.swapaxes(G_tip, -1, -2) @ a_c_tip[..., None])[..., 0]
        F = -P * (self.phi.T @ (self.w.reshape(-1, *([1] * (q.ndim - 1)))
                                * np.sin(q[-1] - theta)))
        Kq = self.K @ q + self.C @ v
        if batched:
            F, Kq = F.T, Kq.T
        if r.kappa > 0:
            xdot = (G * (v.T if batched else v)[..., None, :]).sum(axis=-1)  # (n_q, *b, 2)
            x_flat = (np.moveaxis(xdot, 0, -2) if batched else xdot).reshape(
                *xdot.shape[1:-1], -1)
            F = F - r.kappa * (GwT @ x_flat[..., None])[..., 0]
        return M, h + Kq - F

    def accelerations(self, q: NDArray, v: NDArray, P) -> NDArray:
        """``q_ddot`` of the equations of motion, same shape as ``q``."""
        M, g = self.dynamic_terms(q, v, P)
        if q.ndim == 1:
            return np.linalg.solve(M, -g)
        return np.linalg.solve(M, -g[..., None])[..., 0].T

    def rhs(self, t: float, y: NDArray, P) -> NDArray:
        """First-order form ``y' = (v, q_ddot)``; ``y`` of shape ``(2 n_dof,)`` or
        ``(2 n_dof, m)`` (then ``P`` a number or ``m`` loads)."""
        n = self.n_dof
        if y.ndim == 1 and not np.iscomplexobj(y) and np.ndim(P) == 0:
            P = float(P)
            if P - P != 0.0:  # NaN or inf (NaN accelerations, silently; an outside audit)
                raise ParameterError(f"P must be a finite load [N], got {P!r}")
            return self._rhs_one(y, P)
        if not np.all(np.isfinite(P)):
            raise ParameterError(f"P must be a finite load [N], got {P!r}")
        return np.concatenate([y[n:], self.accelerations(y[:n], y[n:], P)])

    def kernel_args(self, P: float) -> tuple:
        """The compiled kernels' arguments after the state (:func:`flutterfriction.models.
        rod_kernel.rhs_one`): the load ``P`` [N] (checked finite), the discretisation and the
        rod's constants."""
        r = self.rod
        return (check_real("P", P), self.phi, self.w, self.S, self.wg, self.K, self.C, r.rho,
                r.tip_mass, r.kappa)

    def rhs_at(self, P: float):
        """``f(t, y)``: :meth:`rhs` for one real state at the load ``P`` [N], for an
        integrator's many calls (the compiled kernel with its arguments bound once)."""
        from flutterfriction.models.rod_kernel import rhs_one  # numba: imported where used

        args = self.kernel_args(P)

        size = 2 * self.n_dof

        def f(t: float, y: NDArray) -> NDArray:
            y = np.ascontiguousarray(y, dtype=float)  # one layout: one compiled specialisation
            if y.shape != (size,):  # the kernel does not check its indices
                raise ParameterError(f"the state must have shape ({size},) (q and v of "
                                     f"{size // 2} nodes), got {y.shape}")
            out, ok = rhs_one(y, *args)
            if not ok:
                raise ConvergenceError(_NOT_POSITIVE)
            return out

        return f

    def dynamic_terms_at(self, P: float):
        """``(q, v) -> (M, g)``: :meth:`dynamic_terms` for one real state at the load ``P``
        [N], compiled (:func:`flutterfriction.models.rod_kernel._assemble`, its arguments
        bound once; ~10x cheaper than the batched definition, which
        ``tests/test_rod_nonlinear.py`` checks it against): for an implicit structural
        integrator's residuals."""
        from flutterfriction.models.rod_kernel import _assemble  # numba: imported where used

        args = self.kernel_args(P)
        n = self.n_dof
        y = np.empty(2 * n)

        def terms(q: NDArray, v: NDArray) -> tuple[NDArray, NDArray]:
            if np.shape(q) != (n,) or np.shape(v) != (n,):  # (a number would broadcast)
                raise ParameterError(f"q and v must have shape ({n},), got {np.shape(q)}, "
                                     f"{np.shape(v)}")
            if np.iscomplexobj(q) or np.iscomplexobj(v):  # (its imaginary part would be lost)
                raise ParameterError("q and v must be real here; complex steps go through "
                                     "dynamic_terms")
            y[:n], y[n:] = q, v
            M, g = _assemble(y, *args)[:2]
            # the kernel fills M's upper triangle (its Cholesky reads only that)
            return np.triu(M) + np.triu(M, 1).T, g

        return terms

    def jacobians(self, Y: NDArray, P: float) -> tuple[NDArray, NDArray]:
        """``(J, f_P)``: the Jacobian ``d y'/d y`` (m, N, N) and ``d y'/d P`` (m, N) of
        :meth:`rhs` at the ``m`` real states ``Y`` (N, m), differentiated by hand and compiled
        (:func:`flutterfriction.models.rod_kernel.jacobian_one`: ~17 us per state at 4
        elements against ~400 us by complex steps on the batched definition, which checks it
        in ``tests/test_rod_nonlinear.py``)."""
        from flutterfriction.models.rod_kernel import jacobians  # numba: imported where used

        r = self.rod
        # C order always: one compiled specialisation (a second layout compiles again, ~4 s)
        Y = np.ascontiguousarray(Y, dtype=float)
        if Y.ndim != 2 or Y.shape[0] != 2 * self.n_dof:  # the kernel does not check indices
            raise ParameterError(f"the states must have shape ({2 * self.n_dof}, m), got "
                                 f"{Y.shape}")
        J, f_P, ok = jacobians(Y, check_real("P", P), self.phi, self.w, self.S, self.wg,
                               self.K, self.C, r.rho, r.tip_mass, r.kappa)
        if not ok:
            raise ConvergenceError(_NOT_POSITIVE)
        return J, f_P

    def _rhs_one(self, y: NDArray, P: float) -> NDArray:
        """:meth:`rhs` for one real state: the same equations as :meth:`dynamic_terms`,
        compiled (:func:`flutterfriction.models.rod_kernel.rhs_one`; an explicit integrator
        calls this ~1e6 times per branch; the batched path stays the definition,
        ``tests/test_rod_nonlinear.py`` checks both agree)."""
        return self.rhs_at(P)(0.0, y)

    # ------------------------------------------------------------------ linearisation
    def linear_matrices(self):
        """``(M0, C, K, dK/dP)`` of the linearisation about the straight rod:
        ``M0 q_ddot + C q_dot + (K + P K1) q = 0`` with ``K1 = int phi (x) (e_tip - phi)``
        (from ``F_i = -P int (theta_l - theta) phi_i``)."""
        _, _, G, G_tip = self.kinematics(np.zeros(self.n_dof))
        M0 = self.mass_matrix(G, G_tip)
        e_tip = np.zeros(self.n_dof)
        e_tip[-1] = 1.0
        K1 = np.outer(self.int_phi, e_tip) - self.int_phiphi
        C = self.C.copy()
        if self.rod.kappa > 0:
            C = C + self.rod.kappa / self.rod.rho * (M0 - self.rod.tip_mass * G_tip.T @ G_tip)
        return M0, C, self.K.copy(), K1

    # ------------------------------------------------------------------ energy
    def power_balance(self, q: NDArray, v: NDArray, P: float):
        """Power of the follower force and viscous dissipation rate [W] at one state (floats),
        or at ``m`` states at once for ``q``, ``v`` of shape ``(n_dof, m)`` (arrays (m,))."""
        batch = np.ndim(q) == 2
        q2 = np.asarray(q, dtype=float).reshape(self.n_dof, -1)
        v2 = np.asarray(v, dtype=float).reshape(self.n_dof, -1)
        # The velocities x_dot(s) = G v = int_0^s t_perp theta_dot ds' (G of :meth:`kinematics`
        # applied to v) integrated as vectors: n_dof times less work than G itself, the cost
        # of a cycle's work quadrature (~280 calls of 400 states in the quick preset's cycle).
        c, s = _cos_sin(self.phi @ q2)
        tp = np.stack([-s, c], axis=-1)  # (n_q, m, 2)
        xdot, xdot_tip = self._cumint(tp * (self.phi @ v2)[..., None])  # (n_q, m, 2), (m, 2)
        power_P = -P * (np.cos(q2[-1]) * xdot_tip[:, 0] + np.sin(q2[-1]) * xdot_tip[:, 1])
        dissipation = np.einsum("im,ij,jm->m", v2, self.C, v2)
        if self.rod.kappa > 0:
            dissipation = dissipation + self.rod.kappa * np.einsum("q,qmc,qmc->m", self.w,
                                                                   xdot, xdot)
        if batch:
            return power_P, dissipation
        return float(power_P[0]), float(dissipation[0])


def compile_kernels() -> dict[str, float]:
    """Compile the rod's kernels (:mod:`flutterfriction.models.rod_kernel`) into numba's cache
    by one call each on a one-element rod, with the argument types every caller uses: the
    seconds each took (~4-5 s each when compiled, ~0.2 s when loaded from the cache). The
    workflow runs this once, before the jobs that integrate the rod, so that they load the
    kernels instead of compiling them side by side."""
    import time

    rod = NonlinearRod(Rod(length=1.0, B=1.0, rho=1.0, D=1e-3), 1)
    y = np.full(2 * rod.n_dof, 0.1)
    seconds = {}
    start = time.perf_counter()
    rod.rhs_at(1.0)(0.0, y)
    seconds["rhs_one"] = time.perf_counter() - start
    start = time.perf_counter()
    rod.jacobians(y[:, None], 1.0)
    seconds["jacobians"] = time.perf_counter() - start
    from flutterfriction.models.rod_kernel import DOP853_COEFFICIENTS, dop853_orbit

    start = time.perf_counter()
    dop853_orbit(y, 1e-3, 1e-6, 1e-9, True, *DOP853_COEFFICIENTS, *rod.kernel_args(1.0))
    seconds["dop853_orbit"] = time.perf_counter() - start
    return seconds


def prolongation(coarse: NonlinearRod, fine: NonlinearRod) -> NDArray:
    """The linear map of states ``(q, v)`` of ``coarse`` to ``fine`` (the P2 fields evaluated
    at the fine nodes)."""
    nodes = np.linspace(0.0, fine.rod.length, fine.n_dof + 1)[1:]
    Pq = np.column_stack([coarse.nodal_values_at(e, nodes) for e in np.eye(coarse.n_dof)])
    Z = np.zeros_like(Pq)
    return np.block([[Pq, Z], [Z, Pq]])
