"""Figures of §2.7–2.8: Figs. 11 and 12, the FE work-precision study and the stability map."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from flutterfriction.plotting import (
    INTEGRATOR_COLOURS,
    MESH_STYLES,
    REGIME_COLOURS,
    list119,
    tidy_log_axis,
)


def _mode_of_branch(im: np.ndarray) -> np.ndarray:
    """For each branch (rows of ``im``), the mode it starts from at p = 0: 0 for the two
    branches of smallest |Im omega~| (the first mode and its conjugate), 1 for the next two."""
    rank = np.argsort(np.argsort(np.abs(im[:, 0]), kind="stable"), kind="stable")
    return rank // 2


def _critical_label(ax, value: float, sub: str, p: np.ndarray) -> None:
    """``p_sub = value`` above the frame at ``value``, ending at its line (starting at it when
    the line is near the left edge)."""
    ha = "left" if value < p[0] + 0.2 * (p[-1] - p[0]) else "right"
    ax.annotate(rf"$p_{sub}$ = {value:.2f}", (value, 1.0), xycoords=("data", "axes fraction"),
                xytext=(0, 2), textcoords="offset points", ha=ha, va="bottom", fontsize=7)


def _zoom_window(p: np.ndarray, re: np.ndarray, p_flu: float | None
                 ) -> tuple[np.ndarray, int] | None:
    """The loads around the damped flutter load that the inset shows, and the power of ten
    of the largest |Re omega~| there (the inset's unit); None without a flutter load in the
    drawn range (a user's own rod)."""
    if p_flu is None:
        return None
    half = 0.12 * (p[-1] - p[0])
    window = (p >= p_flu - half) & (p <= p_flu + half)
    top = np.abs(re.max(axis=0)[window])
    if not p[0] <= p_flu <= p[-1] or not np.any(top > 0):
        return None
    return window, int(np.floor(np.log10(top.max())))


#: The inset of :func:`_zoom_crossing` in its panel's axes fraction (x0, y0, width, height).
INSET_BOX = (0.18, 0.55, 0.21, 0.25)


def _zoom_crossing(ax, p: np.ndarray, re: np.ndarray, p_flu: float,
                   exp: int | None = None) -> None:
    """Inset of the largest Re omega~ around the damped flutter load: its sign change, which
    is invisible at the scale of the panel; in units of ``10^exp`` (default: its own)."""
    zoom = _zoom_window(p, re, p_flu)
    if zoom is None:
        return
    window, own = zoom
    exp = own if exp is None else exp
    top = re.max(axis=0)[window]
    ymax = np.abs(top).max()
    scale = 10.0 ** -exp
    # Above the branches (which sit near Re = 0 before the flutter load), axis labels on top.
    # (top at 0.8 of the panel: its "p [-]" on top clears the panel's frame and p_f label;
    # left edge at 0.18: its 7-pt axis label clear of the panel's ticks; right edge at 0.39,
    # left of where the branches leave Re = 0 in Figs. 11 and 12)
    ins = ax.inset_axes(INSET_BOX)
    ins.xaxis.tick_top()
    ins.xaxis.set_label_position("top")
    ins.plot(p[window], scale * top, color="k", lw=1.0)
    ins.axhline(0, color="0.4", lw=0.6)
    ins.axvline(p_flu, color="k", ls="--", lw=0.7)
    ins.plot(p_flu, 0.0, "o", color="C3", ms=3.5, zorder=5)
    ins.annotate(f"{p_flu:.2f}", (p_flu, 0.0), xytext=(-3, 3), textcoords="offset points",
                 ha="right", fontsize=7, color="C3")
    ins.set_xlim(p[window][0], p[window][-1])
    ins.set_ylim(-scale * ymax, scale * ymax)
    # 7 pt: at 6 pt the figure check's `small` rule failed (9.8 px with Fig. 12 1200 px wide)
    ins.tick_params(labelsize=7, pad=1)
    ins.xaxis.set_major_locator(plt.MaxNLocator(3))  # (4 labels nearly touched at 6 pt)
    ins.set_xlabel("p [-]", fontsize=7, labelpad=3)
    # "in 10^exp", not "x 10^exp" (a figure review: multiplied by, or in units of?)
    ins.set_ylabel(rf"max Re $\tilde\omega$" "\n" rf"in $10^{{{exp}}}$ [-]", fontsize=7,
                   labelpad=2)
    ins.set_facecolor("white")
    # The panel's own p_f line runs under the inset: the inset (zorder 5) covers it, and its
    # tick and axis labels, outside the inset's box, get a white ground so the line does not
    # strike through them.
    for text in (*ins.get_xticklabels(), *ins.get_yticklabels(), ins.xaxis.label,
                 ins.yaxis.label):
        text.set_bbox({"facecolor": "white", "edgecolor": "none", "pad": 0.6})


def _draw_branch_case(ax_re, ax_im, p: np.ndarray, case: dict[str, Any], title: str,
                      zoom: bool, zoom_exp: int | None = None) -> None:
    """One damping case: Re and Im of omega~ against p, regimes shaded, critical loads."""
    crit = case["critical"]
    re, im = np.array(case["re"]), np.array(case["im"])
    mode = _mode_of_branch(im)
    # the regimes in load order, from the loads that exist (a user's own rod may have no
    # flutter load, or none in the drawn range)
    marks = sorted((e, r) for e, r in ((crit["p_flu"], "flutter"), (crit["p_div"], "divergence"))
                   if e is not None and e < p[-1])
    names = ["stable", *[r for _, r in marks]]
    bounds = [p[0], *[e for e, _ in marks], p[-1]]
    for ax, values, ylabel in ((ax_re, re, r"Re $\tilde\omega$ [-]"),
                               (ax_im, im, r"Im $\tilde\omega$ [-]")):
        for lo, hi, reg in zip(bounds[:-1], bounds[1:], names, strict=False):
            ax.axvspan(lo, hi, color=REGIME_COLOURS[reg], alpha=0.7, lw=0, zorder=0)
        for branch, m in zip(values, mode, strict=True):
            ax.plot(p, branch, color=f"C{m}", lw=1.3)
        ax.axhline(0, color="k", lw=0.6)
        for e, sub in ((crit["p_flu"], "f"), (crit["p_div"], "d")):
            if e is not None and e < p[-1]:
                # under the inset (its own p_f line continues it) and not through the inset's
                # tick labels above it (a figure review saw "13.5" crossed), where the inset
                # is: elsewhere the whole height (a review saw it end in mid-air, Fig. 11)
                x = (e - p[0]) / (p[-1] - p[0])
                under = INSET_BOX[0] - 0.04 <= x <= INSET_BOX[0] + INSET_BOX[2] + 0.02
                top = (INSET_BOX[1] - 0.02 if zoom and ax is ax_re and sub == "f" and under
                       else 1.0)
                ax.axvline(e, ymax=top, color="k", ls="--", lw=0.8)
                if ax is ax_re:
                    _critical_label(ax, e, sub, p)
        ax.set_ylabel(ylabel)
        ax.set_xlim(p[0], p[-1])
    ax_re.set_title(title, fontsize=8, loc="left", pad=13)
    if zoom:
        _zoom_crossing(ax_re, p, re, crit["p_flu"], zoom_exp)


def _branch_legend(fig: Figure, n_modes: int, divergence: bool) -> None:
    """The figure's legend; divergence is named only where a panel shows it (not the Beck
    rod's Fig. 11)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    ordinal = ["1st", "2nd", "3rd", "4th"]
    handles = [Line2D([], [], color=f"C{m}", lw=1.3,
                      label=f"branches from the {ordinal[m]} mode at p = 0 (± Im)")
               for m in range(n_modes)]
    regimes = ("stable", "flutter", "divergence") if divergence else ("stable", "flutter")
    handles += [Patch(color=REGIME_COLOURS[r], alpha=0.7, label=r) for r in regimes]
    handles.append(Line2D([], [], color="k", ls="--", lw=0.8,
                          label=r"critical loads $p_f$ (flutter), $p_d$ (divergence)"
                          if divergence else r"critical load $p_f$ (flutter)"))
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=7, frameon=False)


def _shows_divergence(cases: Any, p: np.ndarray) -> bool:
    """Whether any case has a divergence load within the drawn range (as drawn above)."""
    return any(c["critical"]["p_div"] is not None and c["critical"]["p_div"] < p[-1]
               for c in cases)


def _damping_titles(data: dict[str, Any]) -> dict[str, str]:
    """The two rows' titles: the damped one says what the captions stress (internal damping,
    no external damping) and where eta comes from (D of the rod, eq. 106)."""
    rod = data.get("params", {}).get("rod")
    D = rod.get("D") if isinstance(rod, dict) else None
    gamma = data["cases"]["damped"]["groups"].get("gamma", 0.0)
    internal = (rf"internal damping $\eta = D/(l^2\sqrt{{\rho B}})$ = {data['eta']:.4g}"
                + (f" (D = {D:.4g} N m² s)" if D is not None else ""))
    external = ("no external damping" if not gamma
                else rf"external damping $\gamma$ = {gamma:.4g}")
    return {"undamped": "damping absent 'from the beginning'",
            "damped": f"{internal},\n{external} (inset: the sign change of "
                      r"Re $\tilde\omega$ at $p_f$)"}


def plot_branches(data: dict[str, Any], title: str) -> Figure:
    """Re and Im of omega~ against p; upper row without damping, lower row with (Figs. 11, 12)."""
    p = np.array(data["p"])
    fig, axes = plt.subplots(2, 2, figsize=(8.4, 6.4), sharex=True)
    titles = _damping_titles(data)
    for row, name in enumerate(("undamped", "damped")):
        _draw_branch_case(axes[row, 0], axes[row, 1], p, data["cases"][name], titles[name],
                          zoom=name == "damped")
    for ax in axes[1]:
        ax.set_xlabel(r"$p = P l^2 / B$ [-]")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    _branch_legend(fig, len(data["cases"]["undamped"]["re"]) // 2,
                   _shows_divergence(data["cases"].values(), p))
    return fig


def _rod_case_label(groups: dict[str, float]) -> str:
    """A rod by its groups (eq. 106), not by its name in the config: "Beck rod, η = 0.00136"."""
    ta = groups.get("tan_alpha", 0.0)
    parts = ["Beck rod" if ta == 0 else f"Pflüger rod, tan α = {ta:g}"]
    # (4 digits, as Figs. 11 and 12 print list 119's eta)
    parts += [f"{sym} = {groups[key]:.4g}" for key, sym in (("eta", "η"), ("gamma", "γ"))
              if groups.get(key)]
    return ", ".join(parts)


def plot_fe_convergence(data: dict[str, Any]) -> Figure:
    """Relative error of the FE flutter load against elements and against run time."""
    n = np.array(data["elements"], float)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8.4, 3.9), layout="constrained")
    for i, case in enumerate(data["cases"].values()):
        e = np.array(case["rel_error_p"])
        ew = np.array(case["rel_error_omega"])
        label = _rod_case_label(case["groups"])
        ax1.loglog(n, e, "o-", color=f"C{i}", ms=4,
                   label=rf"{label}: $p_{{flu}}$, rate {case['rate']:.2f}")
        ax1.loglog(n, ew, "s:", color=f"C{i}", ms=3, mfc="none",
                   label=rf"{label}: $\omega_{{flu}}$")
        ax2.loglog(case["time_s"], e, "o-", color=f"C{i}", ms=4)  # (the legend below)
    ref = n[n >= 4]
    c0 = np.array(next(iter(data["cases"].values()))["rel_error_p"])[list(n).index(ref[0])]
    ax1.loglog(ref, c0 * (ref[0] / ref) ** 4, "k--", lw=0.8, label=r"$h^4$")
    ax1.set_xticks(n, [str(int(v)) for v in n])
    ax1.minorticks_off()
    ax1.set_xlabel("number of Hermite elements [-]")
    ax1.set_ylabel("relative error vs exact eq. (118) [-]")
    # (the quick preset's few meshes: run times within a decade)
    tidy_log_axis(ax2.xaxis, [t for c in data["cases"].values() for t in c["time_s"]])
    ax2.set_xlabel("run time per critical-load solve [s] (median of ≤ 3 runs)")
    ax2.set_ylabel(r"relative error of $p_{flu}$ [-]")
    fig.suptitle("Finite elements (scikit-fem) against the exact characteristic function",
                 fontsize=9)
    # One legend for both panels, below them (inside, it covered curves that fill the panel's
    # diagonal; the right panel's curves are the solid p_flu ones): a column per case, its
    # p_flu above its pulsation, then h^4. The layout engine makes room for it (a fixed
    # margin fitted the paper run, not the quick preset's tick labels).
    fig.legend(*ax1.get_legend_handles_labels(), loc="outside lower center", fontsize=7,
               ncol=len(data["cases"]) + 1,
               title=f"rate: least-squares slope of the $p_{{flu}}$ error over "
                     f"{ref[0]:.0f}–{ref[-1]:.0f} elements", title_fontsize=7)
    return fig


def plot_stability_map(data: dict[str, Any]) -> Figure:
    """Flutter and divergence loads against the tip-mass ratio M/(rho l)."""
    r = np.array(data["mass_ratio"], float)
    fig, ax = plt.subplots(figsize=(6.0, 5.0), layout="constrained")
    for name, style, lw, label in (("undamped", "-", 2.6, "damping absent"),
                                   ("vanishing_damping", "--", 1.2,
                                    r"vanishing internal damping")):
        d = data[name]
        ax.plot(r, d["p_flu"], style, lw=lw, color="C0", label=f"flutter, {label}")
        div = np.array([np.nan if v is None else v for v in d["p_div"]], float)
        ax.plot(r, div, style, lw=lw, color="C3" if name == "undamped" else "k",
                label=f"divergence, {label}" + (" (the same)" if name != "undamped" else ""))
    ends = data["undamped"].get("p_div_end")
    p_top = 80.0  # the loads searched
    # The undamped regimes as areas, as in Figs. 11-12: stable below the flutter load, flutter
    # above it (unshaded, a figure review read the flutter region as stable), divergence over
    # it where it comes.
    flu = np.array([np.nan if v is None else v for v in data["undamped"]["p_flu"]], float)
    ax.fill_between(r, 0.0, np.where(np.isnan(flu), p_top, flu), color=REGIME_COLOURS["stable"],
                    lw=0, zorder=0, label="stable (damping absent)")
    ax.fill_between(r, flu, p_top, where=~np.isnan(flu), color=REGIME_COLOURS["flutter"], lw=0,
                    zorder=0, label="flutter (damping absent)")
    if ends is not None:
        div = np.array([np.nan if v is None else v for v in data["undamped"]["p_div"]], float)
        top = np.array([np.nan if v is None else v for v in ends], float)
        has = ~np.isnan(div)
        inside = ~np.isnan(top)
        ax.fill_between(r, div, np.where(inside, top, p_top), where=has,
                        color=REGIME_COLOURS["divergence"], lw=0, zorder=0.5,
                        label="divergence (damping absent)")
        if inside.any():
            ax.plot(r[inside], top[inside], "-", lw=1.0, color="C3",
                    label="end of the divergence window (grid points): flutter above")
        # Where divergence first appears (below p = 80): between two ratios of the map's grid.
        k = int(np.argmax(has))
        if k > 0:
            ax.annotate(f"divergence below p = {p_top:g}\nfirst for "
                        f"{r[k - 1]:.3g} < tan α < {r[k]:.3g}", (r[k], div[k]),
                        xytext=(0.12, 0.62), textcoords="axes fraction", fontsize=7,
                        arrowprops={"arrowstyle": "->", "lw": 0.7})
    # the whole searched range: cut at 65, the window's end was lost from sight where it
    # passes above 65 (an outside review could not tell whether it ends below 80)
    ax.set_ylim(0.0, p_top)
    ax.set_xscale("symlog", linthresh=0.01)
    ax.set_xlim(0, r[-1])
    ax.set_xlabel(r"tip-mass ratio $M/(\rho l) = \tan\alpha$ [-] (linear scale below "
                  r"$10^{-2}$, logarithmic above)")
    ax.set_ylabel(r"critical load $p = P l^2/B$ [-] (searched up to 80)")
    fig.legend(*ax.get_legend_handles_labels(), fontsize=7, loc="outside lower center",
               ncol=2)
    ax.set_title("Beck (ratio 0) to Pflüger rods: the paradox of vanishing damping", fontsize=9)
    return fig


def _tip(data):
    h = data["history"]
    return (np.array(h["t"]), np.array(h["u1"]) * 1000, np.array(h["u2"]) * 1000,
            np.array(h["u1_dot"]), np.array(h["u2_dot"]))


def _loop(data):
    c = data["cycle_loop"]
    return (np.array(c["u1"]) * 1000, np.array(c["u2"]) * 1000, np.array(c["u1_dot"]),
            np.array(c["u2_dot"]))


def _title(data, fig: str, what: str) -> str:
    """Figure number and content; the mesh and its measured error; the cycle's values."""
    c, tr = data["cycle"], data["transient"]
    n = data["history_mesh"]
    err = data["mesh_error"][str(n)]
    # the chapter's model is another one: said on the figure (a figure review)
    return (f"{fig}: nonlinear Beck rod, {list119(data)}, P = {data['P']:g} N: {what}\n"
            "ours: geometrically exact rod, P2 elements (the chapter's: ABAQUS, 20 linear B21 "
            "elements)\n"
            f"black: the limit cycle (Newton) on the transient's {n}-element mesh, within "
            f"{100 * max(err.values()):.2f}% of the {data['meshes'][-1]}-element cycle;\n"
            f"the cycle on {data['meshes'][-2]} elements: A = "
            f"{c['tip_amplitude_m'] * 1000:.1f} mm, T = {c['period_s'] * 1000:.2f} ms\n"
            f"the transient from the flutter mode, tip displacement "
            f"{tr['initial_amplitude_m'] * 1000:g} mm with the mode's velocity, ends "
            f"{100 * tr['final_distance']:.1f}% from it, at t = {tr['t_end']:.2f} s")


def _growth(ax, x, y, t, cx, cy):
    """The transient coloured by time, its start marked, the Newton cycle in black; returns
    the colour mapping (for the colour bar)."""
    from matplotlib.collections import LineCollection

    ax.plot([x[0]], [y[0]], "o", color="C3", ms=5, mec="w", zorder=5,
            label="start: straight rod + small flutter mode (its displacement and velocity)")
    pts = np.array([x, y]).T.reshape(-1, 1, 2)
    lc = LineCollection(np.concatenate([pts[:-1], pts[1:]], axis=1), cmap="viridis", lw=0.6,
                        norm=plt.Normalize(t[0], t[-1]))
    lc.set_array(t[:-1])
    ax.add_collection(lc)
    ax.plot([], [], color=plt.get_cmap("viridis")(0.5), lw=1.2,
            label="transient: flutter grows (colour: time)")
    ax.plot(cx, cy, color="k", lw=1.4,
            label="limit cycle (periodic-orbit Newton): on the transient's mesh")
    ax.autoscale()
    return lc


def _figure_legend(fig, ax):
    # one entry a row: three side by side were 2.5 in wider than the figure
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=1,
               fontsize=7, frameon=False)


