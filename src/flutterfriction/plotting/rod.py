"""Figures of §2.7–2.8: Figs. 11 and 12, the FE work-precision study and the stability map."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from flutterfriction.plotting import REGIME_COLOURS


def plot_branches(data: dict[str, Any], title: str) -> Figure:
    """Re and Im of omega~ against p; upper row without damping, lower row with (Figs. 11, 12)."""
    p = np.array(data["p"])
    fig, axes = plt.subplots(2, 2, figsize=(8.4, 5.8), sharex=True)
    for row, (name, label) in enumerate((("undamped", "damping absent 'from the beginning'"),
                                         ("damped", rf"internal damping $\eta$ = "
                                                    rf"{data['eta']:.4g}"))):
        case = data["cases"][name]
        crit = case["critical"]
        for col, key in enumerate(("re", "im")):
            ax = axes[row, col]
            edges = [crit["p_flu"]] + ([crit["p_div"]] if crit["p_div"] else [])
            names = ["stable", "flutter", "divergence"][: len(edges) + 1]
            bounds = [p[0], *[e for e in edges if e < p[-1]], p[-1]]
            for lo, hi, reg in zip(bounds[:-1], bounds[1:], names, strict=False):
                ax.axvspan(lo, hi, color=REGIME_COLOURS[reg], alpha=0.7, lw=0, zorder=0)
            for i, branch in enumerate(np.array(case[key])):
                ax.plot(p, branch, color=f"C{i // 2}", lw=1.3)
            ax.axhline(0, color="k", lw=0.6)
            for e, sub in ((crit["p_flu"], "f"), (crit["p_div"], "d")):
                if e is not None and e < p[-1]:
                    ax.axvline(e, color="k", ls="--", lw=0.8)
                    if col == 0:
                        ax.annotate(rf"$p_{sub}$ = {e:.2f}", (e, 0.97), rotation=90, va="top",
                                    ha="right", xycoords=("data", "axes fraction"), fontsize=7)
            ax.set_ylabel(r"Re $\tilde\omega$" if key == "re" else r"Im $\tilde\omega$")
            if col == 0:
                ax.set_title(label, fontsize=8, loc="left")
            ax.set_xlim(p[0], p[-1])
    for ax in axes[1]:
        ax.set_xlabel(r"$p = P l^2 / B$")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


def plot_fe_convergence(data: dict[str, Any]) -> Figure:
    """Relative error of the FE flutter load against elements and against run time."""
    n = np.array(data["elements"], float)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8.4, 3.6))
    for i, (name, case) in enumerate(data["cases"].items()):
        e = np.array(case["rel_error_p"])
        ew = np.array(case["rel_error_omega"])
        ax1.loglog(n, e, "o-", color=f"C{i}", ms=4,
                   label=f"{name}: p_flu, rate {case['rate']:.2f}")
        ax1.loglog(n, ew, "s:", color=f"C{i}", ms=3, mfc="none",
                   label=rf"{name}: $\omega_{{flu}}$")
        ax2.loglog(case["time_s"], e, "o-", color=f"C{i}", ms=4, label=name)
    ref = n[n >= 4]
    c0 = np.array(next(iter(data["cases"].values()))["rel_error_p"])[list(n).index(ref[0])]
    ax1.loglog(ref, c0 * (ref[0] / ref) ** 4, "k--", lw=0.8, label=r"$h^4$")
    ax1.set_xticks(n, [str(int(v)) for v in n])
    ax1.minorticks_off()
    ax1.set_xlabel("number of Hermite elements")
    ax1.set_ylabel("relative error vs exact eq. (118)")
    ax1.legend(fontsize=6)
    ax2.set_xlabel("run time per critical-load solve [s] (median)")
    ax2.set_ylabel("relative error of p_flu")
    ax2.legend(fontsize=7)
    fig.suptitle("Finite elements (scikit-fem) against the exact characteristic function",
                 fontsize=9)
    fig.tight_layout()
    return fig


def plot_stability_map(data: dict[str, Any]) -> Figure:
    """Flutter and divergence loads against the tip-mass ratio M/(rho l)."""
    r = np.array(data["mass_ratio"], float)
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    for name, style, lw, label in (("undamped", "-", 2.6, "damping absent"),
                                   ("vanishing_damping", "--", 1.2,
                                    r"vanishing internal damping")):
        d = data[name]
        ax.plot(r, d["p_flu"], style, lw=lw, color="C0", label=f"flutter, {label}")
        div = np.array([np.nan if v is None else v for v in d["p_div"]], float)
        ax.plot(r, div, style, lw=lw, color="C3" if name == "undamped" else "k",
                label=f"divergence, {label}" + (" (the same)" if name != "undamped" else ""))
    ax.set_xscale("symlog", linthresh=0.01)
    ax.set_xlim(0, r[-1])
    ax.set_xlabel(r"tip-mass ratio $M/(\rho l) = \tan\alpha$")
    ax.set_ylabel(r"critical load $p = P l^2/B$ (searched up to 80)")
    ax.legend(fontsize=7)
    ax.set_title("Beck (ratio 0) to Pflüger rods: the paradox of vanishing damping", fontsize=9)
    return fig


def _tip(data):
    h = data["history"]
    return (np.array(h["t"]), np.array(h["u1"]) * 1000, np.array(h["u2"]) * 1000,
            np.array(h["u1_dot"]), np.array(h["u2_dot"]))


def _title(data, fig):
    c = data["cycle"]
    return (f"{fig}: nonlinear Beck rod, list (119), P = {data['P']:g} N ({data['history_mesh']}"
            f" elements): cycle amplitude {c['tip_amplitude_m'] * 1000:.1f} mm, period "
            f"{c['period_s'] * 1000:.2f} ms")


def plot_fig15(data: dict[str, Any]) -> Figure:
    """Fig. 15: the tip's trajectory u1-u2 reaching the (flat) limit cycle."""
    from flutterfriction.plotting.ziegler_nonlinear import _time_coloured

    t, u1, u2, _, _ = _tip(data)
    fig, ax = plt.subplots(figsize=(5.6, 4.0))
    lc = _time_coloured(ax, u2, u1, t, lw=0.6)
    fig.colorbar(lc, ax=ax, label="t [s]")
    ax.set_xlabel(r"$u_2^{tip}$ [mm] (lateral)")
    ax.set_ylabel(r"$u_1^{tip}$ [mm] (axial)")
    ax.set_title(_title(data, "Fig. 15"), fontsize=8)
    return fig


