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
~10 s of compilation (measured on this 2-core machine; 12 s before the slice assignments
below were written element by element).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


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