def plot_fig15(data: dict[str, Any]) -> Figure:
    """Fig. 15: the tip's trajectory u2-u1 as flutter grows into the (flat) limit cycle."""
    t, u1, u2, _, _ = _tip(data)
    c1, c2, _, _ = _loop(data)
    fig, ax = plt.subplots(figsize=(7.0, 5.4), layout="constrained")
    lc = _growth(ax, u2, u1, t, c2, c1)
    fig.colorbar(lc, ax=ax, label="time t [s]")
    ax.set_xlabel(r"lateral tip displacement $u_2^{tip}$ [mm]")
    ax.set_ylabel(r"axial tip displacement $u_1^{tip}$ [mm]")
    # The loop is flat (the chapter: "hardly visible"), so the growth is shown in time too,
    # inside the arc where the trajectory never goes.
    ins = ax.inset_axes([0.32, 0.08, 0.36, 0.34])
    ins.plot(t, u2, color=plt.get_cmap("viridis")(0.5), lw=0.4)
    A = data["cycle"]["tip_amplitude_m"] * 1000
    ins.axhline(A, color="k", lw=0.8, ls="--")
    ins.axhline(-A, color="k", lw=0.8, ls="--")
    # 7 pt (5.5-6 pt read as 9 px with the figure 1200 px wide; a figure review)
    ins.set_xlabel("time t [s]", fontsize=7, labelpad=1)
    ins.set_ylabel(r"$u_2^{tip}$ [mm]", fontsize=7, labelpad=1)
    ins.tick_params(labelsize=7, pad=1)
    ins.xaxis.set_major_locator(plt.MaxNLocator(4))
    ins.set_title("growth, saturation (dashed: the cycle's amplitude)", fontsize=7, pad=2)
    # on white with its labels: its tick labels and title sat on the main grid's lines (an
    # outside review); the trajectory never enters this part of the axes
    ax.add_patch(Rectangle((0.24, 0.005), 0.45, 0.465, transform=ax.transAxes, fc="w",
                           ec="none", zorder=4))
    ins.set_zorder(5)
    _figure_legend(fig, ax)
    fig.suptitle(_title(data, "Fig. 15", "trajectory of the loaded end"), fontsize=8)
    return fig


