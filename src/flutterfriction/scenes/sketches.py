"""The chapter's sketches drawn from the models: Fig. 1 (work of a follower force in a closed
deformation loop), Fig. 10 (the Beck and Pflüger rods with their critical mode shapes) and
Fig. 23 (twinning shear: continuous displacement, rank-one jump of its gradient)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import dblquad
from scipy.linalg import null_space

from flutterfriction.analysis import rod as ar
from flutterfriction.errors import ParameterError, check_positive, check_real
from flutterfriction.models.rod import Rod, RodGroups, lambda_squares
from flutterfriction.models.rod_fe import assemble
from flutterfriction.scenes.common import pendulum_of, quantity, take

#: Gauss-Legendre nodes per leg of a loop: the integrands are trigonometric polynomials of the
#: leg's parameter (bars) or linear in it (rod), so 16 nodes integrate them to round-off.
_GAUSS = np.polynomial.legendre.leggauss(16)


def _leg_work(force, jacobian, q0: NDArray, q1: NDArray) -> float:
    """Work of ``force(q)`` along the straight path ``q0 -> q1`` in the generalised coordinates,
    by Gauss-Legendre quadrature of ``F(q(t)) . J(q(t)) dq/dt``, ``J`` the Jacobian of the
    loaded point's position."""
    t, wts = _GAUSS
    t = 0.5 * (t + 1.0)
    dq = q1 - q0
    return sum(0.5 * wi * float(force(q0 + ti * dq) @ jacobian(q0 + ti * dq) @ dq)
               for ti, wi in zip(t, wts, strict=True))


def _sign(x: float, zero: float) -> str:
    return "zero" if abs(x) <= zero else ("positive" if x > 0 else "negative")


