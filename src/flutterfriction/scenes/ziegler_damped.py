"""Scenes of chapter §2.2 (viscosity, dead load), §2.4 (the Ziegler paradox) and §2.10 (Fig. 19).

Damped flutter loads: exact Routh–Hurwitz on the characteristic polynomial (primary) and the
eigenvalue crossing (independent). Damped divergence loads: eigenvalue coalescence (primary)
and Routh/Sturm root counts with the resultant (independent). Closed forms: eq. (54) and its
generalisation :func:`~flutterfriction.closed_forms.ziegler_damped.damped_flutter_gamma`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.optimize import brentq

from flutterfriction.analysis.damped import state_spectra
from flutterfriction.analysis.ziegler import (
    damped_dead_load_onset,
    damped_divergence_load,
    damped_flutter_load,
    follower_critical_loads,
)
from flutterfriction.closed_forms import ziegler as cf
from flutterfriction.closed_forms import ziegler_damped as cfd
from flutterfriction.errors import ParameterError, check_positive, check_real
from flutterfriction.models.ziegler import ZieglerPendulum
from flutterfriction.scenes.common import n_points, pendulum_of, quantity, take

RH = "exact Routh-Hurwitz on the characteristic polynomial (bisection on the verdict)"
EIG_CROSS = "eigenvalues: Re s = 0 crossing (Brent)"
EIG_COAL = "eigenvalues: coalescence on the real axis (Brent on the discriminant)"
ALGEBRAIC = "Routh/Sturm root counts + resultant Res(p, p') (no eigenvalues)"


def with_viscosity(p: ZieglerPendulum, eps: float, c: float = 1.0) -> ZieglerPendulum:
    """The pendulum with ``epsilon = c2/(l2 sqrt(k2 m2))`` and ``c = c1/c2`` (eq. 29)."""
    c2 = eps / p.relative_viscosity(1.0)  # (l2 sqrt(k2 m2) itself can leave the doubles)
    return p.with_(c1=c * c2, c2=c2)


def _eps_list(params: dict[str, Any], key: str = "eps_values") -> list[float]:
    values = params.get(key)
    if not isinstance(values, list) or not values:
        raise ParameterError(f"{key} must be a non-empty list of numbers > 0")
    return [check_positive(key, v) for v in values]


def _check_viscosities(params: dict[str, Any], keys: tuple[str, ...]) -> None:
    """Each relative viscosity epsilon of ``keys`` (a list or one number) within the pendulum
    model's range (:meth:`ZieglerPendulum.check_numerical_range`), before any job: an outside
    audit's eps = 1e200 passed the configuration check and was refused in the job."""
    p0 = pendulum_of(params)
    for key in keys:
        values = params.get(key)
        if values is None:
            continue
        for eps in values if isinstance(values, list) else [values]:
            try:
                with_viscosity(p0, check_positive(key, eps)).check_numerical_range()
            except ParameterError as exc:
                raise ParameterError(f"{key}: {exc}") from None


def check_fig05(params: dict[str, Any]) -> None:
    """Fig. 5's viscosities as the pendulum model refuses them (the configuration check)."""
    _check_viscosities(params, ("eps_values",))


def check_paradox_limit(params: dict[str, Any]) -> None:
    """The paradox limit's viscosities as the model refuses them (the configuration check)."""
    _check_viscosities(params, ("eps_min", "eps_max"))


def check_damped_dead_load(params: dict[str, Any]) -> None:
    """The viscosities as the pendulum model refuses them (the configuration check)."""
    _check_viscosities(params, ("eps_values",))