def plot_fig16(data: dict[str, Any]) -> Figure:
    """Fig. 16: tip velocities against tip displacements."""
    t, u1, u2, v1, v2 = _tip(data)
    c1, c2, d1, d2 = _loop(data)
    fig, axes = plt.subplots(2, 1, figsize=(7.0, 8.0), layout="constrained")
    for ax, u, v, cu, cv, k, name in ((axes[0], u1, v1, c1, d1, 1, "axial"),
                                      (axes[1], u2, v2, c2, d2, 2, "lateral")):
        lc = _growth(ax, u, v, t, cu, cv)
        ax.set_xlabel(rf"{name} tip displacement $u_{k}^{{tip}}$ [mm]")
        ax.set_ylabel(rf"{name} tip velocity $\dot u_{k}^{{tip}}$ [m/s]")
    fig.colorbar(lc, ax=axes, label="time t [s]", shrink=0.6)
    _figure_legend(fig, axes[0])
    fig.suptitle(_title(data, "Fig. 16", "tip velocities against displacements"), fontsize=8)
    return fig


def plot_fig17(data: dict[str, Any]) -> Figure:
    """Fig. 17: lateral against axial tip velocity."""
    t, _, _, v1, v2 = _tip(data)
    _, _, d1, d2 = _loop(data)
    fig, ax = plt.subplots(figsize=(7.0, 5.4), layout="constrained")
    lc = _growth(ax, v1, v2, t, d1, d2)
    fig.colorbar(lc, ax=ax, label="time t [s]")
    ax.set_xlabel(r"axial tip velocity $\dot u_1^{tip}$ [m/s]")
    ax.set_ylabel(r"lateral tip velocity $\dot u_2^{tip}$ [m/s]")
    _figure_legend(fig, ax)
    fig.suptitle(_title(data, "Fig. 17", "lateral against axial tip velocity"), fontsize=8)
    return fig


