"""The chapter's sketches, drawn from the models' data: Fig. 1 (closed deformation loops and the
follower's work), Fig. 10 (the Beck and Pflüger rods with their critical mode shapes) and
Fig. 23 (twinning shear)."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Polygon

from flutterfriction.plotting.pendulum import ROD, draw_ground

STATES = ("C0", "C1", "C2", "C3")


def _arrow(ax: Axes, tail, head, color, lw: float = 1.4) -> None:
    ax.annotate("", head, tail, arrowprops={"arrowstyle": "-|>", "lw": lw, "color": color,
                                            "shrinkA": 0, "shrinkB": 0,
                                            "mutation_scale": 14}, zorder=9)


def _path_arrows(ax: Axes, pts: np.ndarray, color: str = "0.15") -> None:
    """The loop through ``pts`` (closed), an arrow head at the middle of each leg."""
    closed = np.vstack([pts, pts[:1]])
    ax.plot(*closed.T, color=color, lw=1.2, zorder=3)
    for a, b in zip(closed[:-1], closed[1:], strict=True):
        m = 0.5 * (a + b)
        _arrow(ax, m - 0.02 * (b - a), m + 0.02 * (b - a), color, lw=1.2)


def _fmt_work(w: float) -> str:
    return "W = 0" if abs(w) < 1e-12 else f"W = {w * 1e3:+.1f} mJ"


def plot_fig01(data: dict[str, Any]) -> Figure:
    """Fig. 1: the two structures in the states of their loops (top) and the loops in the
    plane of their generalised coordinates with the work of each leg (bottom)."""
    bars, rod = data["bars"], data["rod"]
    fig, axes = plt.subplots(2, 2, figsize=(10.0, 8.4),
                             gridspec_kw={"height_ratios": [1.0, 1.0]})
    # -- two bars
    ax = axes[0, 0]
    L = bars["l1"] + bars["l2"]
    names = ("1: straight", r"2: rotated rigidly by $\beta$ about A",
             r"3: AB back, BC keeps $\beta$")
    for pts, colour, name in zip(bars["points"], STATES, names, strict=False):
        A, B, C = (np.array(p) for p in pts)
        ax.plot(*np.array([A, B, C]).T, color=colour, lw=2.2, solid_capstyle="round",
                zorder=4, label=name)
        ax.add_patch(Circle(B, 0.018 * L, fc="white", ec=colour, lw=1.0, zorder=6))
        u = (C - B) / np.linalg.norm(C - B)
        _arrow(ax, C + 0.22 * L * u, C, colour)  # the follower load, coaxial with BC
    ax.add_patch(Circle((0, 0), 0.018 * L, fc="white", ec=ROD, lw=1.0, zorder=6))
    draw_ground(ax, np.zeros(2), 0.06 * L, 0.0)
    ax.annotate("A", (0.0, 0.04 * L), ha="center", va="bottom")
    # B (the hinge) and C (the loaded end) on the straight state, below the bars
    A0, B0, C0 = (np.array(p) for p in bars["points"][0])
    ax.annotate("B", B0 + np.array([0.0, -0.05 * L]), ha="center", va="top")
    ax.annotate("C", C0 + np.array([0.0, -0.05 * L]), ha="center", va="top")
    ax.annotate("P (coaxial with BC)", (1.02 * L, -0.12 * L), ha="center", va="top",
                fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlim(-0.2 * L, 1.35 * L)
    ax.set_ylim(-0.2 * L, 0.8 * L)
    ax.set_axis_off()
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    lengths = (f"l1 = l2 = {bars['l1'] * 1e3:.4g} mm" if bars["l1"] == bars["l2"] else
               f"l1 = {bars['l1'] * 1e3:.4g} mm, l2 = {bars['l2'] * 1e3:.4g} mm")
    ax.set_title(f"Two rigid bars, exact kinematics ({lengths}, P = {bars['P']:g} N)",
                 fontsize=9)

    # -- clamped rod, vertical, drawn to scale
    ax = axes[0, 1]
    l = rod["length"]
    y = np.array(rod["x"])
    names = ("1: straight", r"2: end rotated by $\theta_0$ at $v = 0$",
             r"3: end translated by $v_0$", r"4: end rotated back at $v = v_0$")
    ends = []
    for shape, (v, th), colour, name in zip(rod["shapes"], rod["states"], STATES, names,
                                            strict=True):
        ax.plot(shape, y, color=colour, lw=2.0, label=name, zorder=4)
        t = np.array([np.sin(th), np.cos(th)])
        tip = np.array([v, l])
        ends.append(tip)
        # two states share each end position (1, 2 at v = 0; 3, 4 at v0): heads drawn at the
        # end coincided (a review), so the head sits on the force's line above the end, joined
        # to it by a dotted line of action; a solid one read as the rod going on to the head
        # (a later review), so the ends are marked too
        ax.plot(*np.array([tip, tip + 0.1 * l * t]).T, color=ROD, lw=0.9, ls=(0, (1, 1.5)),
                zorder=3)
        _arrow(ax, tip + 0.26 * l * t, tip + 0.1 * l * t, colour)
    for tip in np.unique(np.round(ends, 12), axis=0):
        ax.add_patch(Circle(tip, 0.014 * l, fc="white", ec=ROD, lw=1.0, zorder=6))
    ax.plot([], [], color=ROD, lw=0.9, ls=(0, (1, 1.5)), marker="o", ms=5, mfc="white",
            mec=ROD, mew=1.0, label="the end; P on its line of action\n(the head drawn above it)")
    ax.add_patch(Polygon([[-0.08 * l, 0], [0.08 * l, 0], [0.08 * l, -0.04 * l],
                          [-0.08 * l, -0.04 * l]], fc="0.75", ec=ROD, lw=0.8))
    ax.set_aspect("equal")
    ax.set_xlim(-0.3 * l, 1.25 * l)
    ax.set_ylim(-0.08 * l, 1.3 * l)
    ax.set_axis_off()
    ax.legend(loc="lower right", fontsize=8, frameon=False)
    ax.set_title(f"Clamped rod, tangential follower load (l = {l * 1e3:.0f} mm, "
                 f"P = {rod['P']:g} N)\nshapes: static beam-column at "
                 f"$p = Pl^2/B$ = {rod['p']:.2f}", fontsize=9)

    # -- the loops in configuration space
    ax = axes[1, 0]
    st = np.degrees(np.array(bars["states"]))
    ax.fill(st[:, 0], st[:, 1], color="C2", alpha=0.12, lw=0)
    _path_arrows(ax, st)
    for i, (a1, a2) in enumerate(st):
        ax.plot(a1, a2, "o", color=STATES[i], ms=7, zorder=5)
        ax.annotate(str(i + 1), (a1, a2), xytext=(-10 if i == 2 else 8, 4),
                    textcoords="offset points", fontsize=10, color=STATES[i])
    beta = np.degrees(bars["beta"])
    w = bars["work"]
    ax.annotate(_fmt_work(w["1-2"]) + "\n(rigid rotation)", (0.62 * beta, 0.5 * beta),
                ha="left", va="top", fontsize=8)
    ax.annotate(_fmt_work(w["2-3"]), (0.5 * beta, 1.04 * beta), ha="center", va="bottom",
                fontsize=8)
    ax.annotate(_fmt_work(w["3-1"]) + "\n(BC turns\nabout B)", (-0.04 * beta, 0.5 * beta),
                ha="right", va="center", fontsize=8)
    ax.annotate(f"net {_fmt_work(bars['net'])} > 0", (0.05 * beta, 0.83 * beta), fontsize=8,
                color="C2")
    ax.set_xlim(-0.45 * beta, 1.3 * beta)
    ax.set_ylim(-0.15 * beta, 1.25 * beta)
    ax.set_xlabel(r"rotation of AB, $\alpha_1$ [deg]")
    ax.set_ylabel(r"rotation of BC, $\alpha_2$ [deg]")
    ax.set_title("Loop 1→2→3→1: work of P on each leg", fontsize=9)

    ax = axes[1, 1]
    st = np.array(rod["states"]) * np.array([1e3, 1.0])
    ax.fill(st[:, 0], st[:, 1], color="C2", alpha=0.12, lw=0)
    _path_arrows(ax, st)
    v0, th0 = st[2]
    offsets = ((-12, 4), (-12, -12), (6, -12), (6, 4))
    for i, (v, th) in enumerate(st):
        ax.plot(v, th, "o", color=STATES[i], ms=7, zorder=5)
        ax.annotate(str(i + 1), (v, th), xytext=offsets[i], textcoords="offset points",
                    fontsize=10, color=STATES[i])
    w = rod["work"]
    ax.annotate(_fmt_work(w["1-2"]), (-0.06 * v0, 0.5 * th0), ha="right", va="center",
                fontsize=8)
    ax.annotate(_fmt_work(w["2-3"]), (0.5 * v0, 1.06 * th0), ha="center", va="top",
                fontsize=8)
    ax.annotate(_fmt_work(w["3-4"]), (1.06 * v0, 0.5 * th0), ha="left", va="center",
                fontsize=8)
    ax.annotate(_fmt_work(w["4-1"]), (0.5 * v0, -0.06 * th0), ha="center", va="bottom",
                fontsize=8)
    ax.annotate(f"net {_fmt_work(rod['net'])} > 0", (0.5 * v0, 0.5 * th0), ha="center",
                va="center", fontsize=8, color="C2")
    ax.set_xlim(-0.5 * v0, 1.5 * v0)
    ax.set_ylim(1.3 * th0, -0.3 * th0)
    ax.set_xlabel(r"transverse displacement of the end, $v$ [mm]")
    ax.set_ylabel(r"rotation of the end, $\theta$ [rad]")
    ax.set_title("Loop 1→2→3→4→1 (small displacements)", fontsize=9)
    fig.suptitle("Fig. 1: a follower force does positive work in a closed deformation loop\n"
                 "(the devices of lists (47) and (119); the loops' sizes β, θ0, v0 are ours: "
                 "the caption gives none)", fontsize=10)
    fig.tight_layout()
    return fig


def plot_fig10(data: dict[str, Any]) -> Figure:
    """Fig. 10: the Beck and Pflüger rods, clamped at the bottom, with their mode shapes at the
    exact critical loads (lines) and the finite-element twin's nodes (markers)."""
    xi = np.array(data["xi"])
    amp = 0.25  # drawn tip deflection, in units of l (the mode's amplitude is arbitrary)
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 7.0), sharey=True)
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.27, top=0.9, wspace=0.12)
    styles = {"flu": ("C0", "flutter"), "div": ("C3", "divergence")}
    titles = {"beck": "Beck rod (no tip mass)",
              "pfluger": f"Pflüger rod (tip mass M, tan α = M/(ρl) = "
                         f"{data['pfluger_tan_alpha']:g})"}
    for ax, (name, rod) in zip(axes, data["rods"].items(), strict=True):
        ax.plot([0, 0], [0, 1], color="0.6", lw=1.0, ls="--", label="undeformed axis")
        for kind, mode in rod["modes"].items():
            colour, label = styles[kind]
            v = amp * np.array(mode["v"])
            ax.plot(v, xi, color=colour, lw=2.2,
                    label=f"{label} mode, p = {mode['p']:.2f} (eq. 118)")
            if kind == "flu":  # the oscillation: the same shape half a period later
                ax.plot(-v, xi, color=colour, lw=1.0, ls=":",
                        label="half a period later")
            fe = mode["fe"]
            ax.plot(amp * np.array(fe["v"])[::4], np.array(fe["xi"])[::4], "o", ms=4,
                    mfc="none", color=colour,
                    label=f"{len(fe['xi']) - 1} elements, p = {mode['p_fe']:.2f}")
            tip = np.array([v[-1], 1.0])
            slope = amp * mode["slope"][-1]
            t = np.array([slope, 1.0]) / np.hypot(slope, 1.0)
            # the tangential follower load; with a tip mass the head stops at the disc's edge
            # (a review: the disc hid both heads)
            gap = 0.032 if name == "pfluger" else 0.0
            _arrow(ax, tip + (0.16 + gap) * t, tip + gap * t, colour)
        if name == "pfluger":
            ax.add_patch(Circle(tip, 0.025, fc="0.3", ec="0.1", zorder=2.5))
        # the symbols the legend would otherwise leave unexplained (a review)
        ax.plot([], [], ls="none", marker=r"$\rightarrow$", ms=11, color="0.2",
                label="the follower load P at the end, tangent to the rod\n(drawn in the "
                      "colour of its mode)")
        if name == "pfluger":
            ax.plot([], [], ls="none", marker="o", ms=8, mfc="0.3", mec="0.1",
                    label="the tip mass M")
        ax.add_patch(Polygon([[-0.12, 0.0], [0.12, 0.0], [0.12, -0.04], [-0.12, -0.04]],
                             fc="0.75", ec=ROD, lw=0.8))
        ax.set_aspect("equal")
        ax.set_xlim(-0.6, 0.6)
        ax.set_ylim(-0.06, 1.25)
        ax.set_xlabel(r"mode $v/l$ [-] (drawn with $v(l)/l$ = 0.25)")
        ax.set_title(titles[name], fontsize=9)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.09), fontsize=7.5,
                  frameon=False)
    axes[0].set_ylabel(r"position along the rod, $x/l$ [-]")
    # the loads differ from those Fig. 12's caption quotes for the same tan(alpha) = 1: said here
    # too (a figure review), not only on Fig. 12
    erratum = ("\nthe 16.51 / 30.22 that Fig. 12's caption quotes for tan α = 1 belong to "
               "another tip mass (see the Fig. 12 erratum)"
               if data["pfluger_tan_alpha"] == 1.0 else "")
    fig.suptitle("Fig. 10: the Beck and the Pflüger rods under a tangential follower load, "
                 "with their critical modes" + erratum, fontsize=10)
    return fig


