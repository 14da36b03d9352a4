"""Scenes of chapter §2.1–2.3: critical loads (eqs. 25, 46–48), Figs. 2–4 and errata evidence.

Every quoted quantity is stored as ``{"value": primary, "independent": second method,
"method": ..., "independent_method": ...}`` so that the check can report both.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from flutterfriction.analysis.stability import pencil_eigenvalues
from flutterfriction.analysis.ziegler import (
    dead_critical_loads,
    follower_critical_loads,
    linear_response,
    regime,
)
from flutterfriction.closed_forms import ziegler as cf
from flutterfriction.errors import ParameterError, check_positive, check_real
from flutterfriction.models.ziegler import ZieglerPendulum
from flutterfriction.scenes.common import n_points, pendulum_of, quantity, take

NUMERIC_FLUTTER = "coalescence of Omega^2 eigenvalues (Brent on the discriminant)"
NUMERIC_BUCKLING = "generalised eigenproblem K a = H diag(l1, l2) a"


def _spectrum_curve(pendulum: ZieglerPendulum, K1: np.ndarray, loads: np.ndarray) -> dict:
    """Dimensionless omega^2 = m2 l2^2 Omega^2 / k2 (eq. 17) along a load path."""
    mu = pencil_eigenvalues(pendulum.stiffness_matrix(), K1, pendulum.mass_matrix(), loads)
    omega2 = mu * pendulum.m2 * pendulum.l2**2 / pendulum.k2
    return {"omega2_re": omega2.real.T.tolist(), "omega2_im": omega2.imag.T.tolist()}


# ---------------------------------------------------------------------- eq. (25), dead load
def eq25(params: dict[str, Any]) -> dict[str, Any]:
    """Dead-load buckling loads and the omega^2 branches against eta = H l1/k2 (§2.2)."""
    take(params, {"pendulum", "n_points", "eta_max"})
    p = pendulum_of(params)
    g = p.groups()
    u = p.load_unit
    H_cr, H_sup = dead_critical_loads(p)
    e_cr, e_sup = cf.buckling_etas(g)
    eta_max = check_positive("eta_max", params.get("eta_max", 1.25 * e_sup))
    eta = np.linspace(0.0, eta_max, n_points(params))
    curve = _spectrum_curve(p, p.dead_load_matrix(), eta * u)
    closed = cf.omega2_dead_load(g, eta)
    quantities = {
        "eta_cr": quantity(H_cr / u, e_cr, NUMERIC_BUCKLING, "closed form eq. (22)", "K/L"),
        "eta_sup": quantity(H_sup / u, e_sup, NUMERIC_BUCKLING, "closed form eq. (22)", "K/L"),
        "H_cr": quantity(H_cr, e_cr * u, NUMERIC_BUCKLING, "closed form eq. (22)", "N"),
    }
    if g.equal_rods:  # eq. (25) is the equal rods' (an outside review: it FAILed another's)
        quantities["eta_cr_eq25"] = quantity(H_cr / u, cf.buckling_eta_equal_rods(),
                                             NUMERIC_BUCKLING,
                                             "closed form eq. (25), (3 - sqrt 5)/2", "K/L")
    return {
        "groups": vars(g),
        "quantities": quantities,
        "curve": {"eta": eta.tolist(), **curve,
                  "omega2_closed_form": closed.T.tolist()},
    }


# ---------------------------------------------------------------------- eqs. (46)–(48)
def follower_load_scene(params: dict[str, Any]) -> dict[str, Any]:
    """Flutter and divergence loads and the omega^2 branches against gamma = P l1/k2 (§2.3).

    The closed-form twin is eq. (39)/(41) in general and eq. (42) (with its divergence twin)
    when m3 = 0; eqs. (44)–(45) when eq. (43) also holds.
    """
    take(params, {"pendulum", "n_points", "gamma_max", "regime_checks"})
    p = pendulum_of(params)
    g = p.groups()
    u = p.load_unit
    P_flu, P_div = follower_critical_loads(p)
    g_flu, g_div = cf.flutter_divergence_gammas(g)
    method_cf = "closed form eqs. (39), (41)"
    if p.m3 == 0.0:
        g_flu, g_div = cf.two_mass_gammas(g.lam, g.y1, g.rho1, g.k)
        method_cf = "closed form eq. (42) and its divergence twin"
    quantities = {
        "gamma_flu": quantity(P_flu / u, g_flu, NUMERIC_FLUTTER, method_cf, "K/L"),
        "gamma_div": quantity(P_div / u, g_div, NUMERIC_FLUTTER, method_cf, "K/L"),
        "P_flu": quantity(P_flu, g_flu * u, NUMERIC_FLUTTER, method_cf, "N"),
        "P_div": quantity(P_div, g_div * u, NUMERIC_FLUTTER, method_cf, "N"),
    }
    for load in params.get("regime_checks", []):
        P = check_real("regime_checks", load)
        quantities[f"regime_at_{P:g}N"] = quantity(
            str(regime(p, P)), str(cf.follower_regime(g, P / u)),
            "eigenvalues of the first-order form", "eq. (37) intervals", "")
    gamma_max = check_positive("gamma_max", params.get("gamma_max", 1.25 * g_div))
    gamma = np.linspace(0.0, gamma_max, n_points(params))
    curve = _spectrum_curve(p, p.follower_load_matrix(), gamma * u)
    closed = cf.omega2_follower(g, gamma)
    return {
        "groups": vars(g),
        "load_unit_N": u,
        "quantities": quantities,
        "curve": {"gamma": gamma.tolist(), **curve,
                  "omega2_closed_form_re": closed.real.T.tolist(),
                  "omega2_closed_form_im": closed.imag.T.tolist()},
    }


# ---------------------------------------------------------------------- Fig. 3
def fig03(params: dict[str, Any]) -> dict[str, Any]:
    """The line beta1 - gamma beta2 and the parabola (beta1 - gamma beta2)^2 - 4ka (eq. 34)."""
    take(params, {"pendulum", "n_points", "gamma_max"})
    p = pendulum_of(params)
    g = p.groups()
    g_flu, g_div = cf.flutter_divergence_gammas(g)
    P_flu, P_div = follower_critical_loads(p)
    gamma_max = check_positive("gamma_max", params.get("gamma_max", 1.3 * g_div))
    gamma = np.linspace(0.0, gamma_max, n_points(params))
    line, parabola = cf.follower_line_and_parabola(g, gamma)
    b1, b2 = cf.coefficient_beta1(g), cf.coefficient_beta2(g)
    return {
        "groups": vars(g),
        "load_unit_N": p.load_unit,
        "coefficients": {"a": cf.coefficient_a(g), "beta1": b1, "beta2": b2},
        # Eq. (37) as printed (2 sqrt(k) a for 2 sqrt(k a)): drawn as the erratum's evidence.
        "gammas_as_printed": list(cf.flutter_divergence_gammas_as_printed(g)),
        "quantities": {
            "gamma_flu": quantity(g_flu, P_flu / p.load_unit, "closed form eq. (37)",
                                   NUMERIC_FLUTTER, "K/L"),
            "gamma_div": quantity(g_div, P_div / p.load_unit, "closed form eq. (37)",
                                   NUMERIC_FLUTTER, "K/L"),
            "gamma_vertex": quantity(b1 / b2, b1 / b2, "beta1/beta2", "beta1/beta2", "K/L"),
        },
        "curve": {"gamma": gamma.tolist(), "line": line.tolist(), "parabola": parabola.tolist()},
    }


# ---------------------------------------------------------------------- Fig. 2 and Fig. 4
def fig02(params: dict[str, Any]) -> dict[str, Any]:
    """Geometry of the schematic: the pendulum at the rotations to draw (degrees)."""
    take(params, {"pendulum", "alpha1_deg", "alpha2_deg"})
    p = pendulum_of(params)
    a1 = math.radians(check_real("alpha1_deg", params.get("alpha1_deg", 20.0)))
    a2 = math.radians(check_real("alpha2_deg", params.get("alpha2_deg", 45.0)))
    pos = p.positions(a1, a2)
    return {"alpha1": a1, "alpha2": a2,
            "masses": {"m1": p.m1, "m2": p.m2, "m3": p.m3},
            "points": {k: v.tolist() for k, v in pos.items()}}


def _case_response(p: ZieglerPendulum, name: str, P: float, x0: list[float],
                   times: NDArray) -> NDArray:
    """:func:`linear_response` of one Fig. 4 case, a refusal naming the case's load (an outside
    audit: P = 1e300 N was refused in the job as "times: the linear response overflows")."""
    try:
        return linear_response(p, P, 0.0, x0, times)
    except ParameterError as exc:
        raise ParameterError(f"cases.{name}.P = {P:g} N: {exc}") from None


def _fig04_inputs(params: dict[str, Any]
                  ) -> tuple[ZieglerPendulum, float, list[tuple[str, float, float, float]]]:
    """Fig. 4's pendulum, ``dt`` and cases ``(name, P, duration, alpha0)``, each checked."""
    take(params, {"pendulum", "cases", "dt"})
    p = pendulum_of(params)
    dt = check_positive("dt", params.get("dt", 0.04), "s")
    cases = params.get("cases")
    if not isinstance(cases, dict) or not cases:
        raise ParameterError("fig04 needs 'cases': {name: {P, duration, alpha0_deg}}")
    out = []
    for name, case in cases.items():
        take(case, {"P", "duration", "alpha0_deg"})
        out.append((name, check_real(f"cases.{name}.P", case["P"]),
                    check_positive(f"cases.{name}.duration", case["duration"], "s"),
                    math.radians(check_real(f"cases.{name}.alpha0_deg", case["alpha0_deg"]))))
    return p, dt, out


