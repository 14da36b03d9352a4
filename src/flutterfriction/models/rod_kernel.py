"""The nonlinear rod's one-state right-hand side as a compiled kernel.

Why compiled: an explicit integrator of the 4-element rod calls the right-hand side about a
million times per run of ``beck_branch`` (measured: 1.13e6 calls, half of the job's CPU time).
On this 16-component state numpy's per-operation overhead is the whole cost (~35-45 us per call
in ~15 array operations); the same arithmetic compiled with numba takes ~5 us. The equations are
those of :meth:`flutterfriction.models.rod_nonlinear.NonlinearRod.dynamic_terms` (the batched
numpy definition, which stays the reference: ``tests/test_rod_nonlinear.py`` checks that both
agree to round-off on random states, with and without tip mass and external damping).

Deterministic: no parallel loops and no ``fastmath`` (IEEE arithmetic, no reassociation). The
compiled code is cached next to this file (``__pycache__``), so only the first process pays the
~8 s of compilation (measured on this 2-core machine; 12 s before the slice assignments
below were written element by element, 10 s at numba's default optimisation level).

LLVM optimisation level 1 (``NUMBA_OPT``, numba's default 3) unless the user set one: the
kernels' compilation took 10.0 CPU-s at level 3 and 8.1 at level 1, their run time the same
(beck_branch 7.5 s either way), and without ``fastmath`` LLVM keeps IEEE semantics at every
level: the data of beck_branch, beck_limit_cycle, beck_hopf and beck_work_precision came out
bit for bit the same (measured). Level 0 made beck_branch 10x slower. It applies if numba is
first imported here (it reads the variable once); otherwise numba's level stays.
"""

from __future__ import annotations

import math
import os

os.environ.setdefault("NUMBA_OPT", "1")  # before numba's import (see above)

import numpy as np  # noqa: E402
from numba import njit  # noqa: E402
from scipy.integrate._ivp import dop853_coefficients as _dop853  # noqa: E402


@njit(cache=True)
def _assemble(y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa):  # pragma: no cover
    """The equations of motion at one state: ``M``, ``g`` (``M q_ddot + g = 0``) and the
    intermediate fields the Jacobian reuses (see :func:`rhs_one` for the arguments)."""
    nq, n = phi.shape
    ng = S.shape[0]
    n_el = nq // ng
    q = y[:n]
    v = y[n:]
    c = np.empty(nq)
    s = np.empty(nq)
    td = np.empty(nq)
    td2 = np.empty(nq)
    sn = np.empty(nq)
    cn = np.empty(nq)
    for a in range(nq):
        th = 0.0
        thd = 0.0
        for j in range(n):
            th += phi[a, j] * q[j]
            thd += phi[a, j] * v[j]
        c[a] = math.cos(th)
        s[a] = math.sin(th)
        td[a] = thd
        td2[a] = thd * thd
        sn[a] = math.sin(q[n - 1] - th)
        cn[a] = math.cos(q[n - 1] - th)
    # G_j(s_a) = int_0^{s_a} t_perp phi_j (x: Gx, y: Gy; stored transposed, (n, n_q)) and the
    # centripetal integrals int_0^{s_a} t theta_dot^2 (ax, ay): whole elements before (a running
    # sum over the element's nodes), plus the integration matrix within the element.
    Gx = np.zeros((n, nq))
    Gy = np.zeros((n, nq))
    ax = np.zeros(nq)
    ay = np.zeros(nq)
    bx = np.zeros(n)
    by = np.zeros(n)
    bax = 0.0
    bay = 0.0
    for e in range(n_el):
        j0 = max(2 * e - 1, 0)  # the element's nodes 2e, 2e+1, 2e+2 are columns 2e-1..2e+1
        j1 = 2 * e + 2
        for a in range(ng):
            ia = e * ng + a
            for j in range(n):
                Gx[j, ia] = bx[j]
                Gy[j, ia] = by[j]
            sx = bax
            sy = bay
            for b in range(ng):
                ib = e * ng + b
                sab = S[a, b]
                for j in range(j0, j1):
                    Gx[j, ia] -= sab * s[ib] * phi[ib, j]
                    Gy[j, ia] += sab * c[ib] * phi[ib, j]
                sx += sab * c[ib] * td2[ib]
                sy += sab * s[ib] * td2[ib]
            ax[ia] = sx
            ay[ia] = sy
        for b in range(ng):
            ib = e * ng + b
            for j in range(j0, j1):
                bx[j] -= wg[b] * s[ib] * phi[ib, j]
                by[j] += wg[b] * c[ib] * phi[ib, j]
            bax += wg[b] * c[ib] * td2[ib]
            bay += wg[b] * s[ib] * td2[ib]
    # M = rho int G^T G (+ tip mass), g = h + K q + C v - F (see dynamic_terms).
    M = np.zeros((n, n))
    g = np.zeros(n)
    for i in range(n):
        for j in range(i, n):
            acc = 0.0
            for a in range(nq):
                acc += w[a] * (Gx[i, a] * Gx[j, a] + Gy[i, a] * Gy[j, a])
            M[i, j] = rho * acc
        hh = 0.0
        ff = 0.0
        for a in range(nq):
            hh += w[a] * (Gx[i, a] * ax[a] + Gy[i, a] * ay[a])
            ff += phi[a, i] * w[a] * sn[a]
        g[i] = -rho * hh + P * ff
    if tip_mass > 0.0:  # G(l) = bx, by; int_0^l t theta_dot^2 = bax, bay
        for i in range(n):
            for j in range(i, n):
                M[i, j] += tip_mass * (bx[i] * bx[j] + by[i] * by[j])
            g[i] -= tip_mass * (bx[i] * bax + by[i] * bay)
    if kappa > 0.0:  # external damping -kappa x_dot per length
        xv, yv = _along(Gx, Gy, v)
        for i in range(n):
            acc = 0.0
            for a in range(nq):
                acc += w[a] * (Gx[i, a] * xv[a] + Gy[i, a] * yv[a])
            g[i] += kappa * acc
    for i in range(n):
        acc = 0.0
        for j in range(n):
            acc += K[i, j] * q[j] + C[i, j] * v[j]
        g[i] += acc
    return M, g, c, s, td, td2, sn, cn, Gx, Gy, ax, ay, bx, by, bax, bay


