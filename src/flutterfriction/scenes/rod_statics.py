"""Figs. 6–9 drawn on a computed rod: the clamped elastica of Fig. 9 (§2.5–2.6), geometrically
exact, and on its deformed shape the kinematics of Fig. 6, the internal action at a cut of
Fig. 7 and the equilibrium of a part under the distributed load of Fig. 8.

One scene, :func:`elastica`: the solutions (shooting, collocation, the elliptic-integral closed
form for the end forces alone) and the checked balances of every figure.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from flutterfriction.analysis import elastica as el
from flutterfriction.errors import ConvergenceError, ParameterError, check_real
from flutterfriction.models.rod import Rod
from flutterfriction.scenes.common import n_points, quantity, take

#: Smallest transverse end force [B/l^2] the closed form of the end forces alone resolves
#: (measured on list 119: 1e-30 N solves, 1e-100 N fails to converge).
P2_MIN_OVER_UNIT = 1e-30
_KEYS = {"rod", "P1", "P2", "q1", "q2", "point", "cut", "part", "linear_factors",
         "load_steps", "n_points"}
#: Points of the polylines whose length, extrapolated (Richardson, h^2 -> h^4), measures the
#: inextensibility of the computed curves from their positions alone.
_POLYLINE = 2048


#: The two methods every elastica quantity is computed by (primary, independent).
SHOOTING = "shooting on theta(l), DOP853 rtol 1e-12"
COLLOCATION = "collocation (solve_bvp, tol 1e-10)"

def _fraction(name: str, value: object) -> float:
    x = check_real(name, value)
    if not 0.0 < x < 1.0:
        raise ParameterError(f"{name} must lie in (0, 1) (a fraction of the length l), got {x!r}")
    return x


def _inputs(params: dict[str, Any]) -> tuple[Rod, el.ElasticaLoads, dict[str, Any]]:
    """Every parameter checked before any work (one line naming the bad one)."""
    take(params, _KEYS)
    r = params.get("rod")
    if not isinstance(r, dict):
        raise ParameterError("scene parameters need a 'rod' section (length, B, rho, ...)")
    take(r, {"length", "B", "rho", "D", "kappa", "tip_mass"})
    rod = Rod(**r)
    loads = el.ElasticaLoads(**{k: params.get(k, 0.0) for k in ("P1", "P2", "q1", "q2")})
    if loads.P2 == 0.0:
        raise ParameterError("P2 must be nonzero: the end forces alone are checked against the "
                             "closed form, which needs a transverse end force")
    if loads.P1 < 0.0 and math.atan2(abs(loads.P2), -loads.P1) < el.TENSION_OFF_AXIS_MIN:
        raise ParameterError(
            f"P2: with a pulling end force (P1 < 0) the closed form the end forces are checked "
            f"against needs |P2/P1| >= {math.tan(el.TENSION_OFF_AXIS_MIN):.4g} (the force at "
            f"least {el.TENSION_OFF_AXIS_MIN:g} rad off the axis), got "
            f"{abs(loads.P2 / loads.P1):.3g}")
    # The loads in units of B/l^2 (and B/l^3) within the range the scene's two methods are
    # measured to cover (an outside audit: q2 = 1e6 N/m failed after 23.5 s, 1000 N/m after
    # 86 s here; P2 = 1e-300 N in the closed form, naming no key): at most LOAD_RANGE_MAX (the
    # solvers' own range, el.check_load_range), |P2| at least 1e-30 B/l^2 (measured:
    # 1e-30 N on list 119 solves; 1e-100 N does not)
    el.check_load_range(rod.length, rod.B, loads)
    unit = rod.B / rod.length**2
    if not abs(loads.P2) >= P2_MIN_OVER_UNIT * unit:
        raise ParameterError(f"P2 must be nonzero and at least {P2_MIN_OVER_UNIT:g} B/l^2 = "
                             f"{P2_MIN_OVER_UNIT * unit:.3g} N in magnitude (the closed form's "
                             f"range), got {loads.P2!r}")
    part = params.get("part", [0.3, 0.75])
    if not isinstance(part, list | tuple) or len(part) != 2:
        raise ParameterError(f"part must be two fractions [s1/l, s2/l], got {part!r}")
    s1, s2 = (_fraction("part", p) for p in part)
    if not s1 < s2:
        raise ParameterError(f"part must be increasing, got {part!r}")
    factors = params.get("linear_factors", [1.0, 0.1, 0.01, 0.001])
    if not isinstance(factors, list | tuple) or len(factors) < 2:
        raise ParameterError(f"linear_factors must list >= 2 load factors, got {factors!r}")
    factors = sorted((check_real("linear_factors", f) for f in factors), reverse=True)
    if factors[-1] <= 0.0 or factors[0] > 1.0 or len(set(factors)) != len(factors):
        raise ParameterError(f"linear_factors must be distinct, in (0, 1], got {factors!r}")
    steps = params.get("load_steps", 8)
    if isinstance(steps, bool) or not isinstance(steps, int) or not 1 <= steps <= 1000:
        raise ParameterError(f"load_steps must be an integer in [1, 1000], got {steps!r}")
    return rod, loads, {"point": _fraction("point", params.get("point", 0.6)),
                        "cut": _fraction("cut", params.get("cut", 0.5)),
                        "part": (s1, s2), "factors": factors, "load_steps": steps,
                        "n": n_points(params, 201)}


def _polyline_length(sol: el.ElasticaSolution | el.TipForceElastica, length: float) -> float:
    """The computed curve's length from its positions only: polylines through 2048 and 1024
    equal arc-length steps, Richardson-extrapolated (their error is ``C h^2 + O(h^4)``)."""
    def chord_sum(n: int) -> float:
        x = sol.position(np.linspace(0.0, length, n + 1))
        return float(np.sum(np.hypot(*np.diff(x, axis=0).T)))

    return (4.0 * chord_sum(_POLYLINE) - chord_sum(_POLYLINE // 2)) / 3.0


def _frame(theta: float, curvature: float) -> dict[str, list[float]]:
    """``t`` (eq. 63-64), ``m`` (eq. 71) and ``n = sgn(theta') (-sin, cos)`` (eq. 69)."""
    c, s = math.cos(theta), math.sin(theta)
    sgn = math.copysign(1.0, curvature) if curvature != 0.0 else 0.0
    return {"t": [c, s], "m": [s, -c], "n": [-sgn * s, sgn * c]}


def _curves(sol: el.ElasticaSolution, s: NDArray) -> dict[str, list[float]]:
    st = sol.state(s)
    a = sol.force(s)
    N, T = sol.normal_and_shear(s)
    return {"theta": st[:, 0].tolist(), "M": st[:, 1].tolist(), "x1": st[:, 2].tolist(),
            "x2": st[:, 3].tolist(), "a1": a[:, 0].tolist(), "a2": a[:, 1].tolist(),
            "N": N.tolist(), "T": T.tolist()}


def check_elastica(params: dict[str, Any]) -> None:
    """Figs. 6-9's parameters as :func:`elastica` refuses them (the configuration check)."""
    _inputs(params)


def elastica(params: dict[str, Any]) -> dict[str, Any]:
    """Figs. 6–9: the clamped elastica under ``P = -P1 e1 - P2 e2`` at the end and ``q = q1 e1 +
    q2 e2`` per unit length (eq. 91 at rest), and the balances drawn on it.

    Fig. 9: the shape by shooting (primary) and by collocation (independent); the end forces
    alone by shooting against the elliptic-integral closed form; the small-load limit: the
    transverse loads times ``e`` against the linear cantilever (relative difference ``c e^2``,
    ``c`` from the third-order perturbation of eq. 91). Fig. 6: at ``s = point l``, ``t``,
    ``m``, ``n``, ``theta``, ``u = x - x0 e1``; eqs. (65)-(66) by quadrature against the positions;
    the curve's length from its positions (inextensibility, eq. 60). Fig. 7: at ``s = cut l``
    the internal force ``a`` and moment ``M`` (eqs. 73, 83) against the loads beyond the cut
    (eqs. 74, 89). Fig. 8: the part ``[s1, s2]``: eqs. (74) and (87) as residuals.
    """
    rod, loads, o = _inputs(params)
    l, B = rod.length, rod.B
    tip_loads = el.ElasticaLoads(P1=loads.P1, P2=loads.P2)
    try:
        shoot = el.solve_shooting(l, B, loads, load_steps=o["load_steps"])
        colloc = el.solve_collocation(l, B, loads)
        tip_shoot = el.solve_shooting(l, B, tip_loads, load_steps=o["load_steps"])
        tip_colloc = el.solve_collocation(l, B, tip_loads)
    except ConvergenceError as exc:  # name the config's loads (a config run shows only this)
        euler = math.pi**2 * B / (4 * l * l)
        raise ConvergenceError(
            f"{exc}; elastica: P1, P2, q1, q2 = {loads.P1:g} N, {loads.P2:g} N, {loads.q1:g} "
            f"N/m, {loads.q2:g} N/m: the axial compression at the clamp, P1 - q1 l = "
            f"{loads.P1 - loads.q1 * l:.4g} N, against the Euler load pi^2 B/(4 l^2) = "
            f"{euler:.4g} N (far above it the continuation from the straight rod may not "
            f"follow the branch: smaller loads)"
        ) from None
    s = np.linspace(0.0, l, o["n"])

    # -- the end forces alone: shooting against the closed form
    closed = el.tip_force_closed_form(l, B, loads.P1, loads.P2)
    x_closed = closed.position(s)
    tip_curve_err = float(np.max(np.linalg.norm(tip_shoot.position(s) - x_closed, axis=1)) / l)
    tip_curve_err_c = float(np.max(np.linalg.norm(tip_colloc.position(s) - x_closed, axis=1))
                            / l)
    u_tip_closed = closed.position(l)[0] - np.array([l, 0.0])

    # -- small loads: the transverse loads times e against the linear cantilever
    transverse = el.ElasticaLoads(P2=loads.P2, q2=loads.q2)
    c1, _, c3 = el.perturbation_tip_deflection(l, B, transverse)
    lin = []
    for e in o["factors"]:
        le = transverse.scaled(e)
        u_lin = el.linear_tip_deflection(l, B, le)
        u_s = el.solve_shooting(l, B, le, load_steps=max(1, math.ceil(e * o["load_steps"])))
        u_c = el.solve_collocation(l, B, le)
        lin.append({"factor": e, "linear": u_lin,
                    "shooting": float(u_s.tip_displacement()[1]),
                    "collocation": float(u_c.tip_displacement()[1]),
                    "rel_shooting": float(u_s.tip_displacement()[1] / u_lin - 1.0),
                    "rel_collocation": float(u_c.tip_displacement()[1] / u_lin - 1.0)})
    (e_a, r_a), (e_b, r_b) = ((d["factor"], d) for d in lin[-2:])

    def order(key: str) -> float:
        return math.log(r_a[key] / r_b[key]) / math.log(e_a / e_b)

    # -- Fig. 6: the point s0 = x0
    s0 = o["point"] * l
    th0, M0, *x0 = shoot.state(s0)[0]
    proj = el.projections(shoot)
    proj_c = el.projections(colloc)
    length_s = _polyline_length(shoot, l)
    length_c = _polyline_length(colloc, l)

    # -- Fig. 7: the cut
    sc = o["cut"] * l
    a_beyond = loads.tip_force() + el.gauss_integral(
        lambda x: np.broadcast_to(loads.distributed(), (np.size(x), 2)), sc, l)
    a_colloc = colloc.force(sc)[0]
    (N_c,), (T_c,) = shoot.normal_and_shear(sc)
    M_cut = float(shoot.moment(sc)[0])
    M_eq89 = el.moment_of_loads_beyond(shoot, sc)
    th_c = float(shoot.theta(sc)[0])
    s_cuts = np.linspace(0.0, l, 15)[:-1]  # eq. (89) along the rod, for Fig. 7's right panel
    M_cuts = [el.moment_of_loads_beyond(shoot, float(x)) for x in s_cuts]

    # -- Fig. 8: the part [s1, s2]
    s1, s2 = (f * l for f in o["part"])
    bal = el.part_balances(shoot, s1, s2)
    bal_c = el.part_balances(colloc, s1, s2)
    s_part = np.linspace(s1, s2, max(11, o["n"] // 4))

    u_tip = shoot.tip_displacement()
    u_tip_c = colloc.tip_displacement()
    q = {
        # Fig. 9
        "tip_deflection": quantity(
            float(u_tip[1]), float(u_tip_c[1]), SHOOTING,
            COLLOCATION, "m"),
        "tip_shortening": quantity(
            float(u_tip[0]), float(u_tip_c[0]), SHOOTING,
            COLLOCATION, "m"),
        "tip_rotation": quantity(
            shoot.tip_rotation, colloc.tip_rotation, SHOOTING,
            COLLOCATION, "rad"),
        "tip_force_deflection": quantity(
            float(tip_shoot.tip_displacement()[1]), float(u_tip_closed[1]),
            "shooting, end forces alone", "elliptic integrals (closed form)", "m"),
        "tip_force_shortening": quantity(
            float(tip_shoot.tip_displacement()[0]), float(u_tip_closed[0]),
            "shooting, end forces alone", "elliptic integrals (closed form)", "m"),
        "tip_force_rotation": quantity(
            tip_shoot.tip_rotation, closed.tip_rotation, "shooting, end forces alone",
            "elliptic integrals (closed form)", "rad"),
        "tip_force_curve_error": quantity(
            tip_curve_err, tip_curve_err_c,
            f"max over {o['n']} points of |x - x_closed|/l, shooting (dense output)",
            "the same for collocation", ""),
        "linear_limit_order": quantity(
            order("rel_shooting"), order("rel_collocation"),
            f"log ratio of |u2/u2_linear - 1| at e = {e_a:g}, {e_b:g}, shooting",
            "the same, collocation", ""),
        "linear_limit_coefficient": quantity(
            float(r_b["rel_shooting"] / e_b**2), c3 / c1,
            f"(u2/u2_linear - 1)/e^2 at e = {e_b:g}, shooting",
            "c3/c1 of the third-order perturbation of eq. (91) (exact polynomials)", ""),
        # Fig. 6
        "projection_d": quantity(
            proj["d"], l + float(u_tip[0]), "eq. (65): Gauss-Legendre of cos(theta)",
            "l + u1(l) from the integrated positions", "m"),
        "projection_h": quantity(
            proj["h"], float(u_tip[1]), "eq. (66): Gauss-Legendre of sin(theta)",
            "u2(l) from the integrated positions", "m"),
        "arclength": quantity(
            length_s, length_c, "length of the shooting curve from its positions "
            "(polylines, Richardson)", "the same for the collocation curve", "m"),
        # Fig. 7
        "cut_force": quantity(
            float(np.linalg.norm(a_beyond)), float(np.linalg.norm(a_colloc)),
            "|P + int_s^l q| (the loads beyond the cut, eqs. 74, 97)",
            "|a(s)| integrated by collocation from a(l) = P (eq. 77)", "N"),
        "cut_moment": quantity(
            M_cut, M_eq89, "M = B theta' at the cut (shooting, eq. 83)",
            "eq. (89): moment of the loads beyond the cut about x(s), quadrature over the "
            "computed shape", "N m"),
        # Fig. 8
        "part_force_balance": quantity(
            bal["force"], bal_c["force"], "eq. (74)_1 residual / largest term, shooting",
            "the same, collocation (a a state)", ""),
        "part_moment_balance": quantity(
            bal["moment"], bal_c["moment"], "eq. (74)_2 residual / largest term, shooting",
            "the same, collocation", ""),
        "part_eq87": quantity(
            bal["eq87"], bal_c["eq87"], "eq. (87) integrated over the part / largest term, "
            "shooting", "the same, collocation", ""),
    }
    curv0 = M0 / B
    return {
        "rod": {"length": l, "B": B},
        "loads": {"P1": loads.P1, "P2": loads.P2, "q1": loads.q1, "q2": loads.q2},
        "s": s.tolist(),
        "shooting": _curves(shoot, s),
        "collocation": {"x1": colloc.position(s)[:, 0].tolist(),
                        "x2": colloc.position(s)[:, 1].tolist()},
        "tip_rotation": shoot.tip_rotation,
        "tip_forces_only": {"x1": tip_shoot.position(s)[:, 0].tolist(),
                            "x2": tip_shoot.position(s)[:, 1].tolist(),
                            "x1_closed": x_closed[:, 0].tolist(),
                            "x2_closed": x_closed[:, 1].tolist(),
                            "tip_rotation": closed.tip_rotation,
                            "modulus_k": closed.k, "curve_error": tip_curve_err},
        "linear_limit": {"transverse_loads": {"P2": loads.P2, "q2": loads.q2},
                         "points": lin, "coefficient": c3 / c1, "order": order("rel_shooting")},
        "point": {"s": s0, "x": list(map(float, x0)), "theta": float(th0),
                  "curvature": curv0, "u": [float(x0[0] - s0), float(x0[1])],
                  **_frame(float(th0), curv0), "projections": proj,
                  "projections_collocation": proj_c, "length_from_positions": length_s},
        "cut": {"s": sc, "x": shoot.position(sc)[0].tolist(), "theta": th_c,
                **_frame(th_c, M_cut / B), "a": a_beyond.tolist(), "N": float(N_c),
                "T": float(T_c), "M": M_cut, "M_eq89": M_eq89,
                "eq89_along": {"s": s_cuts.tolist(), "M": M_cuts}},
        "part": {"s1": s1, "s2": s2, "s": s_part.tolist(),
                 "x": shoot.position(s_part).tolist(),
                 "ends": [{"s": si, "x": shoot.position(si)[0].tolist(),
                           "theta": float(shoot.theta(si)[0]),
                           "a": shoot.force(si)[0].tolist(),
                           "M": float(shoot.moment(si)[0])} for si in (s1, s2)],
                 "q": loads.distributed().tolist(), "balances": bal,
                 "balances_collocation": bal_c},
        "solver": {"shooting_newton_iterations": shoot.iterations,
                   "clamp_residual": shoot.clamp_residual},
        "quantities": q,
    }