def plot_beck_work_precision(data: dict[str, Any]) -> Figure:
    """Errors of the period and of the tip amplitude over one return to the Poincaré section,
    against wall time, for each integrator and mesh."""
    fig, axes = plt.subplots(1, 2, figsize=(9.5, 4.8), sharex=True, layout="constrained")
    meshes = sorted({r["mesh"] for r in data["runs"]})
    styles = dict(zip(meshes, MESH_STYLES, strict=False))
    colours = INTEGRATOR_COLOURS
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
        # the target inside the frame (on the frame's top edge it did not show)
        ax.set_ylim(top=max(ax.get_ylim()[1], 3e-3))
        tidy_log_axis(ax.xaxis, [r["wall_s"] for r in data["runs"] if not r["failed"]])
        ax.set_xlabel("wall time for one period [s] (one run each, shared machine)")
        ax.set_ylabel(f"relative error of the {label} [-]")
    handles, labels = axes[0].get_legend_handles_labels()
    # long handles: the mesh's line style (dashed: 8 elements) shows between the markers
    fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=7,
               handlelength=4.0)
    rtols = sorted({r["setting"] for r in data["runs"] if r["method"] != "generalized-alpha"},
                   reverse=True)
    dts = sorted({r["setting"] for r in data["runs"] if r["method"] == "generalized-alpha"},
                 reverse=True)
    P_N = (data.get("params") or {}).get("P_N", 5.5)  # (data without parameters: §2.9's)
    fig.suptitle(f"Nonlinear Beck rod, {list119(data)}, {P_N:g} N: one return to the Poincaré "
                 "section near the cycle (dotted: the 0.1% target)\nalong each line: LSODA, BDF, "
                 f"Radau at rtol {', '.join(f'{x:g}' for x in rtols)}; generalized-α "
                 f"(ρ∞ = 0.8, second order) at fixed steps "
                 f"{', '.join(f'{x * 1e3:g}' for x in dts)} ms", fontsize=8)
    return fig