@njit(cache=True)
def _along(Gx, Gy, x):  # pragma: no cover (compiled)
    """``sum_j G_j(s_a) x_j`` at every point ``a`` (x and y components): the points' velocity
    for ``x = q_dot``, the part of their acceleration in ``q_ddot`` for ``x = q_ddot``."""
    n, nq = Gx.shape
    px = np.zeros(nq)
    py = np.zeros(nq)
    for j in range(n):
        for a in range(nq):
            px[a] += Gx[j, a] * x[j]
            py[a] += Gy[j, a] * x[j]
    return px, py


@njit(cache=True)
def _cholesky(M):  # pragma: no cover (compiled)
    """Lower ``L`` with ``M = L L^T`` (upper triangle of ``M`` read) and whether ``M`` is
    positive definite (M is a Gram matrix: symmetric positive definite on any real state)."""
    n = M.shape[0]
    L = np.zeros((n, n))
    for j in range(n):
        d = M[j, j]
        for k in range(j):
            d -= L[j, k] * L[j, k]
        if not d > 0.0:
            return L, False
        d = math.sqrt(d)
        L[j, j] = d
        for i in range(j + 1, n):
            e = M[j, i]
            for k in range(j):
                e -= L[i, k] * L[j, k]
            L[i, j] = e / d
    return L, True


@njit(cache=True)
def _solve(L, b, out):  # pragma: no cover (compiled)
    """``out = (L L^T)^-1 b``."""
    n = L.shape[0]
    z = np.empty(n)
    for i in range(n):
        e = b[i]
        for k in range(i):
            e -= L[i, k] * z[k]
        z[i] = e / L[i, i]
    for i in range(n - 1, -1, -1):
        e = z[i]
        for k in range(i + 1, n):
            e -= L[k, i] * out[k]
        out[i] = e / L[i, i]


@njit(cache=True)
def rhs_one(y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa):  # pragma: no cover (compiled)
    """``(y', ok)``: ``y' = (v, q_ddot)`` of ``M(q) q_ddot + h + K q + C v = F`` for one real
    state ``y = (q, v)`` under the follower load ``P`` [N]; ``ok`` is False when ``M(q)`` is not
    positive definite (then ``y'`` is undefined).

    ``phi`` (n_q, n) the P2 shape functions at the Gauss points (element by element, ``n_g``
    points each, node 0 clamped), ``w`` the quadrature weights, ``S`` (n_g, n_g) the element's
    cumulative-integration matrix and ``wg`` its weights, ``K``, ``C`` the bending stiffness and
    Kelvin–Voigt viscosity matrices; ``rho`` [kg/m], ``tip_mass`` [kg], ``kappa`` [N s/m^2].
    """
    n = phi.shape[1]
    M, g = _assemble(y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa)[:2]
    out = np.empty(2 * n)
    L, ok = _cholesky(M)
    if not ok:
        return out, False
    # element by element, not ``out[:n] = y[n:]``: numba's slice assignment compiles a
    # shape-mismatch error message with its string formatting (37 more compiled functions,
    # ~2.5 s of a fresh clone's compilation, measured).
    for i in range(n):
        out[i] = y[n + i]
    _solve(L, -g, out[n:])
    return out, True