def check_fig04(params: dict[str, Any]) -> None:
    """Fig. 4's cases as :func:`fig04` refuses them, each case's response at its last frame
    (the configuration check; ~1 ms a case)."""
    p, dt, cases = _fig04_inputs(params)
    for name, P, T, a0 in cases:
        _case_response(p, name, P, [a0, a0, 0.0, 0.0], np.array([0.0, dt * round(T / dt)]))


def fig04(params: dict[str, Any]) -> dict[str, Any]:
    """Exact linear motion (eq. 11, matrix exponential) drawn every ``dt`` seconds."""
    p, dt, cases = _fig04_inputs(params)
    out: dict[str, Any] = {"masses": {"m1": p.m1, "m2": p.m2, "m3": p.m3}, "cases": {}}
    quantities = {}
    for name, P, T, a0 in cases:
        times = dt * np.arange(int(round(T / dt)) + 1)
        states = _case_response(p, name, P, [a0, a0, 0.0, 0.0], times)
        pos = p.positions(states[:, 0], states[:, 1])
        # The same exact solution every dt/20, for the figure's alpha(t) panel.
        t_dense = np.linspace(0.0, times[-1], 20 * (len(times) - 1) + 1)
        dense = linear_response(p, P, 0.0, [a0, a0, 0.0, 0.0], t_dense)
        out["cases"][name] = {"P": P, "times": times.tolist(), "alpha": states[:, :2].tolist(),
                              "points": {k: v.tolist() for k, v in pos.items()},
                              "t_dense": t_dense.tolist(), "alpha_dense": dense[:, :2].tolist()}
        quantities[f"regime_{name}"] = quantity(
            str(regime(p, P)), str(cf.follower_regime(p.groups(), P / p.load_unit)),
            "eigenvalues of the first-order form", "eq. (37) intervals", "")
    out["quantities"] = quantities
    return out