def plot_fig16(data: dict[str, Any]) -> Figure:
    """Fig. 16: tip velocities against tip displacements."""
    from flutterfriction.plotting.ziegler_nonlinear import _time_coloured

    t, u1, u2, v1, v2 = _tip(data)
    fig, axes = plt.subplots(2, 1, figsize=(5.2, 6.0))
    for ax, u, v, k in ((axes[0], u1, v1, 1), (axes[1], u2, v2, 2)):
        lc = _time_coloured(ax, u, v, t, lw=0.6)
        ax.set_xlabel(rf"$u_{k}^{{tip}}$ [mm]")
        ax.set_ylabel(rf"$\dot u_{k}^{{tip}}$ [m/s]")
    fig.colorbar(lc, ax=axes, label="t [s]")
    axes[0].set_title(_title(data, "Fig. 16"), fontsize=7)
    return fig


def plot_fig17(data: dict[str, Any]) -> Figure:
    """Fig. 17: lateral against axial tip velocity."""
    from flutterfriction.plotting.ziegler_nonlinear import _time_coloured

    t, _, _, v1, v2 = _tip(data)
    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    lc = _time_coloured(ax, v1, v2, t, lw=0.6)
    fig.colorbar(lc, ax=ax, label="t [s]")
    ax.set_xlabel(r"$\dot u_1^{tip}$ [m/s]")
    ax.set_ylabel(r"$\dot u_2^{tip}$ [m/s]")
    ax.set_title(_title(data, "Fig. 17"), fontsize=8)
    return fig