@njit(cache=True)
def _cumint_t(h, S, wg):  # pragma: no cover (compiled)
    """``sum_a Cq[a, b] h_a`` for every ``b``: the transpose of the cumulative integral
    (``int_0^{s_a} f = sum_b Cq[a, b] f_b``, whole elements before ``a`` by their weights,
    ``a``'s own element by the integration matrix ``S``)."""
    ng = S.shape[0]
    nq = h.size
    n_el = nq // ng
    out = np.zeros(nq)
    later = 0.0  # sum of h over the elements after the current one
    for e in range(n_el - 1, -1, -1):
        for b in range(ng):
            acc = wg[b] * later
            for a in range(ng):
                acc += S[a, b] * h[e * ng + a]
            out[e * ng + b] = acc
        for a in range(ng):
            later += h[e * ng + a]
    return out


@njit(cache=True)
def jacobian_one(y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa, J, f_P):  # pragma: no cover
    """The Jacobian ``J = d y'/d y`` (N, N) and ``f_P = d y'/d P`` (N,) of :func:`rhs_one` at
    one real state, written into ``J`` and ``f_P``; returns False when ``M(q)`` is not positive
    definite. Differentiated by hand (forward mode through the same fields): with ``q_ddot``
    held, ``R = M q_ddot + g`` has ``dq_ddot/dz = -M^-1 dR/dz``; ``dG_j/dq_k`` and the
    acceleration's ``d/dq_k`` are cumulative integrals of ``phi_k`` times known fields, so
    every term is a sum over quadrature points of ``phi_b,k phi_b,i`` (three nodes per
    element) against a transposed cumulative integral (:func:`_cumint_t`). The complex-step
    Jacobian of the batched definition checks it (``tests/test_rod_nonlinear.py``)."""
    nq, n = phi.shape
    ng = S.shape[0]
    M, g, c, s, td, td2, sn, cn, Gx, Gy, ax, ay, bx, by, bax, bay = _assemble(
        y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa)
    L, ok = _cholesky(M)
    if not ok:
        return False
    acc = np.empty(n)
    _solve(L, -g, acc)
    v = y[n:]
    tdd = np.zeros(nq)  # theta_ddot at the quadrature points
    for a in range(nq):
        for j in range(n):
            tdd[a] += phi[a, j] * acc[j]
    # x_ddot = sum_j G_j q_ddot_j - int t theta_dot^2 at the points (ex, ey) and the tip (EX, EY)
    ex, ey = _along(Gx, Gy, acc)
    ex = w * (ex - ax)
    ey = w * (ey - ay)
    EX = -bax
    EY = -bay
    for j in range(n):
        EX += bx[j] * acc[j]
        EY += by[j] * acc[j]
    Wx = _cumint_t(ex, S, wg)
    Wy = _cumint_t(ey, S, wg)
    Zx = np.empty((n, nq))  # Zx[i, b] = sum_a Cq[a, b] w_a Gx[i, a]
    Zy = np.empty((n, nq))
    tmp = np.empty(nq)
    for i in range(n):
        for a in range(nq):
            tmp[a] = w[a] * Gx[i, a]
        row = _cumint_t(tmp, S, wg)
        for b in range(nq):  # element by element: see rhs_one
            Zx[i, b] = row[b]
        for a in range(nq):
            tmp[a] = w[a] * Gy[i, a]
        row = _cumint_t(tmp, S, wg)
        for b in range(nq):
            Zy[i, b] = row[b]
    Vx = np.zeros(nq)
    Vy = np.zeros(nq)
    if kappa > 0.0:
        xv, yv = _along(Gx, Gy, v)
        Vx = _cumint_t(w * xv, S, wg)
        Vy = _cumint_t(w * yv, S, wg)
    Rq = np.zeros((n, n))  # dR_i/dq_k
    Rv = np.zeros((n, n))  # dR_i/dv_k
    for i in range(n):
        for k in range(n):
            Rq[i, k] = K[i, k]
            Rv[i, k] = C[i, k]
    for b in range(nq):
        e = b // ng
        j0 = max(2 * e - 1, 0)
        j1 = 2 * e + 2
        hx = -c[b] * tdd[b] + s[b] * td2[b]  # d(x_ddot)/dq_k = int phi_k (hx, hy)
        hy = -s[b] * tdd[b] - c[b] * td2[b]
        # the tangent's derivative d t_perp/d theta = -t against the weighted accelerations,
        # the tip's, the load's and the external damping's
        pair = -rho * (c[b] * Wx[b] + s[b] * Wy[b]) \
            - tip_mass * w[b] * (c[b] * EX + s[b] * EY) \
            - P * w[b] * cn[b] - kappa * (c[b] * Vx[b] + s[b] * Vy[b])
        for k in range(j0, j1):
            pk = phi[b, k]
            if pk == 0.0:
                continue
            for i in range(j0, j1):
                Rq[i, k] += pair * pk * phi[b, i]
            for i in range(n):
                Rq[i, k] += pk * (rho * (hx * Zx[i, b] + hy * Zy[i, b])
                                  + tip_mass * w[b] * (bx[i] * hx + by[i] * hy)
                                  - kappa * td[b] * (c[b] * Zx[i, b] + s[b] * Zy[i, b]))
                Rv[i, k] -= 2.0 * td[b] * pk * (rho * (c[b] * Zx[i, b] + s[b] * Zy[i, b])
                                                + tip_mass * w[b] * (c[b] * bx[i]
                                                                     + s[b] * by[i]))
        # the follower load's d/dq_{n-1}: sin(q_{n-1} - theta)
        for i in range(j0, j1):
            Rq[i, n - 1] += P * phi[b, i] * w[b] * cn[b]
    if kappa > 0.0:
        for i in range(n):
            for k in range(n):
                sk = 0.0
                for a in range(nq):
                    sk += w[a] * (Gx[i, a] * Gx[k, a] + Gy[i, a] * Gy[k, a])
                Rv[i, k] += kappa * sk
    # J = [[0, I], [-M^-1 Rq, -M^-1 Rv]]; f_P = (0, -M^-1 dR/dP), dR/dP = int phi sin(.)
    col = np.empty(n)
    sol = np.empty(n)
    for i in range(2 * n):
        for k in range(2 * n):
            J[i, k] = 0.0
    for i in range(n):
        J[i, n + i] = 1.0
    for k in range(n):
        for i in range(n):
            col[i] = -Rq[i, k]
        _solve(L, col, sol)
        for i in range(n):
            J[n + i, k] = sol[i]
        for i in range(n):
            col[i] = -Rv[i, k]
        _solve(L, col, sol)
        for i in range(n):
            J[n + i, n + k] = sol[i]
    for i in range(n):
        ff = 0.0
        for a in range(nq):
            ff += phi[a, i] * w[a] * sn[a]
        col[i] = -ff
    _solve(L, col, sol)
    for i in range(n):
        f_P[i] = 0.0
        f_P[n + i] = sol[i]
    return True