def plot_beck_hopf(data: dict[str, Any]) -> Figure:
    """The rod's branch of limit cycles from the Hopf point, and its Floquet multipliers
    against the normal form."""
    A, P = 1e3 * np.array(data["A"]), np.array(data["P"])  # A in mm, as beck_branch
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.5, 3.9), layout="constrained")
    ax1.plot(P, A, "o-", ms=4, label="limit cycles (periodic-orbit continuation)")
    ax1.axvline(data["P_flu_exact"], color="k", ls=":", lw=1,
                label=f"damped flutter load, exact: {data['P_flu_exact']:.4f} N")
    dP = np.linspace(0, P.max() - data["P_flu_model"], 100)
    c = A[1] / np.sqrt(P[1] - data["P_flu_model"])
    ax1.plot(data["P_flu_model"] + dP, c * np.sqrt(dP), "C1--", lw=1,
             label=r"$A \propto \sqrt{P - P_{flu}}$")
    ax1.set_xlabel("follower load P [N]")
    ax1.set_ylabel("tip amplitude A [mm]\n(largest lateral displacement)")
    ax1.legend(fontsize=7)
    fl = sorted(data["floquet"].values(), key=lambda v: v["A"])
    ax2.plot([1e3 * v["A"] for v in fl], [v["slow_decay"] for v in fl], "o", ms=6,
             label=r"$1 - \mu$, slow Floquet multiplier (return map)")
    ax2.plot([1e3 * v["A"] for v in fl], [v["normal_form_decay"] for v in fl], "x", ms=8,
             label=r"normal form: $1 - e^{-2\sigma(P) T}$" "\n"
                   r"($\sigma$: growth rate of the linearised rod at P, $T$: the cycle's period)")
    ax2.set_yscale("log")
    ax2.set_xlabel("tip amplitude A [mm]")
    ax2.set_ylabel(r"$1 - \mu$: distance inside the unit circle [-]")
    ax2.legend(fontsize=7)
    fig.suptitle(f"Beck rod, {list119(data)}, {data['n_elements']} P2 elements: the Hopf "
                 "bifurcation at the damped flutter load is supercritical (stable cycles, "
                 "branch towards higher loads)", fontsize=9)
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
    ax.set_xlabel("P2 elements for the rotation [-]")
    ax.set_ylabel("relative error vs the exact theory [-]")
    ax.legend(fontsize=7)
    ax.set_title("The nonlinear rod model, linearised, converges to eq. (118)", fontsize=9)
    return fig


