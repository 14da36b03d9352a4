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
~3 s of compilation.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


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
    nq, n = phi.shape
    ng = S.shape[0]
    n_el = nq // ng
    q = y[:n]
    v = y[n:]
    c = np.empty(nq)
    s = np.empty(nq)
    td2 = np.empty(nq)
    sn = np.empty(nq)
    for a in range(nq):
        th = 0.0
        thd = 0.0
        for j in range(n):
            th += phi[a, j] * q[j]
            thd += phi[a, j] * v[j]
        c[a] = math.cos(th)
        s[a] = math.sin(th)
        td2[a] = thd * thd
        sn[a] = math.sin(q[n - 1] - th)
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
        xv = np.zeros(nq)
        yv = np.zeros(nq)
        for j in range(n):
            for a in range(nq):
                xv[a] += Gx[j, a] * v[j]
                yv[a] += Gy[j, a] * v[j]
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
    # Cholesky M = L L^T (M is a Gram matrix: symmetric positive definite), then M a = -g.
    out = np.empty(2 * n)
    L = np.zeros((n, n))
    for j in range(n):
        d = M[j, j]
        for k in range(j):
            d -= L[j, k] * L[j, k]
        if not d > 0.0:
            return out, False
        d = math.sqrt(d)
        L[j, j] = d
        for i in range(j + 1, n):
            e = M[j, i]
            for k in range(j):
                e -= L[i, k] * L[j, k]
            L[i, j] = e / d
    z = np.empty(n)
    for i in range(n):
        e = -g[i]
        for k in range(i):
            e -= L[i, k] * z[k]
        z[i] = e / L[i, i]
    for i in range(n - 1, -1, -1):
        e = z[i]
        for k in range(i + 1, n):
            e -= L[k, i] * out[n + k]
        out[n + i] = e / L[i, i]
    for i in range(n):
        out[i] = v[i]
    return out, True