@njit(cache=True)
def jacobians(Y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa):  # pragma: no cover
    """:func:`jacobian_one` at the ``m`` states ``Y`` (N, m): ``(J (m, N, N), f_P (m, N),
    ok)``."""
    N, m = Y.shape
    J = np.empty((m, N, N))
    f_P = np.empty((m, N))
    y = np.empty(N)
    for k in range(m):
        for i in range(N):
            y[i] = Y[i, k]
        if not jacobian_one(y, P, phi, w, S, wg, K, C, rho, tip_mass, kappa, J[k], f_P[k]):
            return J, f_P, False
    return J, f_P, True


# ---------------------------------------------------------------------- the orbit's integrator
# scipy's DOP853 (Hairer's explicit Runge-Kutta of order 8, error estimators of orders 5 and 3,
# dense output of order 7), step for step as scipy.integrate.solve_ivp(method="DOP853") takes
# it (rk.py: rk_step, _step_impl, _estimate_error_norm, _dense_output_impl; common.py:
# select_initial_step), with the rod's kernel called in the compiled loop. Why: on the 4-element
# rod's 16 states, scipy's per-step Python (the stages' dots, the error norm, the dense output)
# and the per-call wrappers around the kernel were ~3/4 of an orbit's CPU time (measured in
# beck_branch: 1.04e6 right-hand sides, 71e3 steps). The same arithmetic in another order of
# summation: results equal scipy's to round-off (tests/test_rod_nonlinear.py).