def plot_fig11(data: dict[str, Any]) -> Figure:
    return plot_branches(data, f"Fig. 11: the Beck rod, {list119(data)}")


def _one_rad_note(data: dict[str, Any]) -> str:
    """The caption's other reading, alpha = 1 rad, with its loads (computed by the scene)."""
    r = data.get("alpha_1_rad")
    if r is None:
        return ""
    u, d = r["undamped"], r["damped"]
    return (f"\n(α = 1 rad, tan α = {r['tan_alpha']:.4g}, gives the flutter loads "
            f"{u['p_flu']:.2f}, {d['p_flu']:.2f} but the divergence loads {u['p_div']:.2f}, "
            f"{d['p_div']:.2f}: see the errata table)")


def plot_fig12(data: dict[str, Any]) -> Figure:
    """Fig. 12 twice, side by side: at the caption's tan(alpha) = 1 (the figure as printed) and
    at the tan(alpha) that reproduces the quoted loads, with the erratum stated."""
    p = np.array(data["p"])
    fitted = data["cases"]
    t_fit = fitted["undamped"]["groups"]["tan_alpha"]
    if "stated" not in data:  # data from before the stated case was added
        return plot_branches(data, f"Fig. 12: the Pflüger rod, {list119(data)}, "
                                   f"tan α = {t_fit:.5g} (see errata)")
    stated = data["stated"]["cases"]
    t_st = data["stated"]["tan_alpha"]
    fig, axes = plt.subplots(4, 2, figsize=(9.6, 11.0), sharex="col")
    titles = _damping_titles(data)
    p_st = np.array(data["stated"].get("p", data["p"]))
    quoted = data.get("reproduces_quoted", True)
    # one unit for both columns' insets (each its own, 10^-2 beside 10^-3, read as the same
    # scale: a figure review)
    zooms = [_zoom_window(pc, np.array(c["damped"]["re"]), c["damped"]["critical"]["p_flu"])
             for c, pc in ((stated, p_st), (fitted, p))]
    exp = max((z[1] for z in zooms if z is not None), default=None)
    for col, (cases, pc, head) in enumerate((
            (stated, p_st, f"as the caption states: tan α = {t_st:g}" if t_st == 1.0
             else f"tan α = {t_st:g} (the caption states 1)"),
            (fitted, p, f"tan α = {t_fit:.5g}: reproduces the loads the chapter quotes"
             if quoted else f"tan α = {t_fit:.5g} (your choice: not the quoted loads)"))):
        axes[0, col].annotate(head, (0.5, 1.0), xycoords="axes fraction", xytext=(0, 26),
                              textcoords="offset points", ha="center", fontsize=9,
                              fontweight="bold")
        for k, name in enumerate(("undamped", "damped")):
            _draw_branch_case(axes[2 * k, col], axes[2 * k + 1, col], pc, cases[name],
                              titles[name].split(" (inset")[0], zoom=name == "damped",
                              zoom_exp=exp)
    for ax in axes[-1]:
        ax.set_xlabel(r"$p = P l^2 / B$ [-]")

    def loads(cases):
        u, d = cases["undamped"]["critical"], cases["damped"]["critical"]

        def f(v):
            return "none" if v is None else f"{v:.2f}"
        return f"{f(u['p_flu'])} / {f(u['p_div'])}, damped {f(d['p_flu'])} / {f(d['p_div'])}"
    fig.suptitle(f"Fig. 12: the Pflüger rod, {list119(data)}, tip mass tan α = M/(ρl); "
                 "flutter / divergence loads p\n"
                 + (f"Erratum: the caption's tan α = {t_st:g} gives {loads(stated)};\nthe loads "
                    f"the chapter quotes are those at tan α = {t_fit:.5g}: {loads(fitted)}"
                    + _one_rad_note(data) if quoted and t_st == 1.0 else
                    f"tan α = {t_st:g}: {loads(stated)}; tan α = {t_fit:.5g}: {loads(fitted)} "
                    "(the chapter quotes 16.51 / 30.22, damped 7.78 / 30.52; see the errata)"),
                 fontsize=8.5)
    fig.tight_layout(rect=(0, 0.04, 1, 0.98), h_pad=1.6)
    _branch_legend(fig, len(fitted["undamped"]["re"]) // 2,
                   _shows_divergence(stated.values(), p_st)
                   or _shows_divergence(fitted.values(), p))
    return fig