# ---------------------------------------------------------------------- Fig. 5
def fig05(params: dict[str, Any]) -> dict[str, Any]:
    """Re and Im of omega~ against gamma, undamped and for each epsilon (eqs. 33, 51)."""
    take(params, {"pendulum", "eps_values", "gamma_max", "n_points"})
    _check_viscosities(params, ("eps_values",))
    p0 = pendulum_of(params)
    u = p0.load_unit
    T = p0.l2 * math.sqrt(p0.m2 / p0.k2)  # omega~ = s T (eq. 30)
    gamma = np.linspace(0.0, check_positive("gamma_max", params.get("gamma_max", 5.0)),
                        n_points(params))
    g_flu0, g_div0 = (x / u for x in follower_critical_loads(p0))
    quantities = {
        "gamma_flu_undamped": quantity(g_flu0, cf.flutter_divergence_gammas(p0.groups())[0],
                                        "eigenvalue coalescence", "closed form eq. (39)", "K/L")}
    cases = {}
    for eps in [0.0, *_eps_list(params)]:
        p = with_viscosity(p0, eps) if eps > 0 else p0
        s = state_spectra(p.mass_matrix(), p.viscosity_matrix(), p.stiffness_matrix(),
                           p.follower_load_matrix(), gamma * u) * T
        case: dict[str, Any] = {"eps": eps, "re": np.sort(s.real, axis=1).T.tolist(),
                                "im": np.sort(s.imag, axis=1).T.tolist()}
        if eps > 0:
            gf_rh = damped_flutter_load(p, "routh") / u
            gf_eig = damped_flutter_load(p, "eigenvalues") / u
            gd_eig = damped_divergence_load(p, "eigenvalues") / u
            gd_alg = damped_divergence_load(p, "algebraic") / u
            quantities[f"gamma_flu_eps{eps:g}"] = quantity(gf_rh, gf_eig, RH, EIG_CROSS, "K/L")
            if p0.groups().symmetric:  # eq. (54) is the symmetric pendulum's
                quantities[f"eq54_eps{eps:g}"] = quantity(
                    cfd.eq54_flutter_gamma(eps), gf_rh, "closed form eq. (54)", RH, "K/L")
            quantities[f"gamma_div_eps{eps:g}"] = quantity(gd_eig, gd_alg, EIG_COAL,
                                                            ALGEBRAIC, "K/L")
            case.update(gamma_flu=gf_rh, gamma_div=gd_eig)
        else:
            case.update(gamma_flu=g_flu0, gamma_div=g_div0)
        cases[f"{eps:g}"] = case
    # the caption's eps -> 0 limit (4/3 for eq. 51's pendulum; this pendulum's own with
    # c1 = c2): drawn beside the damped loads; its check is the paradox limit scene's
    return {"gamma": gamma.tolist(), "cases": cases, "symmetric": p0.groups().symmetric,
            "gamma_flu_limit": cfd.flutter_gamma_limit(p0, 1.0), "quantities": quantities}


