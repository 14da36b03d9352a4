"""Beyond the chapter: the Beck rod's whole branch of limit cycles (list 119, Kelvin–Voigt,
follower load), from the damped flutter load (the Hopf point) through the 5.5 N cycle of
Figs. 15–17 to ``P_max``, with every cycle's Floquet multipliers.

The continuation is :func:`flutterfriction.analysis.rod_cycles.cycle_branch` with a load stop
(``P_max``): periodic-orbit Newton with the exact Jacobian of the variational equations, a
quadratic predictor, steps from the predictor's measured error, rejected steps logged with
their reason, and the loads of ``land_at`` (the chapter's 5.5 N) landed on exactly.
Deterministic: every loop is bounded by counts, never by the clock.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.integrate import cumulative_trapezoid

from flutterfriction.analysis.rod_orbit import check_orbit_rtol, integrate_orbit
from flutterfriction.errors import ConvergenceError, ParameterError, check_positive
from flutterfriction.models.rod import Rod
from flutterfriction.scenes.common import quantity, take

ALLOWED = {"rod", "n_elements", "A_first", "A_scale", "P_max", "P_cycle", "rtol", "newton_tol",
           "parametrisation", "error_target", "ds_first", "ds_max", "max_points",
           "check_elements", "check_loads", "check_extremes", "check_rtol", "check_tol",
           "chord"}


def _rod(params: dict[str, Any]) -> Rod:
    r = params.get("rod")
    if not isinstance(r, dict):
        raise ParameterError("scene parameters need a 'rod' section (length, B, rho, D, ...)")
    take(r, {"length", "B", "rho", "D", "kappa", "tip_mass"})
    return Rod(**r)


def cycle_shapes(model, y, T: float, P: float, n_times: int = 12, n_s: int = 41,
                 rtol: float = 1e-9) -> list:
    """The rod's centre line at ``n_times`` instants of one period of the cycle through the
    section state ``y``: ``[[x_0..x_{n_s-1}], [y_0..]]`` per instant [m] (rounded to 10 um)."""
    sol = integrate_orbit(model, y, T, P, rtol, rtol * 1e-3, dense_output=True)
    if not sol.success:
        raise ConvergenceError(f"the cycle's orbit at P = {P:g} N failed: {sol.message}")
    s = np.linspace(0.0, model.rod.length, 8 * (n_s - 1) + 1)
    out = []
    for t in np.linspace(0.0, T, n_times, endpoint=False):
        theta = model.nodal_values_at(sol.sol(t)[: model.n_dof], s)
        x = cumulative_trapezoid(np.cos(theta), s, initial=0.0)[::8]
        z = cumulative_trapezoid(np.sin(theta), s, initial=0.0)[::8]
        out.append([np.round(x, 5).tolist(), np.round(z, 5).tolist()])
    return out


def _branch_settings(params: dict[str, Any]) -> tuple[Rod, int, float, float, float, float]:
    """The rod, elements, ``P_max``, ``P_cycle``, ``A_scale`` and the damped flutter load of
    the linearised rod where the branch starts (as cycle_branch computes it: a few small
    eigenproblems), refused before the branch is computed: ``P_max`` not above the flutter
    load, a check load or ``P_cycle`` off the branch (an outside audit: ``P_cycle`` beyond
    ``P_max`` was skipped silently, a check load beyond it failed after the branch)."""
    from flutterfriction.analysis.rod_cycles import linearised_flutter_load

    take(params, ALLOWED)
    rod = _rod(params)
    n_el = int(params.get("n_elements", 4))
    P_max = check_positive("P_max", params.get("P_max", 7.0), "N")
    P_cycle = check_positive("P_cycle", params.get("P_cycle", 5.5), "N")
    A_scale = check_positive("A_scale", params.get("A_scale", 0.3), "m")
    for name, default in (("rtol", 1e-9), ("check_rtol", 1e-10)):
        check_orbit_rtol(name, params.get(name, default))
    P_flu = linearised_flutter_load(rod, n_el)
    if not P_max > P_flu:
        raise ParameterError(f"P_max = {P_max} N must be above the damped flutter load "
                             f"{P_flu:.4f} N, where the branch starts")
    if not P_flu < P_cycle <= P_max:
        raise ParameterError(f"P_cycle must be in ({P_flu:.4f}, {P_max:g}] N, on the branch "
                             f"(the chapter's cycle is landed on there), got {P_cycle:g}")
    for L in [float(x) for x in params.get("check_loads", [])]:
        if not P_flu < L <= P_max:
            raise ParameterError(f"check_loads: {L:g} N is outside the branch "
                                 f"({P_flu:.4f}, {P_max:g}] N")
    return rod, n_el, P_max, P_cycle, A_scale, P_flu


def check_beck_branch(params: dict[str, Any]) -> None:
    """The branch's parameters as :func:`beck_branch` refuses them (the configuration
    check)."""
    _branch_settings(params)


def beck_branch(params: dict[str, Any]) -> dict[str, Any]:
    """The branch of limit cycles from the Hopf point to ``P_max`` on ``n_elements`` P2
    elements (the cycle at ``P_cycle``, the chapter's 5.5 N, landed on exactly), checked:
    (a) the cycle at ``P_cycle`` re-solved at tight tolerances (rtol 1e-10, Newton 1e-9) from
    the branch's point; (b) the onset against the normal form ``A ~ sqrt(P - P_flu)``;
    (c) the cycles at ``check_loads`` on ``check_elements`` elements (the mesh error);
    (d) folds and stability: the sign of dP along the branch, and the largest non-trivial
    Floquet modulus."""
    from flutterfriction.analysis.rod_cycles import (
        PeriodicOrbitNewton,
        cycle_branch,
        cycle_on_finer_mesh,
    )
    from flutterfriction.models.rod_nonlinear import NonlinearRod

    rod, n_el, P_max, P_cycle, A_scale, P_flu = _branch_settings(params)
    rtol = float(params.get("rtol", 1e-9))
    land = (P_cycle,) if P_cycle < P_max else ()
    b = cycle_branch(rod, n_elements=n_el, A_first=float(params.get("A_first", 0.01)),
                     A_max=A_scale, rtol=rtol, max_points=int(params.get("max_points", 80)),
                     P_max=P_max, land_at=land,
                     parametrisation=str(params.get("parametrisation", "arclength")),
                     newton_tol=float(params.get("newton_tol", 1e-5)),
                     ds_first=float(params.get("ds_first", 0.05)),
                     ds_max=float(params.get("ds_max", 0.3)),
                     error_target=float(params.get("error_target", 5e-3)),
                     chord=bool(params.get("chord", True)))
    if b.stopped_by != "P_max":
        raise ConvergenceError(f"beck_branch: the branch stopped at P = {b.P[-1]:.4f} N "
                               f"({b.stopped_by}) before P_max; see the log: "
                               + "; ".join(b.log[-3:]))
    P, A, T = np.array(b.P), np.array(b.A), np.array(b.T)
    model = NonlinearRod(rod, n_el)
    states = np.array(b.states)

    # (a) the cycle at P_cycle, re-solved at tight tolerances from the landed point.
    k_cycle = next((k for k in b.landed if abs(P[k] - P_cycle) <= 1e-9 * P_cycle), None)
    cycle_check = None
    if k_cycle is not None:
        tight = PeriodicOrbitNewton(model, A_scale, b.P_flu, rtol=1e-10, tol=1e-9)
        y = states[k_cycle, :-2]
        cycle_check = tight.solve(y, T[k_cycle], P_cycle, (0.0, 1.0), P_cycle / b.P_flu)

    # (b) onset: log-log slope of A against P - P_flu over the first four cycles.
    dP = P - b.P_flu
    slope = float(np.polyfit(np.log(dP[:4]), np.log(A[:4]), 1)[0])

    # A few cycle shapes: the amplitude's first maximum and the following minimum (the
    # non-monotone stretch; both also mesh-checked below), the chapter's cycle and the last.
    picks = {}
    inner = [k for k in range(1, len(A) - 1) if A[k - 1] < A[k] > A[k + 1]]
    if inner:
        picks["amplitude maximum"] = inner[0]
        after = [k for k in range(inner[0] + 1, len(A) - 1) if A[k - 1] > A[k] < A[k + 1]]
        if after:
            picks["amplitude minimum"] = after[0]
    if k_cycle is not None:
        picks["chapter's cycle (Figs. 15-17)"] = k_cycle

    # (c) a finer mesh at a few loads (each landed on the branch or interpolated onto it), and
    # at the amplitude's first maximum and the following minimum: the dip between them (a
    # third of the amplitude on 4 elements) is the model's, not the mesh's, only if the finer
    # mesh has it too (measured: 112.2 and 77.2 mm on 8 elements, 112.2 and 77.2 on 16).
    # ``check_extremes: false`` leaves them out (the quick preset's 2-element branch has its
    # maximum where no 3-element cycle is near enough for Newton).
    fine = NonlinearRod(rod, int(params.get("check_elements", 2 * n_el)))
    checks = []
    check_extremes = params.get("check_extremes", True)
    if not isinstance(check_extremes, bool):
        raise ParameterError(f"check_extremes must be true or false, got {check_extremes!r}")
    extremes = {k: label for label, k in picks.items()
                if label.startswith("amplitude") and check_extremes}
    targets = sorted([(float(x), "check load") for x in params.get("check_loads", [])]
                     + [(float(P[k]), label) for k, label in extremes.items()])
    for L, kind in targets:
        k = int(np.argmin(np.abs(P - L)))
        if abs(P[k] - L) > 1e-9 * L:  # not landed on: a Newton solve at L from the nearest
            pt = PeriodicOrbitNewton(model, A_scale, b.P_flu, rtol=rtol, tol=1e-7).solve(
                states[k, :-2], T[k], L, (0.0, 1.0), L / b.P_flu)
            y_c, T_c, A_c = pt.y, pt.T, pt.A
        else:
            y_c, T_c, A_c = states[k, :-2], T[k], A[k]
        f = cycle_on_finer_mesh(model, y_c, T_c, L, fine,
                                rtol=float(params.get("check_rtol", 1e-10)),
                                tol=float(params.get("check_tol", 1e-7)))
        checks.append({"P_N": L, "kind": kind,
                       "coarse": {"tip_amplitude_m": float(A_c), "period_s": T_c},
                       "fine": {"tip_amplitude_m": f.A, "period_s": f.T,
                                "tip_rotation_amplitude_rad": f.tip_rotation_amplitude,
                                "iterations": f.newton_iterations},
                       "amplitude_rel_diff": float(abs(A_c - f.A) / f.A),
                       "period_rel_diff": float(abs(T_c - f.T) / f.T)})

    # (d) folds and stability in the load range [3, P_max] N (and over the whole branch).
    in_range = P >= min(3.0, P_max)
    dPs = np.diff(P)
    no_fold = bool(np.all(dPs > 0))
    mu = np.array(b.max_floquet_modulus)
    stable = bool(np.all(mu < 1.0))

    if len(A) - 1 not in picks.values():  # (the quick preset's branch ends at its 5.5 N cycle)
        picks["last"] = len(A) - 1
    shapes = [{"label": label, "index": k, "P_N": float(P[k]),
               "tip_amplitude_m": float(A[k]), "period_s": float(T[k]),
               "shapes": cycle_shapes(model, states[k, :-2], T[k], P[k])}
              for label, k in picks.items()]

    data = {
        "n_elements": b.n_elements, "P_flu_model": b.P_flu, "omega_flu": b.omega_flu,
        "P_N": P.tolist(), "tip_amplitude_m": A.tolist(), "period_s": T.tolist(),
        "tip_rotation_amplitude_rad": list(b.tip_rotation_amplitude),
        "max_floquet_modulus": mu.tolist(), "slow_decay": list(b.slow_decay),
        "landed": list(b.landed), "cycle_index": k_cycle, "P_cycle": P_cycle,
        "cycle_check": None if cycle_check is None else {
            "tip_amplitude_m": cycle_check.A, "period_s": cycle_check.T,
            "newton_iterations": cycle_check.newton_iterations},
        "onset_exponent": slope, "no_fold": no_fold, "stable": stable,
        "settings": {"rtol": rtol, "newton_tol": float(params.get("newton_tol", 1e-5)),
                     "check_elements": int(fine.n_elements)},
        "max_floquet_modulus_in_range": float(mu[in_range].max()) if in_range.any() else None,
        "min_dP": float(dPs.min()), "mesh_checks": checks, "shapes": shapes,
        "continuation": {"integrations": b.integrations,
                         "orbit_integrations": b.orbit_integrations,
                         "rejected_steps": b.rejected_steps,
                         "newton_iterations": b.newton_iterations,
                         "first_correction": b.first_correction, "log": b.log,
                         "stopped_by": b.stopped_by},
    }
    data["growth_rates"] = growth_rates(rod, P_cycle)
    data["quantities"] = branch_quantities(data)
    return data


#: Loads of :func:`growth_rates`, as multiples of the damped flutter load (plus ``P_cycle``).
GROWTH_RATE_FACTORS = (1.05, 1.1, 1.2, 1.5)


def growth_rates(rod: Rod, P_cycle: float) -> list[dict[str, float]]:
    """The flutter mode's linear growth rate and frequency [1/s, rad/s] on the exact theory
    (eq. 118, Kelvin–Voigt) at :data:`GROWTH_RATE_FACTORS` times the damped flutter load
    ``P_d`` and at ``P_cycle``: why the branch starts from a Newton solve and not a
    transient (near ``P_d`` the relaxation time ``1/(2 sigma)`` is minutes; the notebook
    shows the table, from here, not from a second computation)."""
    from flutterfriction.analysis import rod as ar

    P_d = float(ar.critical_loads(rod.groups()).p_flu * rod.load_unit)
    rows = []
    for f in (*GROWTH_RATE_FACTORS, P_cycle / P_d):
        s = ar.fastest_mode(rod, f * P_d)
        rows.append({"P_N": f * P_d, "load_ratio": f, "growth_rate": float(s.real),
                     "frequency": float(abs(s.imag))})
    return rows


def branch_quantities(data: dict[str, Any]) -> dict[str, Any]:
    """The checked quantities of a ``beck_branch`` result (see :func:`beck_branch`)."""
    P, A, T = (np.array(data[k]) for k in ("P_N", "tip_amplitude_m", "period_s"))
    n_el, st = data["n_elements"], data["settings"]
    k = data["cycle_index"]
    q = {}
    if k is not None and data["cycle_check"] is not None:
        method = (f"branch, {n_el} P2 elements (rtol {st['rtol']:g}, Newton tol "
                  f"{st['newton_tol']:g}), landed at {P[k]:g} N")
        tight = f"Newton re-solve from that cycle, rtol 1e-10, tol 1e-9 ({n_el} elements)"
        c = data["cycle_check"]
        q["cycle_tip_amplitude"] = quantity(float(A[k]), c["tip_amplitude_m"], method, tight,
                                            "m")
        q["cycle_period"] = quantity(float(T[k]), c["period_s"], method, tight, "s")
    q["onset_exponent"] = quantity(data["onset_exponent"], 0.5,
                                   "log-log slope of A against P - P_flu (first four cycles "
                                   f"of the branch, A = {A[0]:.3g}-{A[3]:.3g} m)",
                                   "supercritical normal form", "")
    q["onset_load"] = quantity(float(P[0]), data["P_flu_model"],
                               f"load of the branch's first cycle, A = {A[0]:.3g} m",
                               "damped flutter load of the same mesh (Hopf point)", "N")
    checks = data["mesh_checks"]
    if checks:
        diffs = [max(c["amplitude_rel_diff"], c["period_rel_diff"]) for c in checks]
        loads = ", ".join(f"{c['P_N']:g}" for c in checks)
        q["mesh_error"] = quantity(
            float(max(diffs)), 0.0,
            f"largest relative difference of tip amplitude and period, {n_el} against "
            f"{st['check_elements']} P2 elements, at {loads} N",
            "zero (converged mesh)", "")
    q["fold_and_stability"] = quantity(
        "no fold" if data["no_fold"] else "fold",
        "stable cycles" if data["stable"] else "unstable cycles",
        f"P increases at every step of the branch ({len(P)} cycles, {P[0]:.3f}-{P[-1]:g} N; "
        f"smallest step {data['min_dP']:.2g} N)",
        "largest non-trivial Floquet modulus < 1 at every cycle "
        f"(largest {max(data['max_floquet_modulus']):.6f})", "")
    return q
