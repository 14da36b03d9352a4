"""Figures of chapter §2.1–2.3: Fig. 2 (schematic), Fig. 3 (eq. 34), Fig. 4 (motions) and the
load–frequency diagrams of the critical-load scenes (eqs. 25, 46–48)."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Arc, Patch

from flutterfriction.plotting import (
    REGIME_COLOURS,
    list47,
    own_parameters_note,
    pendulum_case,
    pendulum_text,
    wrap_items,
)
from flutterfriction.plotting.labels import declutter, label_at
from flutterfriction.plotting.pendulum import MASS, ROD, draw_pendulum


def _shade_regimes(ax, edges: list[float], names: list[str], x_max: float) -> None:
    bounds = [0.0, *edges, x_max]
    for lo, hi, name in zip(bounds[:-1], bounds[1:], names, strict=True):
        ax.axvspan(lo, hi, color=REGIME_COLOURS[name], alpha=0.8, lw=0, zorder=0)


def _q(data: dict[str, Any], key: str) -> float:
    return data["quantities"][key]["value"]


def plot_dead_load_spectrum(data: dict[str, Any], title: str) -> Figure:
    """omega^2 against eta = H l1/k2 with H_cr and H_sup (eqs. 19, 22, 25)."""
    c = data["curve"]
    eta = np.array(c["eta"])
    re = np.array(c["omega2_re"])
    closed = np.array(c["omega2_closed_form"])
    e_cr, e_sup = _q(data, "eta_cr"), _q(data, "eta_sup")
    fig, ax = plt.subplots(figsize=(5.2, 3.4), layout="constrained")
    _shade_regimes(ax, [e_cr, e_sup], ["stable", "divergence", "divergence"], eta[-1])
    for i, branch in enumerate(re):
        ax.plot(eta, branch, color="C0", lw=1.6,
                label="eigenvalues of (K+G, M)" if i == 0 else None)
    step = max(1, len(eta) // 25)
    for i, branch in enumerate(closed):
        ax.plot(eta[::step], branch[::step], "o", ms=3, mfc="none", color="C1",
                label="closed form, eq. (19)" if i == 0 else None)
    ax.axhline(0, color="k", lw=0.8)
    for val, name in ((e_cr, r"$\eta_{cr}$"), (e_sup, r"$\eta_{sup}$")):
        ax.axvline(val, color="k", ls="--", lw=0.8)
        # Above the frame, clear of the branches.
        ax.annotate(f"{name} = {val:.4f}", (val, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(0, 2), textcoords="offset points", ha="center", va="bottom",
                    fontsize=8)
    # Region names where no branch passes (above the falling upper branch in the middle).
    for name, xpos, ypos in (("stable", e_cr / 2, 0.55),
                             ("divergence: one $\\omega^2 < 0$", 0.4 * e_cr + 0.6 * e_sup, 0.85),
                             ("both $\\omega^2 < 0$", (e_sup + eta[-1]) / 2, 0.55)):
        ax.annotate(name, (xpos, ypos), xycoords=("data", "axes fraction"), ha="center",
                    fontsize=8)
    ax.set_xlim(eta[0], eta[-1])
    ax.set_xlabel(r"dead load $\eta = H l_1/k_2$ [-]")
    ax.set_ylabel(r"$\omega^2 = m_2 l_2^2\,\Omega^2/k_2$ [-]")
    ax.set_title(title, pad=17)
    ax.legend(loc="lower left")
    return fig


def plot_follower_spectrum(data: dict[str, Any], title: str, in_newtons: bool = False) -> Figure:
    """Re and Im of omega^2 against the follower load, regimes shaded (eqs. 34, 39, 41)."""
    c = data["curve"]
    gamma = np.array(c["gamma"])
    unit = data["load_unit_N"] if in_newtons else 1.0
    x = gamma * unit
    g_flu, g_div = _q(data, "gamma_flu"), _q(data, "gamma_div")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(5.2, 4.6), sharex=True, layout="constrained",
                                   gridspec_kw={"height_ratios": [3, 2]})
    step = max(1, len(gamma) // 30)
    for ax, key, label in ((ax1, "re", r"Re $\omega^2$"), (ax2, "im", r"Im $\omega^2$")):
        _shade_regimes(ax, [g_flu * unit, g_div * unit], ["stable", "flutter", "divergence"],
                       x[-1])
        for i, branch in enumerate(np.array(c[f"omega2_{key}"])):
            ax.plot(x, branch, color="C0", lw=1.6,
                    label="eigenvalues of (K+G, M)" if i == 0 else None)
        for i, branch in enumerate(np.array(c[f"omega2_closed_form_{key}"])):
            ax.plot(x[::step], branch[::step], "o", ms=3, mfc="none", color="C1",
                    label="closed form, eq. (34)" if i == 0 else None)
        ax.axhline(0, color="k", lw=0.8)
        for val in (g_flu, g_div):
            ax.axvline(val * unit, color="k", ls="--", lw=0.8)
        ax.set_ylabel(label + r" [-]")
    # the normalisation of eq. (17), as Fig. eq25 states it (a figure review: with the load in
    # newtons, omega^2 read as a dimensional quantity)
    ax1.set_ylabel(r"Re $\omega^2$ [-], $\omega^2 = m_2 l_2^2\,\Omega^2/k_2$")
    fmt = ("{:.4f} N" if in_newtons else "{:.4f} K/L")  # (the caption quotes 4.8038, 8.8042 N)
    # Threshold values above the frame, clear of the branches (ending / starting at their line).
    for name, val, ha in ((r"$P_{flu}$", g_flu, "right"), (r"$P_{div}$", g_div, "left")):
        ax1.annotate(name + " = " + fmt.format(val * unit), (val * unit, 1.0),
                     xycoords=("data", "axes fraction"), xytext=(0, 2),
                     textcoords="offset points", ha=ha, va="bottom", fontsize=8)
    # Regime names just above Im = 0, inside the flutter ellipse and beside it.
    for name, xpos in (("stable", g_flu / 2), ("flutter", (g_flu + g_div) / 2),
                       ("divergence", (g_div + gamma[-1]) / 2)):
        ax2.annotate(name, (xpos * unit, 0.58), xycoords=("data", "axes fraction"),
                     ha="center", fontsize=8)
    ax1.legend(loc="lower left")
    ax1.set_title(title, pad=17)
    ax2.set_xlim(x[0], x[-1])
    ax2.set_xlabel(r"follower load $P$ [N]" if in_newtons
                   else r"follower load $\gamma = P l_1/k_2$ [-]")
    return fig


def plot_fig03(data: dict[str, Any]) -> Figure:
    """Fig. 3: the line beta1 - gamma beta2 and the parabola (beta1 - gamma beta2)^2 - 4ka."""
    c = data["curve"]
    gamma = np.array(c["gamma"])
    line, parab = np.array(c["line"]), np.array(c["parabola"])
    g_flu, g_div = _q(data, "gamma_flu"), _q(data, "gamma_div")
    vertex = _q(data, "gamma_vertex")
    fig, ax = plt.subplots(figsize=(5.4, 3.8), layout="constrained")
    _shade_regimes(ax, [g_flu, g_div], ["stable", "flutter", "divergence"], gamma[-1])
    ax.plot(gamma, line, color="C0", lw=1.8, label=r"$\beta_1 - \gamma\beta_2$")
    ax.plot(gamma, parab, color="C3", lw=1.8, label=r"$(\beta_1 - \gamma\beta_2)^2 - 4ka$")
    ax.axhline(0, color="k", lw=0.8)
    for val, name in ((g_flu, r"$\gamma_{flu}$"), (vertex, r"$\beta_1/\beta_2$"),
                      (g_div, r"$\gamma_{div}$")):
        ax.axvline(val, color="k", ls="--" if val != vertex else ":", lw=0.8)
        # Labels on the side of each line away from the parabola's steep flanks.
        # (2 pt off the line: touching it, the label read as struck through; a review)
        left = val == g_flu
        ax.annotate(f"{name} = {val:.3f}", (val, 0.98), xycoords=("data", "axes fraction"),
                    xytext=(2 if left else -2, 0), textcoords="offset points",
                    rotation=90, va="top", ha="left" if left else "right", fontsize=8)
    ymin = min(line.min(), parab.min())
    ax.set_ylim(1.35 * ymin, 1.2 * line.max())
    for name, xpos in (("stable", g_flu / 2), ("flutter", (g_flu + vertex) / 2),
                       ("divergence", (g_div + gamma[-1]) / 2)):
        ax.annotate(name, (xpos, 0.03), xycoords=("data", "axes fraction"), ha="center",
                    fontsize=8)
    ax.set_xlim(gamma[0], gamma[-1])
    ax.set_xlabel(r"$\gamma = P l_1/k_2$ [-]")
    ax.set_ylabel("the two terms of eq. (34) [-]")
    unit = data["load_unit_N"]
    top = ax.secondary_xaxis("top", functions=(lambda g: g * unit, lambda P: P / unit))
    top.set_xlabel("P [N]")
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 0.12))
    co = data["coefficients"]
    title = (f"Eq. (34) for {list47(data)}: "
             + rf"$a$ = {co['a']:.4f}, $\beta_1$ = {co['beta1']:.4f}, "
             rf"$\beta_2$ = {co['beta2']:.4f}")
    printed = data.get("gammas_as_printed")
    if printed is not None:  # the erratum of eq. (37), stated where its values show
        title += ("\n" + r"$\gamma_{flu}, \gamma_{div}$ from eq. (37) corrected, "
                  r"$(\beta_1 \mp 2\sqrt{ka})/\beta_2$;" + "\n"
                  + r"as printed, $(\beta_1 \mp 2\sqrt{k}\,a)/\beta_2$, "
                  f"they would be {printed[0]:.3f}, {printed[1]:.3f}")
    ax.set_title(title, pad=6, fontsize=8)  # (placed above the top P axis by matplotlib)
    return fig


#: Frames whose linear angles exceed this are flagged: there the linearisation of eq. (11)
#: (sin a ~ a) is meaningless (the divergence's last frame reaches +188 / -221 degrees), but
#: the printed figure draws it, so it is drawn (as printed) with the flag.
FIG04_MAX_DEG = 45.0


def plot_fig04(data: dict[str, Any]) -> Figure:
    """Fig. 4: configurations of the linear motion every dt, flutter (upper), divergence (lower).

    The pendulum is drawn as in Fig. 2 (A on the left, e1 to the right, the load at C pushing
    back along BC), at its true angles (the linear solution's, with the exact rigid-rod
    kinematics of eq. 1). Beside each sequence, alpha1(t) and alpha2(t) of the same solution
    with the drawn instants marked, so the growing oscillation (flutter) and the exponential
    departure (divergence) read off the drawing. Frames with an angle beyond
    ``FIG04_MAX_DEG`` are drawn as printed and flagged: the linearisation is invalid there.
    """
    cases = data["cases"]
    order = [n for n in ("flutter", "divergence") if n in cases] + \
        [n for n in cases if n not in ("flutter", "divergence")]
    ncol = 4
    flagged = False  # a frame beyond FIG04_MAX_DEG (its key entry)
    rows = [int(np.ceil(len(cases[n]["times"]) / ncol)) for n in order]
    L = float(np.linalg.norm(np.array(cases[order[0]]["points"]["B"][0])
                             - np.array(cases[order[0]]["points"]["A"][0])))
    span = float(np.linalg.norm(np.array(cases[order[0]]["points"]["C"][0])))
    fig = plt.figure(figsize=(8.6, 1.05 * sum(rows) + 0.5 * len(order) + 0.5))
    outer = fig.add_gridspec(len(order), 1, height_ratios=[r + 0.5 for r in rows], hspace=0.35,
                             top=0.93, bottom=0.07)
    for k, name in enumerate(order):
        case = cases[name]
        sub = outer[k].subgridspec(rows[k], ncol + 2, width_ratios=[1] * ncol + [0.15, 1.6],
                                   wspace=0.05, hspace=0.12)
        pts = {key: np.array(v) for key, v in case["points"].items()}
        alpha = np.degrees(np.array(case["alpha"]))
        times = case["times"]
        dt = times[1] - times[0]
        for i, t in enumerate(times):
            ax = fig.add_subplot(sub[i // ncol, i % ncol])
            ax.set_aspect("equal")
            # room for the load's arrow beyond C (at 1.15 span its tail was cut by the frame)
            ax.set_xlim(-0.25 * span, 1.25 * span)
            ax.set_ylim(-0.45 * span, 0.45 * span)
            ax.set_xticks([])
            ax.set_yticks([])
            ax.grid(False)
            for side in ax.spines.values():
                side.set_color("0.8")
            a1, a2 = alpha[i]
            beyond = max(abs(a1), abs(a2)) > FIG04_MAX_DEG
            flagged |= beyond
            ax.text(0.02, 0.96, f"t = {t:.2f} s" + (f": |α| > {FIG04_MAX_DEG:g}°" if beyond
                                                   else ""),
                    transform=ax.transAxes, fontsize=7, va="top",
                    color="C3" if beyond else "black")
            ax.text(0.02, 0.04, f"{a1:+.1f}°, {a2:+.1f}°", transform=ax.transAxes,
                    fontsize=6.5, ha="left", va="bottom", color="0.35")
            if beyond:
                # drawn, as in the printed figure, and flagged (a figure review asked for the
                # printed frame rather than a note in its place)
                for side in ax.spines.values():
                    side.set_color("C3")
            ax.plot([0, span], [0, 0], color="0.7", lw=0.6, ls="--")
            frame = {key: v[i] for key, v in pts.items()}
            # (scale 0.5 L drew hinge B and the masses too small to see in these frames)
            draw_pendulum(ax, frame, data["masses"], scale=1.2 * L, springs=False,
                          loads={"P": 0.3 * L}, arrow_head=6.0, arrow_gap=0.0)
            if beyond:  # the whole (folded back) pendulum in its frame, at the same scale
                xy = np.array([np.asarray(v, dtype=float) for v in frame.values()])
                cx, cy = 0.5 * (xy[:, 0].min() + xy[:, 0].max()), 0.5 * (xy[:, 1].min()
                                                                      + xy[:, 1].max())
                ax.set_xlim(cx - 0.7 * span, cx + 0.7 * span)
                ax.set_ylim(cy - 0.35 * span, cy + 0.55 * span)  # room for the flag above
        ax_t = fig.add_subplot(sub[:, ncol + 1])
        t_d = np.array(case["t_dense"])
        a_d = np.degrees(np.array(case["alpha_dense"]))
        for j, (lab, col) in enumerate(((r"$\alpha_1$", "C0"), (r"$\alpha_2$", "C2"))):
            ax_t.plot(t_d, a_d[:, j], color=col, lw=1.2, label=lab)
            ax_t.plot(times, alpha[:, j], "o", ms=2.5, color=col)
        ax_t.plot([], [], "o", ms=2.5, color="0.3", label="instants drawn")
        lim = min(1.1 * np.abs(alpha).max(), FIG04_MAX_DEG + 15)
        ax_t.set_ylim(-lim, lim)
        if np.abs(alpha).max() > FIG04_MAX_DEG:
            for sgn in (1, -1):
                ax_t.axhspan(sgn * FIG04_MAX_DEG, sgn * lim, color="0.88", lw=0)
            ax_t.text(0.03, 0.97, f"|α| > {FIG04_MAX_DEG:g}°: linearisation invalid",
                      transform=ax_t.transAxes, fontsize=6.5, va="top", color="0.3",
                      bbox={"facecolor": "0.88", "edgecolor": "none", "pad": 1.0}, zorder=5)
        ax_t.set_xlim(-0.02 * times[-1], 1.02 * times[-1])  # the end instants' dots whole
        ax_t.set_xlabel("time t [s]")
        ax_t.set_ylabel("linear solution [deg]")
        ax_t.yaxis.set_label_position("right")
        ax_t.yaxis.tick_right()
        ax_t.legend(fontsize=7, loc="lower left")
        n_free = rows[k] * ncol - len(times)
        if k == len(order) - 1:
            # the key to the frames: in the free slots of the last row, else below the figure
            handles = [
                Line2D([], [], color=ROD, lw=2, label="rigid rods AB, BC"),
                Line2D([], [], color=MASS, marker="o", ls="none", mec="k", mew=0.5, ms=5,
                       label="masses at D, E, C"),
                Line2D([], [], color=ROD, marker="o", ls="none", mfc="white", mew=1.0, ms=3,
                       label="hinge B"),
                Line2D([], [], color="#c0392b", marker="<", ls="-", lw=1.6, ms=5,
                       markevery=[0], label="follower load P at C (along BC)"),
                Line2D([], [], color="0.7", lw=0.8, ls="--",
                       label="straight: α1 = α2 = 0")]
            if flagged:  # (the note in its frame overflowed it at 100 dpi)
                handles.append(Patch(facecolor="none", edgecolor="C3",
                                     label=f"frame with |α| > {FIG04_MAX_DEG:g}°: linear\n"
                                           "solution invalid (drawn as printed)"))
            if n_free >= 2:
                ax_key = fig.add_subplot(sub[rows[k] - 1, ncol - n_free:ncol])
                ax_key.set_axis_off()
                ax_key.legend(handles=handles, loc="center", fontsize=6.5,
                              title="key to the frames", title_fontsize=7)
            else:
                fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=6.5,
                           bbox_to_anchor=(0.5, 0.0))
        # The regime this pendulum has at this load (computed): the chapter's cases are
        # flutter and divergence for list (47); with another pendulum they may not be (an
        # outside audit: k1 = k2 = 0.6 N m made the "flutter" load stable).
        computed = data.get("quantities", {}).get(f"regime_{name}", {}).get("value", name)
        part = {"flutter": " (upper part)", "divergence": " (lower part)"}.get(name, "")
        label = (f"{str(computed).capitalize()}{part}" if computed == name else
                 f"The chapter's {name} case{part}, {computed} for this pendulum")
        fig.text(0.1, outer[k].get_position(fig).y1 + 0.008,
                 f"{label}: P = {case['P']:g} N, initially "
                 f"α1 = α2 = {alpha[0, 0]:+.1f}°; every {dt:.2f} s (α1, α2 at the lower "
                 "left of each frame)", fontsize=8, va="bottom")
    fig.suptitle("Linear eq. (11) solved exactly (matrix exponential), "
                 f"{list47(data, short=True)}; "
                 "drawn as in Fig. 2 with the follower load P at C", fontsize=8.5, y=1.0)
    note = own_parameters_note(data, "pendulum", "list47", width=110)
    if note:  # under the figure (in the title it widened the figure; an outside review)
        fig.text(0.5, -0.005, note, ha="center", va="top", fontsize=7.5)
    return fig


def _dimension(ax, p: np.ndarray, q: np.ndarray, normal: np.ndarray, offset: float,
               text: str, inside: bool = False) -> None:
    """A dimension line parallel to p-q at ``offset`` along ``normal``, labelled ``text``
    beyond it (``inside``: between it and the rod)."""
    a, b = p + offset * normal, q + offset * normal
    ax.annotate("", b, a, arrowprops={"arrowstyle": "|-|,widthA=0.25,widthB=0.25", "lw": 0.7,
                                      "color": "0.3", "shrinkA": 0, "shrinkB": 0})
    side = -1.0 if inside else 1.0
    ax.annotate(text, (a + b) / 2, xytext=(10 * side * normal[0], 10 * side * normal[1]),
                textcoords="offset points", ha="center", va="center", color="0.3", fontsize=9)


def plot_fig02(data: dict[str, Any]) -> Figure:
    """Fig. 2: the Ziegler double pendulum with its springs, masses and the loads P and H."""
    pts = {k: np.array(v) for k, v in data["points"].items()}
    L = float(np.linalg.norm(pts["B"] - pts["A"]))
    fig, ax = plt.subplots(figsize=(5.6, 4.2))
    # The undeformed axis, and the rotations alpha1, alpha2 measured from e1, drawn outside
    # the masses D and E (at d and h from the hinges).
    ax.plot([0, 2.25 * L], [0, 0], color="0.6", lw=0.8, ls="--")
    ax.plot([pts["B"][0], pts["B"][0] + 0.75 * L], [pts["B"][1]] * 2, color="0.6", lw=0.8,
            ls="--")
    for centre, angle, name in ((pts["A"], data["alpha1"], r"$\alpha_1$"),
                                (pts["B"], data["alpha2"], r"$\alpha_2$")):
        ax.add_patch(Arc(centre, 1.2 * L, 1.2 * L, theta1=0, theta2=np.degrees(angle), lw=0.8))
        mid = angle / 2
        label_at(ax, name, centre, 0.7 * L * np.array([np.cos(mid), np.sin(mid)]),
                 ha="center", va="center")
    draw_pendulum(ax, pts, data["masses"], scale=L, loads={"P": 0.45 * L, "H": 0.45 * L},
                  labels=True)
    A, B, C, D, E = (pts[k] for k in "ABCDE")
    n1 = np.array([-(B - A)[1], (B - A)[0]]) / np.linalg.norm(B - A)
    n2 = np.array([-(C - B)[1], (C - B)[0]]) / np.linalg.norm(C - B)
    # Lengths d = |AD|, l1 = |AB|, h = |BE|, l2 = |BC|, on the upper side of the rods.
    # h's label between its line and the rod: beyond it, it sat against l1's end tick and
    # could be read as l1's (an outside review)
    for p, q, nn, off, name in ((A, D, n1, 0.25, "$d$"), (A, B, n1, 0.42, "$l_1$"),
                                (B, E, n2, 0.27, "$h$"), (B, C, n2, 0.62, "$l_2$")):
        if np.linalg.norm(q - p) > 0.02 * L:  # h = 0 (eq. 46's pendulum): no length to show
            _dimension(ax, p, q, nn, off * L, name, inside=name == "$h$")
    for name, p, dxy in (("$k_1$", A, (0.1, -0.16)), ("$k_2$", B, (0.1, -0.15)),
                         ("$m_1$", D, (0.06, -0.16)), ("$m_2$", C, (0.15, -0.1)),
                         ("$m_3$", E, (0.13, -0.08))):
        label_at(ax, name, p, L * np.array(dxy), ha="center", va="center", color="0.2")
    o = np.array([1.75 * L, -0.45 * L])
    ax.annotate("", o + [0.3 * L, 0], o, arrowprops={"arrowstyle": "-|>", "lw": 0.8})
    ax.annotate("", o + [0, 0.3 * L], o, arrowprops={"arrowstyle": "-|>", "lw": 0.8})
    ax.annotate(r"$\mathbf{e}_1$", o + [0.33 * L, 0], va="center")
    ax.annotate(r"$\mathbf{e}_2$", o + [0, 0.33 * L], ha="center")
    ax.set_aspect("equal")
    # the chapter's proportions, widened for a pendulum of one's own (l2 >> l1 ran off it)
    top = max(p[1] for p in pts.values())
    right = max(p[0] for p in pts.values())
    ax.set_xlim(min(-0.5 * L, min(p[0] for p in pts.values()) - 0.3 * L),
                max(2.45 * L, right + 0.75 * L))
    ax.set_ylim(-0.55 * L, top + 0.45 * L)
    ax.set_axis_off()
    ax.set_title("The Ziegler double pendulum (follower load P parallel to BC, dead load H "
                 "parallel to $\\mathbf{e}_1$)", fontsize=8)
    declutter(ax)
    return fig


def plot_eq25(data: dict[str, Any]) -> Figure:
    # H_cr does not depend on the masses, the omega^2 curves do: the pendulum is stated.
    text = pendulum_text(data.get("params", {}).get("pendulum"))
    stated = r"Eq. (25): dead load on equal rods, $H_{cr}$ = (3-$\sqrt{5}$)/2 K/L"
    title = pendulum_case(data, lambda g: g.equal_rods, stated)
    if title == stated:
        return plot_dead_load_spectrum(data, stated
                                       + (f"\n{wrap_items(text, 60)}" if text else ""))
    return plot_dead_load_spectrum(data, f"Dead load (eq. 22) on {title}")


def plot_eq46(data: dict[str, Any]) -> Figure:
    return plot_follower_spectrum(data, pendulum_case(
        data, lambda g: g.symmetric,
        r"Eq. (46): $l_1=l_2=L$, $d=L$, $k_1=k_2=K$, $m_1=m_2$, $m_3=0$"))


def plot_eq47(data: dict[str, Any]) -> Figure:
    return plot_follower_spectrum(
        data, f"{list47(data, 'List (47): the device of §2.10')}",
        in_newtons=True)


def plot_eq48(data: dict[str, Any]) -> Figure:
    return plot_follower_spectrum(data, pendulum_case(
        data, lambda g: g.equal_rods and g.rho1 == 1.0 and g.rho2 == 0.0 and g.y1 == 0.5,
        r"Eq. (48): as eq. (46) but $d = L/2$ ($y_1 = 1/2$)"))