def plot_beck_work_precision(data: dict[str, Any]) -> Figure:
    """Errors of the period and of the tip amplitude over one return to the Poincaré section,
    against wall time, for each integrator and mesh."""
    from matplotlib.ticker import NullFormatter

    fig, axes = plt.subplots(1, 2, figsize=(9.5, 4.8), sharex=True, layout="constrained")
    styles = {4: "-", 8: "--", 16: ":"}
    colours = {"LSODA": "C0", "BDF": "C1", "Radau": "C2", "generalized-alpha": "C3"}
    keys = sorted({(r["method"], r["mesh"]) for r in data["runs"]})
    for ax, key, label in zip(axes, ("period_error", "amplitude_error"),
                              ("period", "tip amplitude"), strict=True):
        for method, mesh in keys:
            runs = sorted((r for r in data["runs"] if r["method"] == method
                           and r["mesh"] == mesh and not r["failed"]),
                          key=lambda r: r["wall_s"])
            if runs:
                ax.loglog([r["wall_s"] for r in runs],
                          [max(r[key], 1e-16) for r in runs], "o",
                          ls=styles.get(mesh, "-"), color=colours.get(method, "k"), ms=4,
                          label=f"{method}, {mesh} elements")
        ax.axhline(1e-3, color="0.5", lw=0.8, ls=":")
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("wall time for one period [s]")
        ax.set_ylabel(f"relative error of the {label}")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=7)
    fig.suptitle("Nonlinear Beck rod, list (119), 5.5 N: one return to the Poincaré section "
                 "near the cycle (adaptive tolerances; generalized-α: fixed steps; dotted: "
                 "the 0.1% target)", fontsize=8)
    return fig


def plot_beck_hopf(data: dict[str, Any]) -> Figure:
    """The rod's branch of limit cycles from the Hopf point, and its Floquet multipliers
    against the normal form."""
    A, P = np.array(data["A"]), np.array(data["P"])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.5, 3.9), layout="constrained")
    ax1.plot(P, A, "o-", ms=4, label="limit cycles (periodic-orbit continuation)")
    ax1.axvline(data["P_flu_exact"], color="k", ls=":", lw=1,
                label=f"damped flutter load, exact: {data['P_flu_exact']:.4f} N")
    dP = np.linspace(0, P.max() - data["P_flu_model"], 100)
    c = A[1] / np.sqrt(P[1] - data["P_flu_model"])
    ax1.plot(data["P_flu_model"] + dP, c * np.sqrt(dP), "C1--", lw=1,
             label=r"$A \propto \sqrt{P - P_{flu}}$")
    ax1.set_xlabel("follower load P [N]")
    ax1.set_ylabel("tip amplitude A [m]")
    ax1.legend(fontsize=7)
    fl = sorted(data["floquet"].values(), key=lambda v: v["A"])
    ax2.plot([v["A"] for v in fl], [v["slow_decay"] for v in fl], "o", ms=6,
             label=r"$1 - \mu$, slow Floquet multiplier (return map)")
    ax2.plot([v["A"] for v in fl], [v["normal_form_decay"] for v in fl], "x", ms=8,
             label=r"normal form: $1 - e^{-2\sigma(P) T}$")
    ax2.set_yscale("log")
    ax2.set_xlabel("tip amplitude A [m]")
    ax2.set_ylabel(r"$1 - \mu$: distance inside the unit circle [-]")
    ax2.legend(fontsize=7)
    fig.suptitle("Beck rod, list (119): the Hopf bifurcation at the damped flutter load is "
                 "supercritical (stable cycles, branch towards higher loads)", fontsize=9)
    return fig


def plot_beck_linearisation(data: dict[str, Any]) -> Figure:
    """Errors of the linearised nonlinear rod against the exact theory, per mesh."""
    n = np.array(data["meshes"], float)
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    labels = {"P_flu": "flutter load, undamped", "P_flu_damped": "flutter load, damped",
              "growth": f"growth rate at {data['P']:g} N",
              "frequency": f"frequency at {data['P']:g} N"}
    for key, label in labels.items():
        ax.loglog(n, data["errors"][key], "o-", ms=4,
                  label=f"{label} (last rate {data['rates'][key]:.2f})")
    ax.loglog(n, data["errors"]["growth"][1] * (n[1] / n) ** 4, "k:", lw=1, label=r"$h^4$")
    ax.set_xticks(n, [str(int(v)) for v in n])
    ax.minorticks_off()
    ax.set_xlabel("P2 elements for the rotation")
    ax.set_ylabel("relative error vs the exact theory")
    ax.legend(fontsize=7)
    ax.set_title("The nonlinear rod model, linearised, converges to eq. (118)", fontsize=9)
    return fig


def plot_fig11(data: dict[str, Any]) -> Figure:
    return plot_branches(data, "Fig. 11: the Beck rod, list (119)")


def plot_fig12(data: dict[str, Any]) -> Figure:
    tan_alpha = data["cases"]["undamped"]["groups"]["tan_alpha"]
    return plot_branches(data, f"Fig. 12: the Pflüger rod, list (119), tan α = {tan_alpha:.4g} "
                               "(see errata)")