# ---------------------------------------------------------------------- errata evidence
def _mass_matrix_from_positions(p: ZieglerPendulum, printed_eq1: bool) -> np.ndarray:
    """M_ij = sum_m m (dx/dalpha_i . dx/dalpha_j) at alpha = 0, from eq. (1) by central
    differences (exact to O(step^2) since the kinematics is smooth)."""
    def points(a: np.ndarray) -> list[tuple[float, np.ndarray]]:
        pos = p.positions(a[0], a[1])
        D = pos["D"].copy()
        if printed_eq1:  # eq. (1) as printed: D - A = d cos(alpha1) e1 + d sin(alpha2) e2
            D = np.array([p.d * np.cos(a[0]), p.d * np.sin(a[1])])
        return [(p.m1, D), (p.m2, pos["C"]), (p.m3, pos["E"])]

    step = 1e-6
    jac = []
    for i in range(2):
        e = np.zeros(2)
        e[i] = step
        jac.append([(xp - xm) / (2 * step) for (_, xp), (_, xm) in
                    zip(points(e), points(-e), strict=True)])
    masses = [m for m, _ in points(np.zeros(2))]
    return np.array([[sum(m * jac[i][k] @ jac[j][k] for k, m in enumerate(masses))
                      for j in range(2)] for i in range(2)])


