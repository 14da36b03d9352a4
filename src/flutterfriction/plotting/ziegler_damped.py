"""Figures of §2.4 and §2.10: Fig. 5, the paradox limit, Fig. 19 (theory) and the paradox map."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import Normalize
from matplotlib.figure import Figure

from flutterfriction.plotting import chapter_list, list47, own_parameters_note, pendulum_case
from flutterfriction.plotting.labels import declutter, label_at

COLOURS = ["black", "C0", "C3", "C2", "C1"]


def plot_fig05(data: dict[str, Any]) -> Figure:
    """Fig. 5: Re and Im of omega~ against gamma, undamped and for each epsilon (eq. 51).

    A third panel zooms on the largest Re omega~ around the damped flutter loads, where it is
    too small to see at the scale of the upper panel: it changes sign at the flutter load.
    """
    gamma = np.array(data["gamma"])
    fig = plt.figure(figsize=(5.4, 7.4))
    outer = fig.add_gridspec(2, 1, height_ratios=[6, 2.3], hspace=0.36, top=0.85)
    gs = outer[0].subgridspec(2, 1, hspace=0.08)
    ax_re = fig.add_subplot(gs[0])
    ax_im = fig.add_subplot(gs[1], sharex=ax_re)
    ax_z = fig.add_subplot(outer[1])
    damped = [c for c in data["cases"].values() if c["eps"] > 0]
    limit = data.get("gamma_flu_limit")  # the caption's eps -> 0 limit (4/3 K/L at eq. 51)
    ends = [c["gamma_flu"] for c in damped] + ([limit] if limit is not None else [])
    lo, hi = min(ends) - 0.08, max(ends) + 0.08
    window = (gamma >= lo) & (gamma <= hi)
    damped_top = [np.max(np.array(c["re"]), axis=0)[window] for c in damped]
    ztop = max(np.abs(t).max() for t in damped_top)
    zexp = int(np.floor(np.log10(0.25 * ztop)))  # the zoom's values in units of 10**zexp
    zs = 10.0 ** -zexp
    for colour, case in zip(COLOURS, data["cases"].values(), strict=False):
        name = "undamped" if case["eps"] == 0 else rf"$\epsilon$ = {case['eps']:g}"
        label = rf"{name}: $\gamma_{{flu}}$ = {case['gamma_flu']:.3f}"
        # the undamped branches thinner and on top: the damped ones run under them where
        # the viscosity barely moves them (a review saw the black ones hidden for gamma < 1.8)
        lw, z = (0.9, 3) if case["eps"] == 0 else (1.3, 2)
        for i, branch in enumerate(case["re"]):
            ax_re.plot(gamma, branch, color=colour, lw=lw, zorder=z,
                       label=label if i == 0 else None)
        for branch in case["im"]:
            ax_im.plot(gamma, branch, color=colour, lw=lw, zorder=z)
        for ax in (ax_re, ax_im):
            ax.axvline(case["gamma_flu"], color=colour, ls="--", lw=0.8)
        top = np.max(np.array(case["re"]), axis=0)
        ax_z.plot(gamma[window], zs * top[window], color=colour, lw=1.3)
        if case["eps"] > 0:
            ax_z.axvline(case["gamma_flu"], color=colour, ls="--", lw=0.8)
            ax_z.plot(case["gamma_flu"], 0.0, "o", color=colour, ms=4)
            ax_z.annotate(f"{case['gamma_flu']:.3f}", (case["gamma_flu"], 0.0),
                          xytext=(4, -12), textcoords="offset points", fontsize=7,
                          color=colour)
    if limit is not None:
        text = "4/3" if data.get("symmetric", True) else f"{limit:.4g}"
        label = rf"$\epsilon \to 0$: $\gamma_{{flu}}$ = {text} (the Ziegler paradox; zoom)"
        # in the zoom only: in the upper panels it lies < 1 px from eps = 0.1's dashed line
        # at 1.338 and could not be seen (an outside review); the legend names it there
        ax_z.axvline(limit, color="0.35", ls=":", lw=1.1)
        ax_re.plot([], [], color="0.35", ls=":", lw=1.1, label=label)
        ax_z.annotate(rf"$\epsilon \to 0$: {text}", (limit, 0.0), xytext=(-4, 12),
                      textcoords="offset points", ha="right", fontsize=7, color="0.25")
    ax_re.axhline(0, color="k", lw=0.6)
    ax_z.axhline(0, color="k", lw=0.6)
    ax_re.set_ylabel(r"Re $\tilde\omega$ [-]")
    ax_im.set_ylabel(r"Im $\tilde\omega$ [-]")
    ax_im.set_xlabel(r"$\gamma = P L/K$ [-]")
    ax_im.set_xlim(gamma[0], gamma[-1])
    ax_re.tick_params(labelbottom=False)
    # above the panels: inside, it covered the damped flutter loads' dashed lines
    ax_re.legend(loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=2, fontsize=7,
                 frameon=False, columnspacing=1.2, handlelength=1.8)
    # the assumptions of eq. (50) in full (rho2 = 0: no mass at C) and epsilon of eq. (29)
    symmetric = data.get("symmetric", True)
    which = (r"$l_1=l_2=L$, $k_1=k_2=K$, $m_1=m_2$, $m_3=0$, $d=L$, $c_1=c_2$ (eq. 51)"
             if symmetric else chapter_list(data, "pendulum", "list47", "the pendulum of list (47)",
                                          short=True)
             + r", $c_1=c_2$; $L = l_1$, $K = k_2$")
    ax_re.set_title(f"Fig. 5: {which}\n"
                    r"$\epsilon = c_2/(l_2\sqrt{k_2 m_2})$ (eq. 29); dashed: flutter loads",
                    fontsize=8, pad=30)
    if not symmetric:
        fig.text(0.5, 0.005, own_parameters_note(data, "pendulum", "list47", width=80),
                 ha="center", va="top", fontsize=7)
    ax_z.set_xlim(lo, hi)
    ax_z.set_ylim(-0.25 * ztop * zs, 0.25 * ztop * zs)
    ax_z.set_xlabel(r"$\gamma = P L/K$ [-]")
    ax_z.set_ylabel(rf"largest Re $\tilde\omega$ in $10^{{{zexp}}}$ [-]")
    undamped = next(c["gamma_flu"] for c in data["cases"].values() if c["eps"] == 0)
    ax_z.set_title(r"zoom: the largest Re $\tilde\omega$ changes sign at the damped flutter "
                   f"loads (dots)\nundamped: 0 until {undamped:.4g}"
                   + ("; dotted: the limit $\\epsilon \\to 0$" if limit is not None else ""),
                   fontsize=8)
    return fig


def plot_paradox_limit(data: dict[str, Any]) -> Figure:
    """The damped flutter load against epsilon on a log axis: the Ziegler paradox."""
    eps = np.array(data["eps"])
    fig, ax = plt.subplots(figsize=(5.4, 3.6), layout="constrained")
    ax.semilogx(eps, data["gamma_flu_routh"], "o", ms=3.5, mfc="none", color="C0",
                label="Routh–Hurwitz (exact verdict) on the matrices")
    symmetric = data.get("symmetric", True)
    if symmetric:
        ax.semilogx(eps, data["gamma_flu_eq54"], color="C3", lw=1.2,
                    label=r"eq. (54): $4/3 + \epsilon^2/2$")
    else:  # eq. (54) is the symmetric pendulum's: this pendulum's own closed form
        ax.semilogx(eps, data["gamma_flu_closed_form"], color="C3", lw=1.2,
                    label="closed form (eq. 54 for this pendulum)")
    ax.axhline(data["gamma_flu_undamped"], color="k", ls="--", lw=1.0,
               label=f"undamped (eq. 46): {data['gamma_flu_undamped']:.4g} K/L")
    ax.axhline(data["gamma_flu_limit"], color="0.4", ls=":", lw=1.0,
               label=rf"$\epsilon \to 0$: {data['gamma_flu_limit']:.4f} K/L")
    ax.annotate("", (eps[0] * 1.5, data["gamma_flu_limit"]),
                (eps[0] * 1.5, data["gamma_flu_undamped"]),
                arrowprops={"arrowstyle": "<->", "color": "C3"})
    ax.annotate("the Ziegler paradox:\nthe limit is not the\nundamped value",
                (eps[0] * 2.2, 0.5 * (data["gamma_flu_limit"] + data["gamma_flu_undamped"])),
                va="center", fontsize=8, color="C3")
    ax.set_xlabel(r"viscosity $\epsilon = c_2/(l_2\sqrt{k_2 m_2})$ [-]")
    ax.set_ylabel(r"flutter load $P_{flu}\,L/K$ [-]")
    values = [*data["gamma_flu_routh"], data["gamma_flu_undamped"], data["gamma_flu_limit"]]
    span = max(values) - min(values)
    ax.set_ylim(min(values) - 0.15 * span, max(values) + 0.15 * span)
    # under the axes: at the upper right it hid eq. (54)'s curve (a figure review)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2, fontsize=7)
    ax.set_title("Flutter load with vanishing hinge viscosity ("
                 + ("symmetric pendulum" if symmetric else list47(data, short=True)) + ")")
    note = own_parameters_note(data, "pendulum", "list47", width=90) if not symmetric else ""
    if note:
        fig.text(0.5, -0.02, note, ha="center", va="top", fontsize=7)
    return fig


def plot_fig19_theory(data: dict[str, Any]) -> Figure:
    """Fig. 19, theory: the critical loads with and without viscosity, and how the quoted ratios
    (0.70, 1.49) fix the hinge viscosity."""
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8.4, 3.6),
                                   gridspec_kw={"width_ratios": [1, 1.35]})
    b = data["bars"]
    x = np.arange(2)
    w = 0.36
    ax1.bar(x - w / 2, [b["P_flu_undamped"], b["P_div_undamped"]], w, color="0.6",
            label="viscosity absent")
    ax1.bar(x + w / 2, [b["P_flu_damped"], b["P_div_damped"]], w, color="C0",
            label=f"$c_1=c_2$ = {data['c_reference']:g} N m s")
    for xi, (u, d) in enumerate([(b["P_flu_undamped"], b["P_flu_damped"]),
                                 (b["P_div_undamped"], b["P_div_damped"])]):
        ax1.annotate(f"{u:.2f}", (xi - w / 2, u), ha="center", va="bottom", fontsize=7)
        ax1.annotate(f"{d:.2f}\n(×{d / u:.3f})", (xi + w / 2, d), ha="center", va="bottom",
                     fontsize=7)
    ax1.set_xticks(x, ["flutter", "divergence"])
    ax1.set_xlabel("instability")
    ax1.set_ylabel("critical follower load P [N]")
    ax1.set_ylim(0, 1.25 * max(b.values()))
    ax1.legend(loc="upper left", fontsize=7)
    ax1.set_title(f"{list47(data, 'List (47)', short=True)}: theoretical "
                  "bars of Fig. 19", fontsize=8)
    c = np.array(data["c"])
    ax2.semilogx(c, data["flutter_ratio"], color="C0", label="flutter ratio")
    ax2.semilogx(c, data["divergence_ratio"], color="C3", label="divergence ratio")
    q = data["quantities"]
    for ratio, key, colour in ((data["quoted_ratios"][0], "c_from_flutter_ratio", "C0"),
                               (data["quoted_ratios"][1], "c_from_divergence_ratio", "C3")):
        ax2.axhline(ratio, color=colour, ls=":", lw=0.8)
        ax2.plot(q[key]["value"], ratio, "o", color=colour, ms=5)
        # beside its point, moved clear of the others where one's own pendulum puts the
        # point elsewhere (c near c_max ran into the title; an outside audit's own case)
        # below ratio 1, low: 8 pt up put the ratio-1 line across its first line's tops
        label_at(ax2, f"quoted {ratio:.2f}\n→ c = {q[key]['value'] * 1e3:.2f}e-3 N m s",
                 (q[key]["value"], ratio), (-118, 3 if ratio < 1 else 8), points=True,
                 fontsize=7, color=colour)
    ax2.axvline(data["c_reference"], color="k", ls="--", lw=0.8)
    ax2.annotate(f"§2.9: {data['c_reference']:g} N m s", (data["c_reference"], 0.97),
                 xytext=(-2, 0), textcoords="offset points",  # (2 pt clear of its line)
                 rotation=90, xycoords=("data", "axes fraction"), ha="right", va="top",
                 fontsize=7)
    ax2.axhline(1.0, color="k", lw=0.6, label="ratio 1 (no viscosity effect)")
    ax2.set_xlabel(r"hinge viscosity $c_1 = c_2$ [N m s]")
    ax2.set_ylabel("damped / undamped critical load [-]")
    ax2.legend(loc="upper left", fontsize=7)
    ax2.set_title("Ratios against viscosity", fontsize=8)
    declutter(ax2)
    fig.suptitle("Fig. 19, theory only: the experimental spots of the printed figure are "
                 "measurements, not reproduced;\nits horizontal theory bars are drawn here as "
                 "columns (the model's loads do not depend on the plate's speed, 50 mm/s in "
                 "the experiment)", fontsize=8)
    note = own_parameters_note(data, "pendulum", "list47", width=170)
    fig.tight_layout(rect=(0, 0.05 if note else 0, 1, 1))
    if note:
        fig.text(0.5, 0.005, note, ha="center", va="bottom", fontsize=7.5)
    return fig


def _far_from(cs, level: float, curve: np.ndarray, xlim: tuple, ylim: tuple
              ) -> list[tuple[float, float]]:
    """For each line of ``cs`` at ``level``, its vertex farthest from the polyline ``curve``
    (distances in axes fractions), kept off the frame's outer 10 %: where its label goes."""
    span = np.array([xlim[1] - xlim[0], ylim[1] - ylim[0]], dtype=float)
    origin = np.array([xlim[0], ylim[0]], dtype=float)
    ref = (curve - origin) / span
    out = []
    for line in cs.allsegs[list(cs.levels).index(level)]:
        v = (np.asarray(line) - origin) / span
        inner = np.all((v > 0.1) & (v < 0.9), axis=1)
        if not inner.any():
            continue
        d = np.min(np.linalg.norm(v[:, None, :] - ref[None, :, :], axis=-1), axis=1)
        k = int(np.argmax(np.where(inner, d, -np.inf)))
        out.append(tuple(np.asarray(line)[k]))
    return out


