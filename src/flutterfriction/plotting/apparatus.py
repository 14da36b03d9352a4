"""Fig. 18 drawn from the lever model's data: the pendulum with its wheel on the sliding plate
(top view), the lever calibration with its forces to scale (side view) and the calibration
line P(W)."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrowPatch, Rectangle

from flutterfriction.plotting import list47, own_parameters_note
from flutterfriction.plotting.labels import declutter, label_at
from flutterfriction.plotting.pendulum import MASS, ROD, SPRING, draw_ground, draw_pendulum

FORCE = {"W": "C0", "R": "C2", "P": "C3", "O": "C4"}
PLATE = "0.82"


def _force(ax: Axes, tail, head, colour: str, lw: float = 2.0) -> None:
    ax.add_patch(FancyArrowPatch(tuple(tail), tuple(head), arrowstyle="-|>", mutation_scale=13,
                                 color=colour, lw=lw, zorder=9, shrinkA=0, shrinkB=0))


def _dimension(ax: Axes, x0: float, x1: float, y: float, text: str) -> None:
    ax.add_patch(FancyArrowPatch((x0, y), (x1, y), arrowstyle="<|-|>", mutation_scale=8,
                                 color="0.3", lw=0.8, shrinkA=0, shrinkB=0))
    ax.annotate(text, ((x0 + x1) / 2, y), xytext=(0, 2), textcoords="offset points",
                ha="center", va="bottom", fontsize=8, color="0.2")


def _plate_span(data: dict[str, Any]) -> tuple[float, float]:
    """The plate's extent along the rod [m]: around the wheel, clear of the weight's string."""
    b = data["b"]
    return max(b - 0.07, 0.5 * (data["a"] + b)), b + 0.07


def _top_view(ax: Axes, data: dict[str, Any], s: float) -> None:
    """Upper part of Fig. 18: the deflected pendulum seen from above, its wheel on the plate."""
    top, b, r = data["top"], data["b"], data["r"]
    pts = {k: np.array(v) for k, v in top["points"].items()}
    B, C = pts["B"], pts["C"]
    x0, x1 = _plate_span(data)
    ax.add_patch(Rectangle((x0, -0.06), x1 - x0, 0.12, fc=PLATE, ec="0.5", lw=0.8, zorder=1))
    v = np.array(top["plate_velocity"])
    v_hat = v / np.linalg.norm(v)
    for y in (-0.045, 0.045):
        _force(ax, (b + 0.055, y), (b + 0.055 + 0.05 * v_hat[0], y), "0.35", lw=1.2)
    ax.annotate(f"plate, v = {1e3 * np.linalg.norm(v):.0f} mm/s", ((x0 + x1) / 2, -0.06),
                xytext=(0, -3), textcoords="offset points", ha="center", va="top", fontsize=8)
    # C is labelled below, clear of the wheel drawn over it
    draw_pendulum(ax, top["points"], top["masses"], 0.5 * b, labels="ABDE")
    t = (C - B) / np.linalg.norm(C - B)
    n = np.array([-t[1], t[0]])
    ax.plot(*np.array([C - r * n, C + r * n]).T, color="k", lw=4.5, solid_capstyle="butt",
            zorder=8)
    # the mass at C on top of the wheel (draw_pendulum's size for it), so that all three show
    m = top["masses"]
    r_C = max(0.075 * 0.5 * b * (m["m2"] / max(m.values())) ** (1 / 3), 0.03 * 0.5 * b)
    ax.add_patch(Circle(C, r_C, fc=MASS, ec="black", lw=0.5, zorder=10))
    f = np.array(top["force_direction"])
    _force(ax, C - top["P"] * s * f, C, FORCE["P"])
    # two lines, so that the label stays on the plate (one line ran across its edge)
    ax.annotate(rf"$P = \mu R$ = {top['P']:.2f} N,""\nalong CB", C - top["P"] * s * f,
                xytext=(3, 5), textcoords="offset points", fontsize=8, color=FORCE["P"],
                ha="left", va="bottom")
    ax.annotate("wheel: axle along BC,\nrolls freely normal to BC", C + r * n,
                xytext=(x0 - 0.008, 0.045), textcoords="data", fontsize=7.5, ha="right",
                va="bottom", arrowprops={"arrowstyle": "-", "color": "0.3", "lw": 0.7})
    label_at(ax, "C", C, -(r + 0.004) * n, ha="center", va="top", fontsize=10)
    handles = [Line2D([], [], color=ROD, lw=2, label="rigid rods AB, BC"),
               Line2D([], [], color=SPRING, lw=0.8, label="rotational springs at A, B"),
               Line2D([], [], color=MASS, marker="o", ls="none", mec="k", mew=0.5,
                      label="masses at D, C, E"),
               Line2D([], [], color="k", lw=4, label="wheel (diameter 2r, seen from above)"),
               Line2D([], [], color="0.35", lw=1.2, label="plate velocity")]
    ax.legend(handles=handles, loc="lower left", fontsize=7)
    a1, a2 = top["alpha_deg"]
    which = list47(data, short=True)
    which = which if which.startswith("your own") else f"the pendulum of {which}"
    ax.set_title(f"top view (upper part): {which} drawn at α1 = {a1:g}°, "
                 f"α2 = {a2:g}°;\nthe plate transmits only the friction along BC "
                 f"(its component normal to BC: {top['force_transverse_to_BC']:.0f} N)",
                 fontsize=8)
    # the chapter's view; a longer pendulum of one's own widens it, and its height grows
    # with it, keeping the room under the rods that the key takes (it covered them)
    ax.set_xlim(-0.045, b + 0.125)
    ax.set_ylim(0.075 - 0.16 * max(1.0, (b + 0.17) / 0.37), 0.075)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y (horizontal plane) [m]")
    declutter(ax)


def _side_view(ax: Axes, data: dict[str, Any], s: float) -> None:
    """Lower part of Fig. 18: the straight pendulum as a lever in its vertical plane."""
    a, b, r, mu = data["a"], data["b"], data["r"], data["mu"]
    F = data["forces_drawn"]
    W = data["W_drawn"]
    plate_y = -r
    x0, x1 = _plate_span(data)
    ax.add_patch(Rectangle((x0, plate_y - 0.012), x1 - x0, 0.012, fc=PLATE, ec="0.5", lw=0.8,
                           zorder=1))
    _force(ax, (b + 0.068, plate_y - 0.022), (b + 0.018, plate_y - 0.022), "0.35", lw=1.2)
    ax.annotate("plate velocity", (b + 0.043, plate_y - 0.022), xytext=(0, -3),
                textcoords="offset points", ha="center", va="top", fontsize=7.5)
    draw_ground(ax, np.zeros(2), 0.012, np.pi / 2)
    ax.plot([0, b], [0, 0], color=ROD, lw=2.4, solid_capstyle="round", zorder=4)
    for x in (0.0, data["l1"], b):
        ax.add_patch(Circle((x, 0.0), 0.0035, fc="white", ec=ROD, lw=1.0, zorder=6))
    ax.annotate("A = fulcrum O", (0, 0), xytext=(-6, 6), textcoords="offset points",
                ha="right", va="bottom", fontsize=8)
    ax.annotate("B", (data["l1"], 0), xytext=(0, 6), textcoords="offset points", ha="center",
                va="bottom", fontsize=8)
    ax.add_patch(Rectangle((b - 0.003, -r), 0.006, 2 * r, fc="0.25", ec="k", lw=0.6,
                           zorder=7))
    ax.annotate("wheel at C (edge-on)", (b + 0.003, r), xytext=(6, 4),
                textcoords="offset points", ha="left", va="bottom", fontsize=7.5)
    # the weight, its string and its force at the hook
    hook = np.array([a, 0.0])
    ax.plot([a, a], [0, -W * s], color="0.55", lw=0.8, zorder=2)
    ax.add_patch(Rectangle((a - 0.011, -W * s - 0.02), 0.022, 0.02, fc="0.7", ec="0.3",
                           lw=0.8, zorder=3))
    _force(ax, hook, hook + np.array([0.0, -W * s]), FORCE["W"])
    ax.annotate(f"W = {W:g} N", hook + np.array([0.0, -0.5 * W * s]), xytext=(6, 0),
                textcoords="offset points", color=FORCE["W"], fontsize=8, va="center")
    K = np.array(data["side_points"]["K"])
    _force(ax, K - np.array([0.0, F["R"] * s]), K, FORCE["R"])
    ax.annotate(f"R = {F['R']:.2f} N", K - np.array([0.0, 0.75 * F["R"] * s]),
                xytext=(-5, 0), textcoords="offset points", color=FORCE["R"], fontsize=8,
                ha="right", va="center")
    _force(ax, K + np.array([F["P"] * s, 0.0]), K, FORCE["P"])
    ax.annotate(rf"$P = \mu R$ = {F['P']:.2f} N", K + np.array([F["P"] * s, 0.0]),
                xytext=(3, 3), textcoords="offset points", color=FORCE["P"], fontsize=8,
                ha="left", va="bottom")
    O = np.array([F["O_x"], F["O_y"]])
    _force(ax, -O * s, np.zeros(2), FORCE["O"])
    ax.annotate(f"hinge reaction\n({F['O_x']:.2f}, {F['O_y']:.2f}) N", -O * s, xytext=(0, -3),
                textcoords="offset points", color=FORCE["O"], fontsize=7.5, ha="center",
                va="top")
    _dimension(ax, 0.0, a, 0.024, f"a = {a:g} m")
    _dimension(ax, 0.0, b, 0.046, f"b = l1 + l2 = {b:g} m")
    ax.annotate(f"r = {r:g} m", (b, -r / 2), xytext=(-6, 0), textcoords="offset points",
                ha="right", va="center", fontsize=7.5)
    # force scale bar
    bar = 10.0
    x0, y0 = 0.03, -0.06
    ax.plot([x0, x0 + bar * s], [y0, y0], color="k", lw=2)
    ax.annotate(f"forces: {bar:g} N", (x0 + bar * s / 2, y0), xytext=(0, 3),
                textcoords="offset points", ha="center", va="bottom", fontsize=7.5)
    ax.set_title(f"side view (lower part): the straight pendulum as a lever, forces to scale "
                 f"at W = {W:g} N; moment balance about O: W a = R (b − μ r)", fontsize=8)
    ax.set_xlim(-0.06, b + 0.13)
    ax.set_ylim(-0.125, 0.07)
    ax.set_aspect("equal")
    ax.set_xlabel("x, along the rod [m]")
    ax.set_ylabel("height [m]")
    handles = [Line2D([], [], color=FORCE[k], lw=2, label=lab) for k, lab in (
        ("W", "hanging weight W"), ("R", "contact force R of the plate"),
        ("P", "friction P = μR (the follower force)"), ("O", "reaction of the fulcrum"))]
    ax.legend(handles=handles, loc="lower right", fontsize=7.5)
    ax.text(0.012, 0.02, f"μ = {mu:g}, a = {a:g} m, r = {r:g} m: our choice\n"
            "(the chapter gives no lever arms);\nthe lever's own weight is not modelled",
            transform=ax.transAxes, ha="left", va="bottom", fontsize=7.5,
            bbox={"fc": "white", "ec": "0.7", "lw": 0.6})


def _calibration(ax: Axes, data: dict[str, Any]) -> None:
    W, P, Ps = (np.array(data[k]) for k in ("W", "P", "P_system"))
    step = max(1, len(W) // 12)
    ax.plot(W, P, color=FORCE["P"], lw=1.8,
            label=f"P = μ a W / (b − μ r), slope {data['ratio']:.4f}")
    ax.plot(W[::step], Ps[::step], "o", ms=4, mfc="none", mec="k",
            label="lever equilibrium solved as a linear system")
    ax.plot(W, data["ratio_without_offset"] * W, "--", color="0.5", lw=1.0,
            label=f"μ a W / b (friction's moment neglected), slope "
                  f"{data['ratio_without_offset']:.4f}")
    c = data["critical"]
    for key, name, ls in (("flu", "flutter", ":"), ("div", "divergence", "-.")):
        Pc, Wc = c[f"P_{key}"], c[f"W_{key}"]
        ax.plot([0, Wc, Wc], [Pc, Pc, 0], ls, color="0.25", lw=0.9,
                label=f"{name} load of {list47(data, short=True)}: P = {Pc:.2f} N at "
                      f"W = {Wc:.1f} N")
    ax.set_xlim(0, 1.02 * W[-1])
    ax.set_ylim(0, 1.07 * P[-1])
    ax.set_xlabel("hanging weight W [N]")
    ax.set_ylabel("follower force P [N]")
    ax.legend(loc="upper left", fontsize=7)
    mu = data["mu"]
    right = ax.secondary_yaxis("right", functions=(lambda p: p / mu, lambda R: R * mu))
    right.set_ylabel(rf"contact force R = P/μ [N] (μ = {mu:g})")
    ax.set_title("calibration line: P proportional to W", fontsize=8)


def plot_fig18(data: dict[str, Any]) -> Figure:
    """Fig. 18: top view with the wheel and plate, the calibration line, and the lever's side
    view with its forces to scale."""
    fig = plt.figure(figsize=(11.0, 8.6))
    gs = fig.add_gridspec(2, 2, height_ratios=[1.0, 1.05], width_ratios=[1.15, 1.0])
    ax_top, ax_cal = fig.add_subplot(gs[0, 0]), fig.add_subplot(gs[0, 1])
    ax_side = fig.add_subplot(gs[1, :])
    s = 0.09 / max(data["W_drawn"], data["forces_drawn"]["R"])  # metres per newton
    _top_view(ax_top, data, s)
    _calibration(ax_cal, data)
    _side_view(ax_side, data, s)
    fig.suptitle("Fig. 18: a follower force from sliding friction, and its lever calibration "
                 "W → R → P", fontsize=10)
    note = own_parameters_note(data, "pendulum", "list47")
    fig.tight_layout(rect=(0, 0.03 if note else 0, 1, 1))
    if note:
        fig.text(0.5, 0.005, note, ha="center", va="bottom", fontsize=8)
    return fig