def plot_fig23(data: dict[str, Any]) -> Figure:
    """Fig. 23: the twinning shear: a square lattice aligned with the twinning plane f1 (grey)
    and the same lattice after the displacement s |x . f2| f1 (blue above, orange below)."""
    f1, f2 = np.array(data["f1"]), np.array(data["f2"])
    R = data["R"]
    fig, ax = plt.subplots(figsize=(6.4, 6.0))
    for i, line in enumerate(data["lines"]):
        x, y = np.array(line["reference"]), np.array(line["deformed"])
        ax.plot(*x.T, color="0.75", lw=0.7, label="reference lattice" if i == 0 else None)
        side = y @ f2
        for mask, colour, name in ((side >= 0, "C0", r"deformed, $\mathbf{x}\cdot\mathbf{f}_2>0$"),
                                   (side <= 0, "C1", r"deformed, $\mathbf{x}\cdot\mathbf{f}_2<0$")):
            yy = np.where(mask[:, None], y, np.nan)
            ax.plot(*yy.T, color=colour, lw=1.1, label=name if i == 1 else None)
    ends = np.array([-1.55 * R * f1, 1.55 * R * f1])
    ax.plot(*ends.T, color="k", lw=1.8, label=r"twinning plane ($\mathbf{f}_1$)")
    o = np.array([1.15 * R, -1.8 * R])
    for vec, name in ((f1, r"$\mathbf{f}_1$"), (f2, r"$\mathbf{f}_2$")):
        _arrow(ax, o, o + 0.35 * R * vec, "k", lw=1.2)
        ax.annotate(name, o + 0.45 * R * vec, ha="center", va="center")
    sv = data["singular_values"]
    # (at unit amplitude, as eq. 171: the lattice drawn with s has s times it; a review)
    ax.text(0.02, 0.02, "jump of the gradient across the plane (eq. 171, unit amplitude;\n"
            f"drawn: s = {data['amplitude']:g} times it): "
            r"$[[\nabla\dot{\mathbf{u}}]] = 2\,\mathbf{f}_1\otimes\mathbf{f}_2$,"
            f"\nsingular values {sv[0]:.3g}, {sv[1]:.1e} (rank one)",
            transform=ax.transAxes, fontsize=8, va="bottom")
    ax.set_aspect("equal")
    ax.set_xlim(-2.0 * R, 2.0 * R)
    ax.set_ylim(-2.0 * R, 2.0 * R)
    ax.set_xlabel(r"$x_1$ [lattice units]")
    ax.set_ylabel(r"$x_2$ [lattice units]")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(r"Fig. 23: twinning shear across the plane $\mathbf{f}_1$ (at α = "
                 f"{np.degrees(data['alpha']):.0f}° from " r"$\mathbf{e}_1$, drawn with s = "
                 f"{data['amplitude']:g})",
                 fontsize=9)
    fig.tight_layout()
    return fig