def plot_paradox_map(data: dict[str, Any]) -> Figure:
    """Vanishing-viscosity flutter load over the undamped one, against c1/c2 and the masses."""
    lc = np.array(data["log10_c"])
    fig, axes = plt.subplots(1, 2, figsize=(8.6, 3.8), sharex=True)
    panels = ((axes[0], np.array(data["log10_mass_ratio"]), data["ratio_mass"],
               data["paradox_free_c_mass"], r"$\log_{10}(m_1/m_2)$ [-]   ($d = l_1$)"),
              (axes[1], np.array(data["d_ratio"]), data["ratio_d"], data["paradox_free_c_d"],
               r"$d/l_1$ [-]   ($m_1 = m_2$)"))
    norm = Normalize(vmin=0.0, vmax=1.0)
    for ax, y, z, free, ylabel in panels:
        im = ax.pcolormesh(lc, y, np.array(z), cmap="viridis", norm=norm, shading="auto")
        # white on the dark (low) levels, black on the light ones: white labels on the yellow
        # were unreadable (a figure review)
        cs = ax.contour(lc, y, np.array(z), levels=[0.25, 0.5, 0.75, 0.9, 0.99],
                        colors=["w", "w", "k", "k", "k"], linewidths=0.6)
        pts = [(np.log10(c), yy) for c, yy in zip(free, y, strict=True) if c is not None]
        if pts:
            # 0.99 runs beside the no-paradox curve (ratio 1): its labels where its lines
            # are farthest from that curve (matplotlib put one on it; a figure review)
            ax.clabel(cs, levels=[0.25, 0.5, 0.75, 0.9], fontsize=7, fmt="%.2f")
            ax.clabel(cs, levels=[0.99], fontsize=7, fmt="%.2f",
                      manual=_far_from(cs, 0.99, np.array(pts), (lc[0], lc[-1]), (y[0], y[-1])))
        else:
            ax.clabel(cs, fontsize=7, fmt="%.2f")
        if pts:
            # Every point, clipped at the frame (the curve runs on beyond it).
            px, py = np.array(pts).T
            ax.plot(px, py, color="C3", lw=1.8, label="no paradox (closed form)")
            ax.legend(loc="lower left", fontsize=7)
        else:
            ax.text(0.03, 0.03, "no c1/c2 removes the paradox\nanywhere on this panel "
                    "(closed form)", transform=ax.transAxes, fontsize=7, color="w",
                    va="bottom")
        ax.set_xlim(lc[0], lc[-1])
        ax.set_ylim(y[0], y[-1])
        on_panel = [pt for pt in data["check_points"]
                    if (ax is axes[0] and pt["d_over_l1"] == 1.0)
                    or (ax is axes[1] and pt["m1_over_m2"] == 1.0)]
        for pt in on_panel:
            yy = np.log10(pt["m1_over_m2"]) if ax is axes[0] else pt["d_over_l1"]
            ax.plot(np.log10(pt["c_ratio"]), yy, "X", color="k", mfc="w", mec="k", mew=0.8, ms=8,
                    clip_on=False)  # on the frame too (it was half cut off)
        ax.set_xlabel(r"damping distribution $\log_{10}(c_1/c_2)$ [-]")
        ax.set_ylabel(ylabel)
    fig.subplots_adjust(wspace=0.38)
    fig.colorbar(im, ax=axes,
                 label=r"$\lim_{\epsilon\to 0} P^*_{flu} / P_{flu}$(undamped) [-]")
    stated = r"$l_1=l_2$, $k_1=k_2$, $m_3=0$"
    case = pendulum_case(data, lambda g: g.equal_rods and g.rho2 == 0.0, stated, short=True)
    fig.suptitle("Where the Ziegler paradox is strong (dark) and where it vanishes (ratio 1); "
                 f"{case}; × = checked by Routh–Hurwitz at small " r"$\epsilon$", fontsize=8)
    if case != stated:
        fig.text(0.45, -0.04, own_parameters_note(data, "pendulum", "list47", width=110),
                 ha="center", va="top", fontsize=7)
    return fig