# ---------------------------------------------------------------------- Fig. 1
def fig01(params: dict[str, Any]) -> dict[str, Any]:
    """Fig. 1: the closed deformation loops of the two structures and the follower's work.

    Left, two rigid bars (lengths l1, l2 of ``pendulum``; exact kinematics, any rotation):
    hinge A at the origin, the load ``P`` at C coaxial with BC, pointing from C to B. Rotations
    ``(alpha1, alpha2)`` of AB and BC; the loop 1 -> 2 -> 3 -> 1 is: 1 straight; 2 the whole
    system rotated rigidly by ``beta`` about A (the load passes through A: no work);
    3 AB back to e1 with BC keeping its inclination (the work ``P l1 (1 - cos beta) > 0``);
    back to 1 by rotating BC about B (C moves normal to BC: no work). The generalised forces are
    ``Q1 = P l1 sin(alpha1 - alpha2)``, ``Q2 = 0``: not a gradient, and by Green's theorem the
    net work is the integral of ``P l1 cos(alpha1 - alpha2)`` over the loop's area.

    Right, a clamped rod (length of ``rod``) under a tangential follower load ``P`` at its free
    end, with the caption's small-displacement kinematics: the end moves transversely by ``v``
    and its tangent turns by ``theta``; the load's transverse component is ``-P theta``. The
    loop 1 -> 2 -> 3 -> 4 -> 1 of the caption: rotation at v = 0, translation at
    ``theta = theta0`` (work ``-P theta0 v0 > 0``), rotation back at ``v = v0``, translation
    back at ``theta = 0``. (The axial component ``-P`` works on the end's axial shortening,
    a second-order state function whose sum over a closed loop is zero.) The drawn shapes are
    the static beam-column solutions ``v'''' + p v'' = 0`` (eq. 105, static) with the clamp and
    the imposed end displacement and rotation, ``p = P l^2/B``.
    """
    pend, P, beta, rod, P_rod, v0, th0 = _fig01_inputs(params)
    l1, l2 = pend.l1, pend.l2
    n = int(params.get("n_points", 101))

    # -- two bars, exact kinematics
    def pos_c(q: NDArray) -> NDArray:
        return np.array([l1 * math.cos(q[0]) + l2 * math.cos(q[1]),
                         l1 * math.sin(q[0]) + l2 * math.sin(q[1])])

    def jac_c(q: NDArray) -> NDArray:
        return np.array([[-l1 * math.sin(q[0]), -l2 * math.sin(q[1])],
                         [l1 * math.cos(q[0]), l2 * math.cos(q[1])]])

    def force_bars(q: NDArray) -> NDArray:
        return -P * np.array([math.cos(q[1]), math.sin(q[1])])

    states_b = np.array([[0.0, 0.0], [beta, beta], [0.0, beta]])
    legs_b = {}
    for a, b in ((0, 1), (1, 2), (2, 0)):
        legs_b[f"{a + 1}-{b + 1}"] = _leg_work(force_bars, jac_c, states_b[a], states_b[b])
    closed_b = {"1-2": 0.0, "2-3": P * l1 * (1.0 - math.cos(beta)), "3-1": 0.0}
    net_b = sum(legs_b.values())
    # Green's theorem: the curl P l1 cos(alpha1 - alpha2) over the triangle
    # 0 <= alpha1 <= alpha2 <= beta, which the loop runs counterclockwise in (alpha1, alpha2).
    green_b = dblquad(lambda a1, a2: P * l1 * math.cos(a1 - a2), 0.0, beta, 0.0,
                      lambda a2: a2, epsabs=1e-14, epsrel=1e-13)[0]
    zero_b = 1e-12 * P * (l1 + l2)

    # -- clamped rod, small displacements: q = (v, theta) of the loaded end
    length = rod.length
    p = P_rod * length**2 / rod.B

    def jac_end(q: NDArray) -> NDArray:
        # the end moves transversely only (its axial shortening is second order)
        return np.array([[1.0, 0.0], [0.0, 0.0]])

    def force_rod(q: NDArray) -> NDArray:
        return np.array([-P_rod * q[1], -P_rod])  # -P (theta e_transverse + e_axial)

    states_r = np.array([[0.0, 0.0], [0.0, th0], [v0, th0], [v0, 0.0]])
    legs_r = {}
    for a in range(4):
        b = (a + 1) % 4
        legs_r[f"{a + 1}-{b + 1}"] = _leg_work(force_rod, jac_end, states_r[a], states_r[b])
    closed_r = {"1-2": 0.0, "2-3": -P_rod * th0 * v0, "3-4": 0.0, "4-1": 0.0}
    net_r = sum(legs_r.values())
    # Green: curl of (Q_v, Q_theta) = (-P theta, 0) is P; the signed area of the loop in
    # (v, theta) by the shoelace formula.
    x, y = states_r[:, 0], states_r[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    green_r = P_rod * area
    zero_r = 1e-12 * P_rod * (abs(v0) + abs(th0) * length)
    xi = np.linspace(0.0, 1.0, n)
    shapes = [(_beam_column(p, s_[0] / length, s_[1], xi) * length).tolist() for s_ in states_r]

    q = {}
    for leg in legs_b:
        q[f"bars_work_{leg}"] = quantity(
            legs_b[leg], closed_b[leg], "Gauss-Legendre quadrature of F . dx_C along the leg "
            "(exact kinematics)", "closed form: 0 on the rigid rotations, P l1 (1 - cos beta)",
            "J")
    q["bars_net_work"] = quantity(net_b, green_b, "sum of the legs' quadratures",
                                  "Green's theorem: double integral of P l1 cos(a1 - a2) over "
                                  "the loop's area", "J")
    q["bars_net_work_sign"] = quantity(_sign(net_b, zero_b), _sign(green_b, zero_b),
                                       "sign of the legs' sum", "sign of Green's integral", "")
    for leg in legs_r:
        q[f"rod_work_{leg}"] = quantity(
            legs_r[leg], closed_r[leg], "Gauss-Legendre quadrature of F . dx along the leg "
            "(small displacements)", "closed form: 0, -P theta0 v0, 0, 0", "J")
    q["rod_net_work"] = quantity(net_r, green_r, "sum of the legs' quadratures",
                                 "Green's theorem: P times the loop's signed area in "
                                 "(v, theta)", "J")
    q["rod_net_work_sign"] = quantity(_sign(net_r, zero_r), _sign(green_r, zero_r),
                                      "sign of the legs' sum", "sign of Green's integral", "")
    return {
        "bars": {"l1": l1, "l2": l2, "P": P, "beta": beta, "states": states_b.tolist(),
                 "points": [[[0.0, 0.0], [l1 * math.cos(a1), l1 * math.sin(a1)],
                             pos_c(np.array([a1, a2])).tolist()] for a1, a2 in states_b],
                 "work": legs_b, "net": net_b},
        "rod": {"length": length, "P": P_rod, "p": p, "tip_displacement": v0,
                "tip_rotation": th0, "states": states_r.tolist(), "x": (xi * length).tolist(),
                "shapes": shapes, "work": legs_r, "net": net_r,
                "kinematics": "small displacements (the caption's assumption)"},
        "quantities": q,
    }


def _fig01_inputs(params: dict[str, Any]) -> tuple:
    """Fig. 1's parameters, each checked (one line naming it): the pendulum, ``P_bars``,
    ``beta_deg``, the rod, ``P_rod`` (``p = P_rod l^2/B`` within the rod solver's range and off
    the clamped beam-column's buckling loads), the end's displacement and rotation."""
    take(params, {"pendulum", "P_bars", "beta_deg", "rod", "P_rod", "tip_displacement",
                  "tip_rotation", "n_points"})
    pend = pendulum_of(params)
    P = check_positive("P_bars", params.get("P_bars", 1.0), "N")
    beta = math.radians(check_real("beta_deg", params.get("beta_deg", 30.0)))
    if not 0.0 < beta < math.pi / 2:
        raise ParameterError(f"beta_deg must lie in (0, 90) deg, got {math.degrees(beta)!r}")
    rod = _rod(params)
    P_rod = check_positive("P_rod", params.get("P_rod", 1.0), "N")
    v0 = check_real("tip_displacement", params.get("tip_displacement", 0.03))
    th0 = check_real("tip_rotation", params.get("tip_rotation", -0.2))
    if v0 == 0.0 or th0 == 0.0:
        raise ParameterError("tip_displacement and tip_rotation must be nonzero")
    # (an outside audit: P_rod = 1e20 N was refused as "a buckling load", and at one, in the
    # job only: fig01 had no configuration check)
    bound = ar.P_MAX_LIMIT * rod.load_unit
    if not P_rod <= bound:
        raise ParameterError(f"P_rod must be in (0, {bound:.6g}] N ({ar.P_MAX_LIMIT:g} B/l^2, "
                             f"the rod solver's range), got {P_rod!r}")
    p = P_rod * rod.length**2 / rod.B
    try:
        _beam_column(p, v0 / rod.length, th0, np.zeros(1))
    except ParameterError as exc:
        raise ParameterError(f"P_rod = {P_rod:g} N: {exc}") from None
    return pend, P, beta, rod, P_rod, v0, th0


def check_fig01(params: dict[str, Any]) -> None:
    """Fig. 1's parameters as :func:`fig01` refuses them (the configuration check)."""
    _fig01_inputs(params)


def _rod(params: dict[str, Any]) -> Rod:
    r = params.get("rod")
    if not isinstance(r, dict):
        raise ParameterError("scene parameters need a 'rod' section (length, B, rho, ...)")
    take(r, {"length", "B", "rho", "D", "kappa", "tip_mass"})
    return Rod(**r)


def _beam_column(p: float, v_end: float, theta_end: float, xi: NDArray) -> NDArray:
    """``v(xi)/l`` of ``v'''' + p v'' = 0`` on [0, 1] with ``v(0) = v'(0) = 0`` and the end
    values ``v(1) = v_end`` (in units of l), ``v'(1) = theta_end``; basis 1, xi, cos k xi,
    sin k xi with ``k = sqrt(p)`` (p > 0; not at a clamped-clamped buckling load)."""
    k = math.sqrt(p)
    A = np.array([[1.0, 0.0, 1.0, 0.0],
                  [0.0, 1.0, 0.0, k],
                  [1.0, 1.0, math.cos(k), math.sin(k)],
                  [0.0, 1.0, -k * math.sin(k), k * math.cos(k)]])
    if np.linalg.cond(A) > 1e10:
        raise ParameterError(f"p = {p:.6g} is a buckling load of the clamped beam-column")
    c = np.linalg.solve(A, [0.0, 0.0, v_end, theta_end])
    return c[0] + c[1] * xi + c[2] * np.cos(k * xi) + c[3] * np.sin(k * xi)


# ---------------------------------------------------------------------- Fig. 10
def _exact_mode(p: float, w: complex, g: RodGroups, xi: NDArray) -> tuple[NDArray, NDArray,
                                                                            float]:
    """The mode ``v(xi)`` (normalised to ``v(1) = 1``) and its slope, at a root ``omega~ = w``
    of eq. (118) at load ``p``: the null vector of the boundary matrix of eqs. (114)-(115)
    (undamped; conditions (111) on ``A1 sinh l1 xi + A2 cosh l1 xi + A3 sin l2 xi +
    A4 cos l2 xi``). Also returns the smallest over the largest singular value of the matrix."""
    L1, L2 = lambda_squares(p, w, g)
    l1, l2 = complex(np.sqrt(L1)), complex(np.sqrt(L2))
    mu = complex(w) ** 2
    t = g.tan_alpha
    sh, ch, sn, cs = np.sinh(l1), np.cosh(l1), np.sin(l2), np.cos(l2)
    B = np.array([[0.0, 1.0, 0.0, 1.0],
                  [l1, 0.0, l2, 0.0],
                  [l1**2 * sh, l1**2 * ch, -l2**2 * sn, -l2**2 * cs],
                  [l1**3 * ch - mu * t * sh, l1**3 * sh - mu * t * ch,
                   -l2**3 * cs - mu * t * sn, l2**3 * sn - mu * t * cs]], dtype=complex)
    sv = np.linalg.svd(B, compute_uv=False)
    A = null_space(B, rcond=1e-6)
    if A.shape[1] != 1:
        raise ParameterError(f"the boundary matrix at p = {p:.6g} has a {A.shape[1]}-dimensional"
                             " null space (not a simple root)")
    A = A[:, 0]
    v = (A[0] * np.sinh(l1 * xi) + A[1] * np.cosh(l1 * xi) + A[2] * np.sin(l2 * xi)
         + A[3] * np.cos(l2 * xi))
    dv = (A[0] * l1 * np.cosh(l1 * xi) + A[1] * l1 * np.sinh(l1 * xi)
          + A[2] * l2 * np.cos(l2 * xi) - A[3] * l2 * np.sin(l2 * xi))
    scale = v[-1]
    v, dv = v / scale, dv / scale
    if np.max(np.abs(v.imag)) > 1e-8:
        raise ParameterError("the mode shape is not real (not an undamped critical point)")
    return v.real, dv.real, float(sv[-1] / sv[0])


def _fe_mode(g: RodGroups, p: float, mu: float, n_elements: int) -> dict[str, Any]:
    """The FE twin's mode at its own critical load ``p`` and ``omega~^2 = mu``: the smallest
    right singular vector of ``K + mu M`` (at a coalescence the pair's eigenvectors merge, and
    this vector is their common limit), nodal values normalised to ``v(1) = 1``."""
    fe = assemble(g, n_elements)
    K = fe.K_B + p * fe.load_matrix(True)
    _, _, vh = np.linalg.svd(K + mu * fe.M)
    x = vh[-1]
    u, ux = x[0::2], x[1::2]  # Hermite dofs per node: value, slope (the clamped node removed)
    return {"xi": np.linspace(0.0, 1.0, n_elements + 1).tolist(),
            "v": np.concatenate([[0.0], u / u[-1]]).tolist(),
            "slope": np.concatenate([[0.0], ux / u[-1]]).tolist()}


def fig10(params: dict[str, Any]) -> dict[str, Any]:
    """Fig. 10: the Beck rod (no tip mass) and the Pflüger rod (tip mass ``tan(alpha) = M/(rho
    l)``, undamped) with their mode shapes at the critical loads of the exact eq. (118):
    flutter for both, divergence for the Pflüger rod. Each mode twice: the null vector of the
    boundary matrix (eqs. 114-115) and the finite-element twin at its own critical load."""
    take(params, {"pfluger_tan_alpha", "fe_elements", "n_points", "p_max"})
    t = check_real("pfluger_tan_alpha", params.get("pfluger_tan_alpha", 1.0))
    if t <= 0:
        raise ParameterError(f"pfluger_tan_alpha must be > 0 (the Pflüger rod), got {t!r}")
    n_el = params.get("fe_elements", 32)
    if isinstance(n_el, bool) or not isinstance(n_el, int) or n_el < 2:
        raise ParameterError(f"fe_elements must be an integer >= 2, got {n_el!r}")
    n = int(params.get("n_points", 201))
    p_max = check_positive("p_max", params.get("p_max", 40.0))
    xi = np.linspace(0.0, 1.0, n)
    rods = {"beck": RodGroups(), "pfluger": RodGroups(tan_alpha=t)}
    out: dict[str, Any] = {"xi": xi.tolist(), "pfluger_tan_alpha": t, "fe_elements": n_el,
                           "rods": {}}
    q = {}
    for name, g in rods.items():
        exact = ar.critical_loads(g, p_max=p_max)
        fe = ar.fe_critical_loads(g, n_el, p_max=p_max)
        modes = {}
        for kind in ("flu", "div"):
            p_ex, om_ex = getattr(exact, f"p_{kind}"), getattr(exact, f"omega_{kind}")
            p_fe, om_fe = getattr(fe, f"p_{kind}"), getattr(fe, f"omega_{kind}")
            if p_ex is None:
                continue
            # omega~ = i Omega at flutter, real at divergence: mu = omega~^2
            w = 1j * om_ex if kind == "flu" else om_ex
            mu_fe = -om_fe**2 if kind == "flu" else om_fe**2
            v, dv, cond = _exact_mode(p_ex, w, g, xi)
            fem = _fe_mode(g, p_fe, mu_fe, n_el)
            xn = np.array(fem["xi"])
            v_nodes, _, _ = _exact_mode(p_ex, w, g, xn)
            diff = float(np.max(np.abs(v_nodes - np.array(fem["v"]))))
            modes[kind] = {"p": p_ex, "omega": om_ex, "p_fe": p_fe, "omega_fe": om_fe,
                           "v": v.tolist(), "slope": dv.tolist(), "fe": fem,
                           "max_nodal_difference": diff, "singular_ratio": cond}
            label = "flutter" if kind == "flu" else "divergence"
            q[f"{name}_p_{kind}"] = quantity(
                p_ex, p_fe, f"exact eq. (118), {label} double root (Newton)",
                f"{n_el} cubic Hermite elements", "")
            q[f"{name}_{kind}_mode_tip_slope"] = quantity(
                float(dv[-1]), fem["slope"][-1],
                "v'(1)/v(1) of the null vector of the boundary matrix (eqs. 114-115)",
                f"v'(1)/v(1) of the {n_el}-element twin's mode at its own critical load", "")
        out["rods"][name] = {"tan_alpha": g.tan_alpha, "modes": modes}
    out["quantities"] = q
    return out


# ---------------------------------------------------------------------- Fig. 23
def fig23(params: dict[str, Any]) -> dict[str, Any]:
    """Fig. 23 (eqs. 169-173): the twinning shear ``u = |x . f2| f1`` across the plane of
    normal ``f2`` (``f1 = cos a e1 + sin a e2``, eq. 172), drawn as a square lattice aligned with
    ``f1, f2`` deformed by ``x + s u(x)`` (``s``: the drawing's amplitude; the checked values are
    the chapter's field, ``s = 1``).

    Primary: the gradient on each side by central differences of ``u`` (step ``h``) at points
    ``2h`` off the plane, so that each stencil stays on one side (``u`` is linear there: exact to
    round-off), their difference ``[[grad u]]`` and its singular values. Independent: the
    component form of eq. (173).
    """
    take(params, {"alpha_deg", "amplitude", "n_lines", "n_points"})
    a = math.radians(check_real("alpha_deg", params.get("alpha_deg", 30.0)))
    s = check_positive("amplitude", params.get("amplitude", 0.4))
    n_lines = int(params.get("n_lines", 9))
    n = int(params.get("n_points", 201))
    if n_lines < 3:
        raise ParameterError(f"n_lines must be >= 3, got {n_lines}")
    f1 = np.array([math.cos(a), math.sin(a)])
    f2 = np.array([-math.sin(a), math.cos(a)])

    def u(x: NDArray) -> NDArray:
        return np.abs(x @ f2)[..., None] * f1

    h = 1e-3
    x0 = 0.37 * f1  # a point of the plane

    def grad(at: NDArray) -> NDArray:
        cols = [(u(at + h * e) - u(at - h * e)) / (2 * h) for e in np.eye(2)]
        return np.column_stack(cols)  # G[i, j] = d u_i / d x_j

    jump = grad(x0 + 2 * h * f2) - grad(x0 - 2 * h * f2)
    sv = np.linalg.svd(jump, compute_uv=False)
    sa, ca = math.sin(a), math.cos(a)
    eq173 = 2 * np.array([[-sa * ca, ca**2], [-sa**2, sa * ca]])
    sv173 = np.linalg.svd(eq173, compute_uv=False)
    dyad = 2 * np.outer(f1, f2)

    # The drawing: lines parallel to f1 and to f2 through a square of half-width R.
    R = 1.0
    c = np.linspace(-R, R, n_lines)
    t = np.linspace(-R, R, n)
    lines = []
    for ci in c:
        for along, across in ((f1, f2), (f2, f1)):
            x = ci * across + t[:, None] * along
            y = x + s * u(x)
            lines.append({"reference": x.tolist(), "deformed": y.tolist()})
    q = {
        "jump_largest_singular_value": quantity(
            float(sv[0]), float(sv173[0]), "SVD of the finite-difference jump of grad u",
            "SVD of the components of eq. (173)", ""),
        "jump_second_singular_value": quantity(
            float(sv[1]), float(sv173[1]), "SVD of the finite-difference jump of grad u",
            "SVD of the components of eq. (173)", ""),
        "jump_along_plane": quantity(
            float(np.linalg.norm(jump @ f1)), float(np.linalg.norm(eq173 @ f1)),
            "|[[grad u]] f1|, finite differences", "|eq. (173) f1|", ""),
        "jump_normal_derivative": quantity(
            float(np.linalg.norm(jump @ f2)), float(np.linalg.norm(eq173 @ f2)),
            "|[[grad u]] f2|, finite differences", "|eq. (173) f2|", ""),
        "eq173_minus_dyad": quantity(
            float(np.max(np.abs(eq173 - dyad))), float(np.max(np.abs(jump - dyad))),
            "max |eq. (173) - 2 f1 (x) f2| (components)",
            "max |finite-difference jump - 2 f1 (x) f2|", ""),
    }
    return {"alpha": a, "amplitude": s, "f1": f1.tolist(), "f2": f2.tolist(), "R": R,
            "lines": lines, "jump": jump.tolist(), "singular_values": sv.tolist(),
            "quantities": q}