# ---------------------------------------------------------------------- the paradox limit
def paradox_limit(params: dict[str, Any]) -> dict[str, Any]:
    """P*_flu against epsilon -> 0 (log axis): the jump from 2 K/L to 4/3 K/L (eq. 54)."""
    take(params, {"pendulum", "eps_min", "eps_max", "n_points"})
    _check_viscosities(params, ("eps_min", "eps_max"))
    p0 = pendulum_of(params)
    u = p0.load_unit
    g = p0.groups()
    eps_min = check_positive("eps_min", params.get("eps_min", 1e-4))
    eps_max = check_positive("eps_max", params.get("eps_max", 2.0))
    n = max(11, n_points(params) // 20)
    eps = np.geomspace(eps_min, eps_max, n)
    viscous = [with_viscosity(p0, e) for e in eps]
    numeric = np.array([damped_flutter_load(p, "routh") / u for p in viscous])
    # on the pendulums Routh-Hurwitz is given (eps rounded through c2), in doubles or, where
    # the closed form's terms cancel (a user's extreme pendulum), exactly
    closed = np.array([cfd.damped_flutter_gamma_of(p) for p in viscous])
    # eq. (54) is the symmetric pendulum's; another's is drawn with its own closed form only
    eq54 = np.array([cfd.eq54_flutter_gamma(e) for e in eps]) if g.symmetric else None
    g_flu0 = follower_critical_loads(p0)[0] / u
    limit = cfd.flutter_gamma_limit(p0, 1.0)
    return {
        "eps": eps.tolist(), "gamma_flu_routh": numeric.tolist(),
        "gamma_flu_closed_form": closed.tolist(), "symmetric": g.symmetric,
        "gamma_flu_eq54": None if eq54 is None else eq54.tolist(),
        "gamma_flu_undamped": g_flu0, "gamma_flu_limit": limit,
        "quantities": {
            "limit": quantity(limit, float(numeric[0]), "closed form, eps -> 0",
                               f"Routh-Hurwitz at eps = {eps_min:g}", "K/L"),
            "undamped": quantity(g_flu0, cf.flutter_divergence_gammas(g)[0],
                                  "eigenvalue coalescence", "closed form eq. (39)", "K/L"),
            "max_closed_vs_numeric": quantity(
                float(np.max(np.abs(closed / numeric - 1))), 0.0,
                "max relative difference, closed form vs Routh-Hurwitz over the curve",
                "zero", ""),
        },
    }


# ---------------------------------------------------------------------- Fig. 19 (theory)
class _Fig19:
    """Fig. 19's pendulum with c1 = c2 = c, its undamped loads, and the damped/undamped load
    ratios as functions of c; refused (:class:`ParameterError`) before any inference where a
    quoted ratio is out of reach in [c_min, c_max] (an outside audit's own pendulum ended in
    scipy's "f(a) and f(b) must have different signs")."""

    def __init__(self, params: dict[str, Any]) -> None:
        take(params, {"pendulum", "c_reference", "flutter_ratio", "divergence_ratio",
                       "c_min", "c_max", "n_points"})
        self.p0 = p0 = pendulum_of(params)
        self.c_ref = check_positive("c_reference", params["c_reference"], "N m s")
        self.r_flu = check_positive("flutter_ratio", params["flutter_ratio"])
        self.r_div = check_positive("divergence_ratio", params["divergence_ratio"])
        self.c_min = check_positive("c_min", params.get("c_min", 1e-5), "N m s")
        self.c_max = check_positive("c_max", params.get("c_max", 3e-2), "N m s")
        if not self.c_min < self.c_max:
            raise ParameterError(f"c_min must be < c_max = {self.c_max:g} N m s, "
                                 f"got {self.c_min:g}")
        self.P_flu0, self.P_div0 = follower_critical_loads(p0)
        for name, r, ratio in (("flutter_ratio", self.r_flu, self.flutter_ratio_closed),
                               ("divergence_ratio", self.r_div, self.divergence_ratio)):
            ends = sorted((ratio(self.c_min), ratio(self.c_max)))
            if not ends[0] < r < ends[1]:
                raise ParameterError(
                    f"{name} must lie in ({ends[0]:.6g}, {ends[1]:.6g}): the viscosity is "
                    f"inferred from it, and this pendulum's damped/undamped load ratio spans "
                    f"that interval for c1 = c2 = c in [c_min, c_max] = [{self.c_min:g}, "
                    f"{self.c_max:g}] N m s (the shipped 0.70 and 1.49 are the ratios measured "
                    f"on the chapter's device: give your own device's); got {r:g}")

    def hinge(self, c: float) -> ZieglerPendulum:
        return self.p0.with_(c1=c, c2=c)

    def flutter_ratio_closed(self, c: float) -> float:
        return cfd.damped_flutter_gamma_exact(self.hinge(c)) * self.p0.load_unit / self.P_flu0

    def divergence_ratio(self, c: float, method: str = "eigenvalues") -> float:
        return damped_divergence_load(self.hinge(c), method) / self.P_div0


def check_fig19_theory(params: dict[str, Any]) -> None:
    """Fig. 19's parameters as :func:`fig19_theory` refuses them (the configuration check)."""
    _Fig19(params)


def fig19_theory(params: dict[str, Any]) -> dict[str, Any]:
    """Flutter and divergence loads with and without hinge viscosity for list (47), c1 = c2 = c;
    the viscosity inferred from the quoted ratios 0.70 (flutter) and 1.49 (divergence)."""
    f = _Fig19(params)
    c_min, c_max, c_ref, r_flu, r_div = f.c_min, f.c_max, f.c_ref, f.r_flu, f.r_div
    P_flu0, P_div0 = f.P_flu0, f.P_div0
    hinge, flutter_ratio_closed, divergence_ratio = (f.hinge, f.flutter_ratio_closed,
                                                     f.divergence_ratio)

    n = max(11, n_points(params) // 20)
    cs = np.geomspace(c_min, c_max, n)
    curve_flu = [flutter_ratio_closed(c) for c in cs]
    curve_div = [divergence_ratio(c) for c in cs]
    # Inferred viscosities: the flutter ratio from the closed form (checked by Routh-Hurwitz),
    # the divergence ratio from the eigenvalues (checked algebraically).
    c_flu = brentq(lambda c: flutter_ratio_closed(c) - r_flu, c_min, c_max, xtol=1e-15)
    c_div = brentq(lambda c: divergence_ratio(c) - r_div, c_min, c_max, xtol=1e-12)
    c_div_alg = brentq(lambda c: divergence_ratio(c, "algebraic") - r_div, 0.5 * c_div,
                       2 * c_div, xtol=1e-12)
    ref = hinge(c_ref)
    P_flu_c = damped_flutter_load(ref, "routh")
    P_div_c = damped_divergence_load(ref, "eigenvalues")
    return {
        "c": cs.tolist(), "flutter_ratio": curve_flu, "divergence_ratio": curve_div,
        "c_reference": c_ref, "quoted_ratios": [r_flu, r_div],
        "bars": {"P_flu_undamped": P_flu0, "P_div_undamped": P_div0,
                 "P_flu_damped": P_flu_c, "P_div_damped": P_div_c},
        "quantities": {
            "flutter_ratio_at_c_ref": quantity(
                P_flu_c / P_flu0, flutter_ratio_closed(c_ref),
                RH, "closed form (generalised eq. 54)", ""),
            "divergence_ratio_at_c_ref": quantity(
                P_div_c / P_div0, divergence_ratio(c_ref, "algebraic"), EIG_COAL, ALGEBRAIC, ""),
            "c_from_flutter_ratio": quantity(
                c_flu, brentq(lambda c: damped_flutter_load(hinge(c), "routh") / P_flu0 - r_flu,
                              0.5 * c_flu, 2 * c_flu, xtol=1e-12),
                "closed form ratio = quoted ratio (Brent)",
                "Routh-Hurwitz ratio = quoted ratio (Brent)", "N m s"),
            "c_from_divergence_ratio": quantity(
                c_div, c_div_alg, "eigenvalue ratio = quoted ratio (Brent)",
                "algebraic ratio = quoted ratio (Brent)", "N m s"),
        },
    }


# ---------------------------------------------------------------------- paradox map
def _map_range(params: dict[str, Any], key: str, default: list[float], lo: float, hi: float,
               what: str) -> list[float]:
    """An increasing range ``[a, b]`` of ``params[key]`` within ``[lo, hi]``."""
    r = params.get(key, default)
    if not (isinstance(r, list) and len(r) == 2):
        raise ParameterError(f"{key} must be a list of two numbers [a, b], got {r!r}")
    a, b = (check_real(key, v) for v in r)
    if not lo <= a < b <= hi:
        raise ParameterError(f"{key} must be an increasing range within [{lo:g}, {hi:g}] "
                             f"({what}), got {r}")
    return [a, b]


def _paradox_map_ranges(params: dict[str, Any]) -> tuple[list[float], ...]:
    """The map's ranges, within the pendulum model's (an outside audit: log10_c_range up to
    200 wrote NaN into the data): the damping ratio c1/c2 and m1/m2 within the model's ratios
    10^+-RATIO_DECADES, d/l1 in (0, 1] (D on the rod AB)."""
    from flutterfriction.models.ziegler import RATIO_DECADES

    decades = f"the model's ratios 10^-{RATIO_DECADES} ... 10^{RATIO_DECADES}"
    lc = _map_range(params, "log10_c_range", [-2.0, 2.0], -RATIO_DECADES, RATIO_DECADES,
                    f"log10 of c1/c2, {decades}")
    lm = _map_range(params, "log10_mass_ratio_range", [-1.0, 1.0], -RATIO_DECADES,
                    RATIO_DECADES, f"log10 of m1/m2, {decades}")
    yd = _map_range(params, "d_ratio_range", [0.1, 1.0], 10.0**-RATIO_DECADES, 1.0,
                    "d/l1: D on the rod AB")
    return lc, lm, yd


def check_paradox_map(params: dict[str, Any]) -> None:
    """The map's ranges as :func:`paradox_map` refuses them (the configuration check)."""
    _paradox_map_ranges(params)


def paradox_map(params: dict[str, Any]) -> dict[str, Any]:
    """lim_{eps->0} P*_flu / P_flu(undamped) over the damping ratio c1/c2 and the mass
    distribution (m1/m2 with d = l1; d/l1 with m1 = m2), from the closed form, verified by
    Routh–Hurwitz at small epsilon at a few points."""
    take(params, {"pendulum", "log10_c_range", "log10_mass_ratio_range", "d_ratio_range",
                   "n_grid", "check_points", "eps_check"})
    p0 = pendulum_of(params)
    n = int(params.get("n_grid", 81))
    if n < 5:
        raise ParameterError(f"n_grid must be >= 5, got {n}")
    lc, lm, yd = (np.linspace(*r, n) for r in _paradox_map_ranges(params))

    def ratios(p: ZieglerPendulum, cs) -> list[float]:
        """The ratio at the damping ratios ``cs`` of one pendulum (its undamped load made once
        per row of the map, not at each of its 81 points: the scene 2.5 s -> 1.1 s, the same
        numbers)."""
        undamped = cf.flutter_divergence_gammas(p.groups())[0]
        return [cfd.flutter_gamma_limit(p, c) / undamped for c in cs]

    row = [10**c for c in lc]

    def pend_mass(log_m: float) -> ZieglerPendulum:
        return p0.with_(m1=p0.m2 * 10**log_m)

    def pend_d(y: float) -> ZieglerPendulum:
        return p0.with_(d=y * p0.l1)

    mass_map = [ratios(pend_mass(m), row) for m in lm]
    d_map = [ratios(pend_d(y), row) for y in yd]
    free_mass = [cfd.paradox_free_damping_ratio(pend_mass(m).groups()) for m in lm]
    free_d = [cfd.paradox_free_damping_ratio(pend_d(y).groups()) for y in yd]
    eps = check_positive("eps_check", params.get("eps_check", 1e-4))
    quantities = {}
    for i, pt in enumerate(params.get("check_points", [])):
        take(pt, {"c_ratio", "m1_over_m2", "d_over_l1"})
        p = p0.with_(m1=p0.m2 * pt["m1_over_m2"], d=pt["d_over_l1"] * p0.l1)
        pd = with_viscosity(p, eps, pt["c_ratio"])
        numeric = damped_flutter_load(pd, "routh") / follower_critical_loads(p)[0]
        quantities[f"check_{i}"] = quantity(
            ratios(p, [pt["c_ratio"]])[0], numeric, "closed form, eps -> 0",
            f"Routh-Hurwitz at eps = {eps:g} over eigenvalue coalescence", "")
    return {"log10_c": lc.tolist(), "log10_mass_ratio": lm.tolist(), "d_ratio": yd.tolist(),
            "check_points": params.get("check_points", []),
            "ratio_mass": mass_map, "ratio_d": d_map,
            "paradox_free_c_mass": free_mass, "paradox_free_c_d": free_d,
            "quantities": quantities}


# ---------------------------------------------------------------------- dead load + viscosity
def damped_dead_load(params: dict[str, Any]) -> dict[str, Any]:
    """§2.2 after eq. (31): viscosity leaves the dead-load critical load at H_cr (eq. 22)."""
    take(params, {"pendulum", "eps_values"})
    _check_viscosities(params, ("eps_values",))
    p0 = pendulum_of(params)
    u = p0.load_unit
    e_cr = cf.buckling_etas(p0.groups())[0]
    quantities = {}
    for eps in _eps_list(params):
        p = with_viscosity(p0, eps)
        quantities[f"eta_cr_eps{eps:g}"] = quantity(
            damped_dead_load_onset(p, "routh") / u, damped_dead_load_onset(p, "eigenvalues") / u,
            RH, EIG_CROSS, "K/L")
        quantities[f"eta_cr_eps{eps:g}_vs_eq22"] = quantity(
            damped_dead_load_onset(p, "routh") / u, e_cr, RH, "closed form eq. (22), undamped",
            "K/L")
    return {"quantities": quantities}


# ---------------------------------------------------------------------- errata of eq. (31)
def _eq31(params: dict[str, Any]) -> tuple:
    """The pendulum, its viscosity groups, the dead load ``H`` (a real number; a refusal of
    the coefficients names it: an outside audit's H = 1e300 N was refused in the job as "eq.
    (30) coefficients: beyond the double range") and eq. (31)'s printed and derived
    coefficients."""
    p, eps, c, H, eta = _eq31_inputs(params)
    g = p.groups()
    try:
        printed = cfd.coefficients_as_printed_eq31(g, eps, c, eta)
        derived = cfd.characteristic_coefficients(g, eps, c, eta=eta)
    except ParameterError as exc:
        raise ParameterError(f"H = {H:g} N: {exc}") from None
    return p, eps, c, H, eta, g, printed, derived


#: Largest |eta| = |H| l1/k2 of eq. (31): its coefficients are quadratic in eta (the groups
#: within 1e6 of each other keep them in range; 1e160 overflowed, 1e150 did not, measured).
ETA_MAX = 1e150


def _eq31_inputs(params: dict[str, Any]) -> tuple:
    """The pendulum, its viscosity groups, ``H`` and ``eta = H l1/k2``, each checked."""
    take(params, {"pendulum", "H", "eq52_eps", "eq52_gamma"})
    p = pendulum_of(params)
    eps, c = cfd.viscosity_groups(p)
    H = check_real("H", params.get("H", 1.0))
    eta = H * p.l1 / p.k2
    if not abs(eta) <= ETA_MAX:
        raise ParameterError(f"H = {H:g} N: eta = H l1/k2 = {eta:.3g} must be within "
                             f"+-{ETA_MAX:g} (eq. 31's coefficients are quadratic in it)")
    return p, eps, c, H, eta


def check_errata_damped(params: dict[str, Any]) -> None:
    """eq. (31)'s inputs as :func:`errata_damped` refuses them (the configuration check;
    without forming the coefficients, whose symbolic derivation takes ~0.5 s)."""
    _eq31_inputs(params)


def errata_damped(params: dict[str, Any]) -> dict[str, Any]:
    """Eq. (31) as printed vs derived (sympy) vs the coefficients of det(M s^2 + C s + K + G)
    expanded numerically from the matrices; eq. (52) vs the derivation."""
    from flutterfriction.analysis.polynomial import characteristic_polynomial

    p, eps, c, H, eta, g, printed, derived = _eq31(params)
    # det(M s^2 + C s + K + G) = k2^2 det(M^ w^2 + C^ w + K^ + G^) with w = s T.
    T = p.l2 * math.sqrt(p.m2 / p.k2)
    si = characteristic_polynomial(p.mass_matrix(), p.viscosity_matrix(),
                                   p.stiffness_matrix() + p.geometric_matrix(0.0, H))
    numeric = si / (p.k2**2 * T ** np.arange(4, -1, -1))
    errata = {}
    for i in range(3):
        errata[f"eq31_p{i}"] = {
            "quantity": f"p{i} of eq. (31), list (47) with c1 = c2 = {p.c2:g} N m s, "
                        f"H = {H:g} N",
            "printed": float(printed[i]), "corrected": float(derived[i]),
            "independent": float(numeric[i]),
            "independent_method": "coefficients of det(M s^2 + C s + K + G) from the matrices"}
    e52, g52 = float(params.get("eq52_eps", 0.1)), float(params.get("eq52_gamma", 1.2))
    sym = ZieglerPendulum(l1=1.0, l2=1.0, d=1.0, h=0.0, m1=1.0, m2=1.0, m3=0.0, k1=1.0, k2=1.0,
                          c1=e52, c2=e52)
    num52 = characteristic_polynomial(sym.mass_matrix(), sym.viscosity_matrix(),
                                      sym.stiffness_matrix() + sym.geometric_matrix(g52))
    der52 = cfd.characteristic_coefficients(sym.groups(), e52, 1.0, gamma=g52)
    quantities = {
        f"eq52_p{i}": quantity(float(der52[i]), float(num52[i]), "sympy derivation",
                                "coefficients from the matrices", "")
        for i in range(5)}
    return {"errata": errata, "quantities": quantities,
            "eq52_printed": cfd.eq52_coefficients(e52, g52).tolist(),
            "eq31_terms_check": {"printed": printed.tolist(), "derived": derived.tolist(),
                                 "numeric": numeric.tolist()}}