def _linearised_stiffness(p: ZieglerPendulum, P: float, H: float) -> np.ndarray:
    """-d(generalised force)/d(alpha) of eq. (10) at rest, by central differences."""
    step = 1e-6
    M = p.mass_matrix()
    cols = []
    for i in range(2):
        e = np.zeros(4)
        e[i] = step
        acc = (p.equations_of_motion(e, P, H)[2:] - p.equations_of_motion(-e, P, H)[2:])
        cols.append(-M @ acc / (2 * step))
    return np.array(cols).T


def errata(params: dict[str, Any]) -> dict[str, Any]:
    """Numbers that show each erratum of §2.1–2.3: printed form, corrected form, independent."""
    take(params, {"pendulum", "P", "H"})
    p = pendulum_of(params)
    P = check_real("P", params.get("P", 1.0))
    H = check_real("H", params.get("H", 1.0))
    g = p.groups()
    u = p.load_unit

    M_printed = _mass_matrix_from_positions(p, printed_eq1=True)
    M_corrected = _mass_matrix_from_positions(p, printed_eq1=False)
    M_eq11 = p.mass_matrix()

    KG_numeric = _linearised_stiffness(p, P, H)
    KG_printed_11 = p.k1 + p.k2 - p.l1 * (P - H)

    P_flu, P_div = follower_critical_loads(p)
    printed = cf.flutter_divergence_gammas_as_printed(g)
    corrected = cf.flutter_divergence_gammas(g)
    return {
        "groups": vars(g),
        "errata": {
            "eq1_D_position": {
                "quantity": "M22 [kg m^2] from the kinematics of eq. (1)",
                "printed": float(M_printed[1, 1]), "corrected": float(M_corrected[1, 1]),
                "independent": float(M_eq11[1, 1]),
                "independent_method": "mass matrix of eqs. (10)/(11) (also derived with sympy "
                                      "in tests/test_derivation.py)"},
            "eq11_geometric_11": {
                "quantity": f"(1,1) entry of K + G [N m] at P = {P:g} N, H = {H:g} N",
                "printed": KG_printed_11,
                "corrected": float((p.stiffness_matrix() + p.geometric_matrix(P, H))[0, 0]),
                "independent": float(KG_numeric[0, 0]),
                "independent_method": "central-difference linearisation of eq. (10)"},
            "eq39_flutter_sqrt_ka": {
                "quantity": "P_flu [N]",
                "printed": printed[0] * u, "corrected": corrected[0] * u,
                "independent": P_flu, "independent_method": NUMERIC_FLUTTER},
            "eq41_divergence_sqrt_ka": {
                "quantity": "P_div [N]",
                "printed": printed[1] * u, "corrected": corrected[1] * u,
                "independent": P_div, "independent_method": NUMERIC_FLUTTER},
        },
    }