#: (A, B, C, E3, E5, D) of DOP853, scipy's tables (dop853_coefficients: Hairer's constants),
#: so that the compiled method is the one it is compared with.
DOP853_COEFFICIENTS = tuple(np.ascontiguousarray(getattr(_dop853, k))
                            for k in ("A", "B", "C", "E3", "E5", "D"))
_SAFETY = 0.9
_MIN_FACTOR = 0.2
_MAX_FACTOR = 10.0
_ERROR_EXPONENT = -1.0 / 8.0  # -1 / (error estimator order 7 + 1)


@njit(cache=True)
def _rms(x):  # pragma: no cover (compiled)
    s = 0.0
    for v in x:
        s += v * v
    return math.sqrt(s) / math.sqrt(x.size)


@njit(cache=True)
def _stage(K, s, a, h, y, out):  # pragma: no cover (compiled)
    """``out = y + h (K[:s].T @ a[:s])``, as scipy's ``y + np.dot(K[:s].T, a[:s]) * h``."""
    for i in range(y.size):
        acc = 0.0
        for j in range(s):
            acc += K[j, i] * a[j]
        out[i] = y[i] + acc * h


@njit(cache=True)
def _stages(Kx, first, last, A, h, y, tmp, P, phi, w, S, wg, K_b, C_v, rho, tip_mass,
            kappa):  # pragma: no cover (compiled)
    """Runge-Kutta stages ``first .. last - 1``: ``Kx[s] = f(y + h sum_j A[s, j] Kx[j])``.
    Returns ``(ok, evaluations)``; ``ok`` False where the mass matrix was not positive
    definite."""
    for s in range(first, last):
        _stage(Kx, s, A[s], h, y, tmp)
        k, ok = rhs_one(tmp, P, phi, w, S, wg, K_b, C_v, rho, tip_mass, kappa)
        if not ok:
            return False, s - first + 1
        for i in range(y.size):
            Kx[s, i] = k[i]
    return True, last - first


@njit(cache=True)
def dop853_orbit(y0, t_end, rtol, atol, dense, A, B, Cn, E3, E5, D, P, phi, w, S, wg, K_b,
                 C_v, rho, tip_mass, kappa):  # pragma: no cover (compiled)
    """Integrate ``y' = rhs_one(y, P, ...)`` from ``t = 0`` to ``t_end`` > 0 by DOP853.

    ``A`` (16, 16), ``B`` (12,), ``Cn`` (16,), ``E3``, ``E5`` (13,), ``D`` (4, 16): the method's
    coefficients (scipy's ``dop853_coefficients``); the rest as :func:`rhs_one`. Returns
    ``(status, ts, ys, F, n_fev)``: status 0 (reached ``t_end``), 1 (step size below
    10 ulp of t: scipy's "Required step size is less than spacing between numbers"), 2 (the
    mass matrix was not positive definite); ``ts`` (m + 1,), ``ys`` (m + 1, N) and, with
    ``dense``, ``F`` (m, 7, N) the dense-output coefficients of each step (scipy's
    ``Dop853DenseOutput.F``), else an empty array."""
    n = y0.size
    # Stage counts as run-time integers (np.int64), not literals: numba compiles a callee once
    # per literal value it is called with (_stage, _stages were compiled twice each).
    n_stages = np.int64(12)
    first = np.int64(1)
    n_all = np.int64(16)
    cap = 64
    ts = np.empty(cap)
    ys = np.empty((cap, n))
    F = np.empty((cap if dense else 0, 7, n))
    Kx = np.empty((16, n))
    tmp = np.empty(n)
    y = y0.copy()
    f, ok = rhs_one(y, P, phi, w, S, wg, K_b, C_v, rho, tip_mass, kappa)
    n_fev = 1
    if not ok:
        return 2, ts[:1], ys[:1], F[:0], n_fev
    ts[0] = 0.0
    # copies element by element, not ``ys[0] = y``: numba's array assignment compiles a
    # shape-mismatch error with its string formatting (three signatures here, ~4.8 s of a
    # fresh clone's 28-s compilation, measured; the values are the same)
    for i in range(n):
        ys[0, i] = y[i]
    m = 0
    # select_initial_step (order 7)
    scale = np.empty(n)
    for i in range(n):
        scale[i] = atol + abs(y[i]) * rtol
    d0 = _rms(y / scale)
    d1 = _rms(f / scale)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, t_end)
    for i in range(n):
        tmp[i] = y[i] + h0 * f[i]
    f1, ok = rhs_one(tmp, P, phi, w, S, wg, K_b, C_v, rho, tip_mass, kappa)
    n_fev += 1
    if not ok:
        return 2, ts[:1], ys[:1], F[:0], n_fev
    d2 = _rms((f1 - f) / scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    h_abs = min(100 * h0, h1, t_end)
    t = 0.0
    y_new = np.empty(n)
    while t < t_end:
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        if h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if h_abs < min_step:
                return 1, ts[:m + 1], ys[:m + 1], F[:m], n_fev
            t_new = t + h_abs
            if t_new - t_end > 0:
                t_new = t_end
            h = t_new - t
            h_abs = abs(h)
            # rk_step
            for i in range(n):
                Kx[0, i] = f[i]
            ok, k_fev = _stages(Kx, first, n_stages, A, h, y, tmp, P, phi, w, S, wg, K_b, C_v,
                                rho, tip_mass, kappa)
            n_fev += k_fev
            if not ok:
                return 2, ts[:m + 1], ys[:m + 1], F[:m], n_fev
            _stage(Kx, n_stages, B, h, y, y_new)
            f_new, ok = rhs_one(y_new, P, phi, w, S, wg, K_b, C_v, rho, tip_mass, kappa)
            n_fev += 1
            if not ok:
                return 2, ts[:m + 1], ys[:m + 1], F[:m], n_fev
            for i in range(n):
                Kx[n_stages, i] = f_new[i]
            # _estimate_error_norm
            e5 = 0.0
            e3 = 0.0
            for i in range(n):
                sc = atol + max(abs(y[i]), abs(y_new[i])) * rtol
                a5 = 0.0
                a3 = 0.0
                for j in range(n_stages + 1):
                    a5 += Kx[j, i] * E5[j]
                    a3 += Kx[j, i] * E3[j]
                e5 += (a5 / sc) ** 2
                e3 += (a3 / sc) ** 2
            if e5 == 0.0 and e3 == 0.0:
                error_norm = 0.0
            else:
                error_norm = h_abs * e5 / math.sqrt((e5 + 0.01 * e3) * n)
            if error_norm < 1:
                if error_norm == 0:
                    factor = _MAX_FACTOR
                else:
                    factor = min(_MAX_FACTOR, _SAFETY * error_norm ** _ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(_MIN_FACTOR, _SAFETY * error_norm ** _ERROR_EXPONENT)
            rejected = True
        if m + 1 == ts.size:  # grow the outputs (element by element: see ``ys[0]`` above)
            ts2 = np.empty(2 * ts.size)
            ys2 = np.empty((2 * ts.size, n))
            for k in range(ts.size):
                ts2[k] = ts[k]
                for i in range(n):
                    ys2[k, i] = ys[k, i]
            if dense:
                F2 = np.empty((2 * ts.size, 7, n))
                for k in range(ts.size):
                    for r in range(7):
                        for i in range(n):
                            F2[k, r, i] = F[k, r, i]
                F = F2
            ts, ys = ts2, ys2
        if dense:  # _dense_output_impl: three more stages, then the coefficients
            ok, k_fev = _stages(Kx, n_stages + first, n_all, A, h, y, tmp, P, phi, w, S, wg, K_b,
                                C_v, rho, tip_mass, kappa)
            n_fev += k_fev
            if not ok:
                return 2, ts[:m + 1], ys[:m + 1], F[:m], n_fev
            for i in range(n):
                dy = y_new[i] - y[i]
                F[m, 0, i] = dy
                F[m, 1, i] = h * Kx[0, i] - dy
                F[m, 2, i] = 2 * dy - h * (f_new[i] + Kx[0, i])
                for r in range(4):
                    acc = 0.0
                    for j in range(16):
                        acc += D[r, j] * Kx[j, i]
                    F[m, 3 + r, i] = h * acc
        m += 1
        t = t_new
        ts[m] = t
        for i in range(n):
            y[i] = y_new[i]
            ys[m, i] = y_new[i]
            f[i] = f_new[i]
    return 0, ts[:m + 1], ys[:m + 1], F[:m], n_fev
