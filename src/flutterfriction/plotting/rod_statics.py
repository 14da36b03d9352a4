"""Figs. 6–9 drawn from the computed clamped elastica (scene ``elastica``): the kinematics
(Fig. 6), the internal action at a cut (Fig. 7), the equilibrium of a part under the
distributed load (Fig. 8) and the elastica itself under P1, P2, q1, q2 (Fig. 9). Lengths in mm
on every axis (drawn to scale, equal aspect); force arrows to the scale stated in each legend.
"""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from matplotlib.text import Annotation

from flutterfriction.plotting import list119

MM = 1e3  # m -> mm
ROD = "#222222"
REF = "0.6"
T_COL, M_COL, U_COL = "C0", "C1", "C3"
F_COL, MOM_COL, Q_COL = "C3", "C4", "C2"


def _arrow(ax: Axes, tail, head, color, lw: float = 1.5, ls: str = "-",
           zorder: int = 9) -> None:
    ax.annotate("", tuple(head), tuple(tail),
                arrowprops={"arrowstyle": "-|>", "lw": lw, "color": color, "ls": ls,
                            "shrinkA": 0, "shrinkB": 0, "mutation_scale": 12}, zorder=zorder)


def _moment(ax: Axes, centre, radius: float, positive: bool, color, lw: float = 1.4,
            start: float = 0.0) -> None:
    """A curved arrow of 270 degrees about ``centre``: counterclockwise (``+e3``) when
    ``positive``."""
    sweep = 1.5 * np.pi
    ang = start + (np.linspace(0.0, sweep, 60) if positive else np.linspace(sweep, 0.0, 60))
    pts = np.asarray(centre) + radius * np.column_stack([np.cos(ang), np.sin(ang)])
    ax.plot(*pts[:-3].T, color=color, lw=lw, zorder=9)
    _arrow(ax, pts[-4], pts[-1], color, lw=lw)


def _clamp(ax: Axes, size: float) -> None:
    """The clamp at s = 0 (eq. 96): a hatched wall at x1 = 0."""
    ax.add_patch(Rectangle((-0.35 * size, -size), 0.35 * size, 2 * size, fc="0.85", ec=ROD,
                           lw=0.8, hatch="////", zorder=2))


def _xy(d: dict[str, Any], key: str = "shooting") -> np.ndarray:
    c = d[key]
    return np.column_stack([c["x1"], c["x2"]]) * MM


def _basis(ax: Axes, at, size: float) -> None:
    at = np.asarray(at)
    for v, name in (((1.0, 0.0), r"$\mathbf{e}_1$"), ((0.0, 1.0), r"$\mathbf{e}_2$")):
        _arrow(ax, at, at + size * np.array(v), "k", lw=1.0)
        ax.annotate(name, at + 1.25 * size * np.array(v), ha="center", va="center",
                    fontsize=8)


def _layout(ax: Axes, pts: np.ndarray, l: float, up: bool, box: str, right: float = 1.2,
            handles: list | None = None, labels: list | None = None,
            legend_below: bool = False) -> None:
    """Equal-aspect limits around the drawn points (the clamp on the left), and the legend, the
    text box and the basis on the side the rod leaves free: a rod bending towards ``-e2`` gets
    the legend above the clamp and the box below the rod; ``up`` (towards ``+e2``) mirrors.
    ``legend_below``: a legend too tall for that side goes below the axes, in two columns, and
    the free side keeps only the room of the clamp and the basis."""
    free = 0.17 * l if legend_below else 0.55 * l
    ax.set_aspect("equal")
    ax.set_xlim(-0.12 * l, max(right * l, pts[:, 0].max() + 0.1 * l))
    band = 0.3 * l if box else 0.2 * l  # the box's own band beyond everything drawn
    if up:
        ax.set_ylim(-free, max(pts[:, 1].max(), 0.1 * l) + band)
    else:
        ax.set_ylim(min(pts[:, 1].min(), -0.1 * l) - band, free)
    if legend_below:  # 0.55 in below the axes: clear of the ticks and the x label
        ax.apply_aspect()
        h = ax.get_position().height * ax.figure.get_figheight()
        ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, -0.55 / h), ncol=2,
                  fontsize=7.5, framealpha=0.9)
    else:
        ax.legend(handles, labels, loc="lower right" if up else "upper right", fontsize=7.5,
                  framealpha=0.9)
    if box:
        _box(ax, box, loc=(0.02, 0.98) if up else (0.02, 0.02), va="top" if up else "bottom")
    # the basis where it is farthest from everything drawn (and every label, which may extend
    # ~0.15 l either side of its anchor), on the free side of the rod
    anchors = []
    for tx in ax.texts:
        if isinstance(tx, Annotation):
            anchors.append(tx.xy)
            if tx.anncoords == "data":
                anchors.append(tx.xyann)
    pts = np.vstack([pts, *(np.asarray(a) + np.array([dx * l, 0.0]) for a in anchors
                            for dx in (-0.15, 0.0, 0.15))])
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    ax.apply_aspect()  # the legend's extent in data units, as it will be drawn
    leg = ax.get_legend().get_window_extent(ax.figure.canvas.get_renderer())
    (lx0, ly0), (lx1, ly1) = ax.transData.inverted().transform(leg.get_points())
    # (the basis reaches 0.1 l above its anchor: below the box's band when the box is on top)
    lo, hi = (y0 + 0.1 * l, y1 - band - 0.12 * l) if up else (y0 + band, y1 - 0.15 * l)
    cands = [np.array([x, y]) for x in np.linspace(x0 + 0.1 * l, x1 - 0.2 * l, 9)
             for y in np.linspace(lo, hi, 9)
             if not (lx0 - 0.2 * l < x < lx1 and ly0 - 0.15 * l < y < ly1 + 0.05 * l)]
    best = max(cands, key=lambda c: np.min(np.linalg.norm(pts - c - 0.035 * l, axis=1)))
    _basis(ax, best, 0.07 * l)


def _seg_dist(p0, p1, q0, q1) -> float:
    """The least distance between the segments ``p0 p1`` and ``q0 q1`` (sampled finely)."""
    u = np.linspace(0.0, 1.0, 41)[:, None]
    a = np.asarray(p0) + u * (np.asarray(p1) - np.asarray(p0))
    b = np.asarray(q0) + u * (np.asarray(q1) - np.asarray(q0))
    return float(np.min(np.linalg.norm(a[:, None] - b[None], axis=2)))


def _free_direction(avoid) -> np.ndarray:
    """Of the eight compass directions, the one farthest in angle from every direction in
    ``avoid`` (arrows and the rod at a point): where a label next to that point goes."""
    dirs = [np.array([np.cos(a), np.sin(a)]) for a in np.arange(8) * np.pi / 4]
    unit = [v / np.linalg.norm(v) for v in map(np.asarray, avoid) if np.linalg.norm(v) > 0]
    return max(dirs, key=lambda d: min((np.arccos(np.clip(d @ u, -1, 1)) for u in unit),
                                       default=np.pi))


def _loads_text(loads: dict[str, float]) -> str:
    return (f"P1 = {loads['P1']:g} N, P2 = {loads['P2']:g} N, q1 = {loads['q1']:g} N/m, "
            f"q2 = {loads['q2']:g} N/m")


#: Said on each of Figs. 6-9: the chapter draws these rods without numbers.
OUR_LOADS = "(our loads: the chapter gives none)"


def _box(ax: Axes, text: str, loc=(0.02, 0.02), va: str = "bottom") -> None:
    ax.text(*loc, text, transform=ax.transAxes, fontsize=7.5, va=va, ha="left",
            bbox={"fc": "white", "ec": "0.7", "alpha": 0.9, "boxstyle": "round,pad=0.3"},
            zorder=20)


# ---------------------------------------------------------------------- Fig. 6
def plot_fig06(data: dict[str, Any]) -> Figure:
    """Fig. 6: the kinematics of the inextensible rod, drawn on the computed elastica: the
    reference point ``x0 e1``, its image ``x = g(x0)``, the displacement ``u(x0)`` (eq. 55), the
    tangent ``t`` and the unit vector ``m`` (eqs. 63, 71), the rotation ``theta(s)`` (eq. 64) and
    the arc length ``s = x0``; beside it, ``u1, u2`` and ``theta`` along the rod."""
    l = data["rod"]["length"] * MM
    s = np.array(data["s"]) * MM
    x = _xy(data)
    pt = data["point"]
    s0, X = pt["s"] * MM, np.array(pt["x"]) * MM
    fig = plt.figure(figsize=(11.0, 5.6))
    gs = fig.add_gridspec(2, 2, width_ratios=[1.55, 1.0], hspace=0.35, wspace=0.22)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.09, top=0.9)
    ax = fig.add_subplot(gs[:, 0])
    _clamp(ax, 0.08 * l)
    ax.plot([0, l], [0, 0], color=REF, lw=1.4, ls="--", label="reference configuration "
            r"(straight, along $\mathbf{e}_1$)")
    ax.plot(*x.T, color=ROD, lw=2.2, label="deformed rod (computed elastica of Fig. 9)")
    arc = s <= s0 + 1e-9
    ax.plot(*x[arc].T, color=Q_COL, lw=6, alpha=0.3, solid_capstyle="butt",
            label=r"arc length $s$ from the clamp: $s = x_0$ (inextensible)")
    ax.plot([s0], [0.0], "o", color=U_COL, ms=5, zorder=10)
    ax.plot(*X, "o", color=U_COL, ms=5, zorder=10)
    ax.annotate(r"$x_0\mathbf{e}_1$", (s0, 0.0), xytext=(4, 6), textcoords="offset points",
                fontsize=9)
    _arrow(ax, (s0, 0.0), X, U_COL, lw=1.6)
    mid = 0.5 * (np.array([s0, 0.0]) + X)
    ax.annotate(r"$\mathbf{u}(x_0)$", mid, xytext=(6, 0), textcoords="offset points",
                color=U_COL, fontsize=9)
    L = 0.16 * l
    t, m, n = (np.array(pt[k]) for k in ("t", "m", "n"))
    up = bool(x[-1, 1] > 0)
    # the label of x between the incoming rod (-t) and n (the concave side), where no arrow is
    # drawn
    side = n if np.any(n) else m
    w = (side - t) / np.linalg.norm(side - t)
    ax.annotate(r"$\mathbf{x} = \mathbf{g}(x_0)$", X, xytext=X + 0.3 * l * w, fontsize=9,
                ha="right" if w[0] < 0 else "left", va="top" if w[1] < 0 else "bottom",
                arrowprops={"arrowstyle": "-", "lw": 0.6, "color": "0.4", "shrinkB": 4})
    # t lies along the rod: drawn above it (wider) and named beside its head, on the side
    # towards m, inside the right angle of t and m (theta is drawn on the other side; the rod
    # itself runs on through the head)
    _arrow(ax, X, X + L * t, T_COL, lw=2.4, zorder=12)
    ax.annotate(r"$\mathbf{t}$", X + 0.9 * L * t, xytext=9 * m, textcoords="offset points",
                color=T_COL, fontsize=10, ha="right" if m[0] < 0 else "left",
                va="top" if m[1] < 0 else "bottom", zorder=12)
    _arrow(ax, X, X + L * m, M_COL, lw=1.8)
    same = np.allclose(m, n)
    ax.annotate(r"$\mathbf{m} = \mathbf{n}$" if same else r"$\mathbf{m}$",
                X + 1.2 * L * m, color=M_COL, fontsize=10, ha="center", va="center")
    if not same:
        _arrow(ax, X, X + L * n, M_COL, lw=1.2, ls="--")
        ax.annotate(r"$\mathbf{n}$", X + 1.2 * L * n, color=M_COL, fontsize=10)
    # the rotation theta: from e1 to t
    r = 0.09 * l
    ax.plot([X[0], X[0] + 1.3 * r], [X[1], X[1]], color="0.3", lw=0.8, ls=":")
    ang = np.linspace(0.0, pt["theta"], 40)
    ax.plot(X[0] + r * np.cos(ang), X[1] + r * np.sin(ang), color="0.2", lw=1.0)
    th = pt["theta"]
    if abs(th) > np.radians(30):  # inside the angle's arc
        at, off, va = X + 1.05 * r * np.array([np.cos(0.5 * th), np.sin(0.5 * th)]), (6, -2), \
            "center"
    else:  # a narrow angle: beyond the dotted e1 line, on the side away from t
        at, off, va = X + np.array([1.3 * r, 0.0]), (4, 4 if th < 0 else -4), \
            "bottom" if th < 0 else "top"
    ax.annotate(rf"$\theta(s)$ = {np.degrees(th):.1f}°", at, xytext=off,
                textcoords="offset points", fontsize=8, va=va)
    handles, labels = ax.get_legend_handles_labels()
    handles += [Line2D([], [], color=U_COL, lw=1.6, marker=">", ms=5),
                Line2D([], [], color=T_COL, lw=1.8, marker=">", ms=5),
                Line2D([], [], color=M_COL, lw=1.8, marker=">", ms=5)]
    labels += [r"displacement $\mathbf{u} = \mathbf{x} - x_0\mathbf{e}_1$ (eq. 55)",
               r"unit tangent $\mathbf{t} = \cos\theta\,\mathbf{e}_1 + \sin\theta\,"
               r"\mathbf{e}_2$ (eqs. 63-64)",
               r"$\mathbf{m} = \sin\theta\,\mathbf{e}_1 - \cos\theta\,\mathbf{e}_2$ (eq. 71)"
               + (r"; $\mathbf{n} = \mathbf{m}$ as $\theta' < 0$ (eq. 69)" if same else "")]
    if not same:
        handles.append(Line2D([], [], color=M_COL, lw=1.2, ls="--"))
        labels.append(r"normal $\mathbf{n} = \mathrm{sgn}(\theta')(-\sin\theta\,\mathbf{e}_1"
                      r" + \cos\theta\,\mathbf{e}_2) = -\mathbf{m}$ here (eq. 69)")
    pr = data["point"]["projections"]
    box = (f"eq. (65): d = ∫cos θ ds = {pr['d'] * MM:.3f} mm = l + u1(l) "
             f"(to {abs(pr['d'] - pr['d_positions']) / l * MM:.0e} l)\n"
             f"eq. (66): h = ∫sin θ ds = {pr['h'] * MM:.3f} mm = u2(l) "
             f"(to {abs(pr['h'] - pr['h_positions']) / l * MM:.0e} l)\n"
             f"curve's length from its positions: "
             f"{data['point']['length_from_positions'] * MM:.9f} mm = l")
    drawn = np.vstack([x, np.column_stack([s, 0.0 * s]), X + L * t, X + L * m, X + 0.3 * l * w])
    _layout(ax, drawn, l, up, box, right=1.08, handles=handles, labels=labels)
    ax.set_xlabel(r"$x_1$ [mm]")
    ax.set_ylabel(r"$x_2$ [mm]")
    ax.set_title(f"Kinematics on the computed rod (l = {l:g} mm; {_loads_text(data['loads'])})",
                 fontsize=8.5)
    # u1, u2 and theta against s
    c = data["shooting"]
    u1 = (np.array(c["x1"]) * MM - s)
    u2 = np.array(c["x2"]) * MM
    ax1 = fig.add_subplot(gs[0, 1])
    ax1.plot(s, u1, color="C0", label=r"$u_1 = x_1 - x_0$")
    ax1.plot(s, u2, color="C1", label=r"$u_2 = x_2$")
    ax1.axvline(s0, color=U_COL, lw=0.8, ls=":", label=r"the point $x_0$")
    ax1.set_xlabel(r"$s = x_0$ [mm]")
    ax1.set_ylabel("displacement [mm]")
    ax1.legend(fontsize=7.5, loc="best")
    ax1.set_title("Displacement along the rod (eq. 55)", fontsize=8.5)
    ax2 = fig.add_subplot(gs[1, 1])
    ax2.plot(s, c["theta"], color="C2", label=r"rotation $\theta(s)$")
    ax2.axvline(s0, color=U_COL, lw=0.8, ls=":", label=r"the point $x_0$")
    ax2.set_xlabel(r"$s = x_0$ [mm]")
    ax2.set_ylabel(r"$\theta$ [rad]")
    ax2.legend(fontsize=7.5, loc="best")
    ax2.set_title(r"Rotation of the tangent, $\sin\theta = u_2'$, $\cos\theta = 1 + u_1'$ "
                  "(eq. 64)", fontsize=8.5)
    fig.suptitle("Fig. 6: the kinematics of an inextensible rod (reference straight, "
                 r"$s = x_0$) " + OUR_LOADS, fontsize=10)
    return fig


# ---------------------------------------------------------------------- Fig. 7
def plot_fig07(data: dict[str, Any]) -> Figure:
    """Fig. 7: the rod cut at ``s`` (the two parts drawn apart along ``t``), the action
    ``a(s), M(s)`` on the left part and ``-a(s), -M(s)`` on the right (action-reaction), the unit
    vectors ``t`` and ``m``; right: ``M = B theta'`` along the rod against the moment of the
    loads beyond each cut (eq. 89)."""
    l = data["rod"]["length"] * MM
    s = np.array(data["s"]) * MM
    x = _xy(data)
    cut = data["cut"]
    sc, X = cut["s"] * MM, np.array(cut["x"]) * MM
    t, m = np.array(cut["t"]), np.array(cut["m"])
    a = np.array(cut["a"])
    gap = 0.25 * l
    fs = 0.2 * l / np.linalg.norm(a)  # mm per N
    left, right = s <= sc, s >= sc
    fig = plt.figure(figsize=(11.0, 5.4))
    gs = fig.add_gridspec(1, 2, width_ratios=[1.5, 1.0], wspace=0.22)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.1, top=0.9)
    ax = fig.add_subplot(gs[0, 0])
    _clamp(ax, 0.08 * l)
    ax.plot(*x[left].T, color=ROD, lw=2.4, label=r"left part $[0, s]$ (clamped)")
    xr = x[right] + gap * t
    ax.plot(*xr.T, color="0.45", lw=2.4,
            label=f"right part $[s, l]$, drawn {gap:.0f} mm apart along " r"$\mathbf{t}$")
    Xr = X + gap * t
    # on the left part (t exiting it): a(s), M(s); on the right part: -a(s), -M(s)
    _arrow(ax, X, X + fs * a, F_COL, lw=2.0)
    ax.annotate(r"$\mathbf{a}(s)$", X + fs * a, xytext=(4, -10), textcoords="offset points",
                color=F_COL, fontsize=10)
    _arrow(ax, Xr, Xr - fs * a, F_COL, lw=2.0)
    ax.annotate(r"$-\mathbf{a}(s)$", Xr - fs * a, xytext=(6, 0), textcoords="offset points",
                color=F_COL, fontsize=10, ha="left", va="center")
    rm = 0.06 * l
    pos = cut["M"] > 0
    _moment(ax, X, rm, pos, MOM_COL, start=np.pi / 2)
    ax.annotate(r"$\mathcal{M}(s)$", X + rm * np.array([-1.0, 1.0]), xytext=(-8, 4),
                textcoords="offset points", color=MOM_COL, fontsize=10, ha="right")
    _moment(ax, Xr, rm, not pos, MOM_COL, start=np.pi / 2)
    ax.annotate(r"$-\mathcal{M}(s)$", Xr + rm * np.array([1.0, -1.0]), xytext=(4, -4),
                textcoords="offset points", color=MOM_COL, fontsize=10, va="top")
    L = 0.13 * l
    for v, name, col in ((t, r"$\mathbf{t}$", T_COL), (m, r"$\mathbf{m}$", M_COL)):
        _arrow(ax, X, X + L * v, col, lw=1.4)
        ax.annotate(name, X + 1.25 * L * v, color=col, fontsize=10, ha="center", va="center")
    handles, labels = ax.get_legend_handles_labels()
    handles += [Line2D([], [], color=F_COL, lw=2.0, marker=">", ms=5),
                Line2D([], [], color=MOM_COL, lw=1.4, marker=">", ms=5),
                Line2D([], [], color=T_COL, lw=1.4, marker=">", ms=5),
                Line2D([], [], color=M_COL, lw=1.4, marker=">", ms=5)]
    labels += [f"internal force (arrows: {fs:.3g} mm per N)",
               "internal moment (counterclockwise: +e3)",
               r"tangent $\mathbf{t}$ (exits the left part)",
               r"$\mathbf{m}$ (eq. 71)"]
    a1, a2 = a
    box = (f"cut at s = {sc:.1f} mm = {cut['s'] / data['rod']['length']:.2f} l\n"
           f"a = ({a1:+.4f}, {a2:+.4f}) N, N = {cut['N']:+.4f} N, T = {cut['T']:+.4f} N\n"
           f"M = Bθ' = {cut['M']:+.6f} N m (eq. 83)\n"
           f"eq. (89): {cut['M_eq89']:+.6f} N m (relative difference "
           f"{abs(cut['M'] - cut['M_eq89']) / abs(cut['M']):.0e})")
    _layout(ax, np.vstack([x[left], xr, X + fs * a, Xr - fs * a, X + L * t, X + L * m]), l,
            x[-1, 1] > 0, box, handles=handles, labels=labels)
    ax.set_xlabel(r"$x_1$ [mm]")
    ax.set_ylabel(r"$x_2$ [mm]")
    ax.set_title(f"The internal action at a cut of the computed rod ({_loads_text(data['loads'])})",
                 fontsize=8.5)
    ax2 = fig.add_subplot(gs[0, 1])
    ax2.plot(s, data["shooting"]["M"], color=MOM_COL, lw=1.8,
             label=r"$\mathcal{M} = B\theta'$ (solution, eq. 83)")
    e89 = cut["eq89_along"]
    ax2.plot(np.array(e89["s"]) * MM, e89["M"], "o", mfc="none", color="k", ms=6,
             label="moment of the loads beyond the cut (eq. 89)")
    ax2.axvline(sc, color="0.4", lw=0.8, ls=":", label="the cut drawn left")
    ax2.set_xlabel(r"arc length $s$ [mm]")
    ax2.set_ylabel(r"bending moment $\mathcal{M}$ [N m]")
    ax2.legend(fontsize=7.5, loc="best")
    ax2.set_title("Moment at every cut: constitutive against equilibrium", fontsize=8.5)
    fig.suptitle(r"Fig. 7: action $\mathbf{a}(s)$, $\mathcal{M}(s)$ and reaction "
                 r"$-\mathbf{a}(s)$, $-\mathcal{M}(s)$ at an ideal cut of a deformed rod "
                 + OUR_LOADS, fontsize=10)
    return fig


# ---------------------------------------------------------------------- Fig. 8
def plot_fig08(data: dict[str, Any]) -> Figure:
    """Fig. 8: the part ``[s1, s2]`` of the computed rod as a free body: the distributed load
    ``q`` along it, ``a(s2), M(s2)`` at its end and ``-a(s1), -M(s1)`` at its start (eq. 74);
    right: ``N, T`` and ``M`` along the rod, the part shaded (eqs. 81, 87)."""
    l = data["rod"]["length"] * MM
    s = np.array(data["s"]) * MM
    x = _xy(data)
    part = data["part"]
    xp = np.array(part["x"]) * MM
    e1, e2 = part["ends"]
    q = np.array(part["q"])
    forces = np.array([e1["a"], e2["a"]])
    fs = 0.28 * l / np.max(np.linalg.norm(forces, axis=1))  # mm per N
    qs = 0.1 * l / max(np.linalg.norm(q), 1e-300)  # mm per N/m (no arrows when q = 0)
    fig = plt.figure(figsize=(11.0, 5.6))
    gs = fig.add_gridspec(2, 2, width_ratios=[1.5, 1.0], hspace=0.35, wspace=0.22)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.09, top=0.9)
    ax = fig.add_subplot(gs[:, 0])
    ax.plot(*x.T, color="0.8", lw=1.6, label="the rest of the rod")
    ax.plot(*xp.T, color=ROD, lw=2.6, label=rf"the part $[s_1, s_2]$ = [{part['s1'] * MM:.0f},"
            rf" {part['s2'] * MM:.0f}] mm")
    # q along the part, with a gap at its ends: clear of the actions drawn there
    idx = np.linspace(0.2 * (len(xp) - 1), 0.7 * (len(xp) - 1), 5).round().astype(int)
    for i in idx if np.any(q) else []:
        _arrow(ax, xp[i], xp[i] + qs * q, Q_COL, lw=1.2)
    X1, X2 = np.array(e1["x"]) * MM, np.array(e2["x"]) * MM
    a1, a2 = np.array(e1["a"]), np.array(e2["a"])
    _arrow(ax, X2, X2 + fs * a2, F_COL, lw=2.0)
    ax.annotate(r"$\mathbf{a}(s_2)$", X2 + fs * a2, xytext=(4, -4), textcoords="offset points",
                color=F_COL, fontsize=10)
    _arrow(ax, X1, X1 - fs * a1, F_COL, lw=2.0)
    ax.annotate(r"$-\mathbf{a}(s_1)$", X1 - fs * a1, xytext=(-4, 4), textcoords="offset points",
                color=F_COL, fontsize=10, ha="right")
    rm = 0.05 * l
    t1, t2 = (np.array([np.cos(e["theta"]), np.sin(e["theta"])]) for e in (e1, e2))
    for X, sign, name, avoid in ((X2, 1, r"$\mathcal{M}(s_2)$", (a2, q, t2, -t2, X1 - X2)),
                                 (X1, -1, r"$-\mathcal{M}(s_1)$", (-a1, q, t1, -t1))):
        positive = (sign * (e2 if sign > 0 else e1)["M"]) > 0
        start = np.pi if sign > 0 else np.pi / 2
        _moment(ax, X, rm, positive, MOM_COL, start=start)
        head = start + (1.5 * np.pi if positive else 0.0)  # where the moment's arrowhead is
        d = _free_direction((*avoid, (np.cos(head), np.sin(head))))
        ax.annotate(name, X + 1.2 * rm * d, xytext=6 * d, textcoords="offset points",
                    color=MOM_COL, fontsize=10, ha="left" if d[0] > 0.3 else
                    ("right" if d[0] < -0.3 else "center"),
                    va="bottom" if d[1] > 0.3 else ("top" if d[1] < -0.3 else "center"))
    for X in (X1, X2):  # the ends s1, s2 (named by the labels of their actions)
        ax.plot(*X, "o", color=ROD, ms=4, zorder=10)
    if np.any(q):
        # before the first arrow's head (back towards s1), clear of the others
        tq = xp[idx[0] + 1] - xp[idx[0]]
        tq = -tq / np.linalg.norm(tq)
        ax.annotate(r"$\mathbf{q}$", xp[idx[0]] + qs * q, xytext=8 * tq,
                    textcoords="offset points", color=Q_COL, fontsize=10,
                    ha="right" if tq[0] < 0 else "left", va="center")
    handles, labels = ax.get_legend_handles_labels()
    handles += [Line2D([], [], color=Q_COL, lw=1.2, marker=">", ms=5),
                Line2D([], [], color=F_COL, lw=2.0, marker=">", ms=5),
                Line2D([], [], color=MOM_COL, lw=1.4, marker=">", ms=5)]
    # both scales in mm, as the axes (the load's was in m: two units for one length)
    labels += [f"q = ({q[0]:g}, {q[1]:g}) N/m (arrows: {qs:.3g} mm per N/m)",
               f"internal force on the part (arrows: {fs:.3g} mm per N)",
               "internal moment on the part (counterclockwise: +e3)"]
    b = part["balances"]
    box = ("equilibrium of the part, residual / largest term:\n"
             f"eq. (74)1, forces: {b['force']:.0e}\neq. (74)2, moments about O: "
             f"{b['moment']:.0e}\n"
             r"eq. (87), $[\mathcal{N} + \mathcal{M}^2/(2B)] + "
             r"\int \mathbf{q}\cdot\mathbf{t}\,ds$: " f"{b['eq87']:.0e}")
    _layout(ax, np.vstack([x, X2 + fs * a2, X1 - fs * a1, xp[idx] + qs * q]), l,
            x[-1, 1] > 0, box, handles=handles, labels=labels)
    ax.set_xlabel(r"$x_1$ [mm]")
    ax.set_ylabel(r"$x_2$ [mm]")
    ax.set_title(f"A part of the computed rod as a free body ({_loads_text(data['loads'])})",
                 fontsize=8.5)
    c = data["shooting"]
    ax1 = fig.add_subplot(gs[0, 1])
    ax1.plot(s, c["N"], color="C0", label=r"normal force $\mathcal{N} = \mathbf{a}\cdot"
             r"\mathbf{t}$")
    ax1.plot(s, c["T"], color="C1", label=r"shear force $\mathcal{T} = \mathbf{a}\cdot"
             r"\mathbf{m}$")
    ax1.axvspan(part["s1"] * MM, part["s2"] * MM, color="0.9", label="the part")
    ax1.set_xlabel(r"arc length $s$ [mm]")
    ax1.set_ylabel("force [N]")
    ax1.legend(fontsize=7.5, loc="best")
    ax1.set_title("Internal force (eqs. 73, 77)", fontsize=8.5)
    ax2 = fig.add_subplot(gs[1, 1])
    ax2.plot(s, c["M"], color=MOM_COL, label=r"$\mathcal{M}$, $\mathcal{M}' = \mathcal{T}$ "
             "(eq. 80)")
    ax2.axvspan(part["s1"] * MM, part["s2"] * MM, color="0.9", label="the part")
    ax2.set_xlabel(r"arc length $s$ [mm]")
    ax2.set_ylabel(r"moment $\mathcal{M}$ [N m]")
    ax2.legend(fontsize=7.5, loc="best")
    ax2.set_title("Internal moment", fontsize=8.5)
    fig.suptitle(r"Fig. 8: equilibrium of a part of a deformed rod under the distributed "
                 r"load $\mathbf{q}$ (eq. 74) " + OUR_LOADS, fontsize=10)
    return fig


# ---------------------------------------------------------------------- Fig. 9
def plot_fig09(data: dict[str, Any]) -> Figure:
    """Fig. 9: the clamped elastica under ``-P1 e1``, ``-P2 e2`` at the end and ``q1, q2`` per
    unit length (shooting; collocation as markers), the end forces alone (shooting; the
    elliptic-integral closed form as markers); right: the small-load limit against the linear
    cantilever."""
    l = data["rod"]["length"] * MM
    loads = data["loads"]
    x = _xy(data)
    xc = _xy(data, "collocation")
    tip = data["tip_forces_only"]
    xt = np.column_stack([tip["x1"], tip["x2"]]) * MM
    xtc = np.column_stack([tip["x1_closed"], tip["x2_closed"]]) * MM
    fig = plt.figure(figsize=(11.0, 6.2))
    gs = fig.add_gridspec(1, 2, width_ratios=[1.5, 1.0], wspace=0.24)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.24, top=0.88)  # the legend below
    ax = fig.add_subplot(gs[0, 0])
    _clamp(ax, 0.08 * l)
    ax.plot([0, l], [0, 0], color=REF, lw=1.4, ls="--", label="straight reference rod")
    ax.plot(*x.T, color=ROD, lw=2.4, label="P1, P2, q1, q2: shooting (eq. 91)")
    k = max(1, len(x) // 12)
    ax.plot(*xc[k // 2::k].T, "s", ms=4, mfc="none", color=ROD, mew=0.8,
            label="the same by collocation")
    ax.plot(*xt.T, color="C0", lw=1.6, label="P1, P2 only (q = 0): shooting")
    ax.plot(*xtc[k // 2::k].T, "o", ms=4, mfc="none", color="C0",
            label="P1, P2 only: elliptic integrals (closed form)")
    # the loads: -P1 e1 and -P2 e2 at the end, q1 e1 + q2 e2 along the rod (dead loads)
    fs = 0.2 * l / max(abs(loads["P1"]), abs(loads["P2"]))  # mm per N
    X = x[-1]
    for vec, name in (((-loads["P1"], 0.0), rf"$P_1$ = {loads['P1']:g} N"),
                      ((0.0, -loads["P2"]), rf"$P_2$ = {loads['P2']:g} N")):
        v = np.array(vec)
        if not np.any(v):
            continue
        _arrow(ax, X, X + fs * v, F_COL, lw=2.0)
        # P2 beside its arrow, P1 beyond its head (clear of the rod)
        ax.annotate(name, X + (0.6 if v[1] else 1.0) * fs * v, xytext=(6, 0) if v[1] else
                    (-4, 0), textcoords="offset points", color=F_COL, fontsize=9,
                    ha="left" if v[1] else "right", va="center")
    qv = np.array([loads["q1"], loads["q2"]])
    qs = 0.12 * l / max(np.max(np.abs(qv)), 1e-300)  # mm per N/m (no arrows when q = 0)
    idx = np.linspace(0, len(x) - 1, 10).round().astype(int)[1:-1]
    # no q arrow (nor its head) within 0.05 l of the end forces' arrows
    ends = [(X, X + fs * np.array(v)) for v in ((-loads["P1"], 0.0), (0.0, -loads["P2"]))]
    idx = np.array([i for i in idx if min(
        _seg_dist(x[i], x[i] + qs * qv * e, *seg) for e in ((1, 0), (0, 1)) for seg in ends)
        > 0.05 * l], dtype=int)
    for i in idx:
        for comp, col in ((0, Q_COL), (1, "C5")):
            v = np.zeros(2)
            v[comp] = qv[comp]
            if v[comp]:
                _arrow(ax, x[i], x[i] + qs * v, col, lw=1.1)
    # the labels where the rod leaves room: q2 near the clamp (rod flat), q1 near the end
    if qv[0]:
        head = x[idx[-1]] + qs * np.array([qv[0], 0.0])
        ax.annotate(r"$q_1$", head, xytext=(-6 if qv[0] < 0 else 6, 0),
                    textcoords="offset points", color=Q_COL, fontsize=10,
                    ha="right" if qv[0] < 0 else "left", va="center")
    if qv[1]:
        head = x[idx[0]] + qs * np.array([0.0, qv[1]])
        ax.annotate(r"$q_2$", head, xytext=(0, -6 if qv[1] < 0 else 6),
                    textcoords="offset points", color="C5", fontsize=10, ha="center",
                    va="top" if qv[1] < 0 else "bottom")
    handles, labels = ax.get_legend_handles_labels()
    handles += [Line2D([], [], color=F_COL, lw=2.0, marker=">", ms=5),
                Line2D([], [], color=Q_COL, lw=1.1, marker=">", ms=5),
                Line2D([], [], color="C5", lw=1.1, marker=">", ms=5)]
    labels += [rf"end force $\mathbf{{P}} = -P_1\mathbf{{e}}_1 - P_2\mathbf{{e}}_2$ "
               f"({fs:.3g} mm per N)",
               rf"$q_1\mathbf{{e}}_1$ per unit length, $q_1$ = {loads['q1']:g} N/m "
               f"({qs:.3g} mm per N/m)",
               rf"$q_2\mathbf{{e}}_2$ per unit length, $q_2$ = {loads['q2']:g} N/m "
               f"({qs:.3g} mm per N/m)"]
    qd = data["quantities"]
    u = (qd["tip_shortening"]["value"] * MM, qd["tip_deflection"]["value"] * MM)
    rel = abs(qd["tip_deflection"]["value"] / qd["tip_deflection"]["independent"] - 1)
    box = (f"end: u = ({u[0]:.2f}, {u[1]:.2f}) mm,\n"
           f"θ(l) = {np.degrees(data['tip_rotation']):.2f}°; collocation: {rel:.0e}\n"
           f"q = 0: θ(l) = {np.degrees(tip['tip_rotation']):.2f}°; against the\n"
           f"closed form: {tip['curve_error']:.0e} l along the rod")
    heads = [X + fs * np.array([-loads["P1"], 0.0]), X + fs * np.array([0.0, -loads["P2"]])]
    # the P2 label's extent beside its arrow
    heads += [X + 0.6 * fs * np.array([0.0, -loads["P2"]]) + np.array([d * l, 0.0])
              for d in (0.1, 0.2, 0.3)]
    heads += [x[i] + qs * np.array(v) for i in idx for v in ((qv[0], 0.0), (0.0, qv[1]))]
    _layout(ax, np.vstack([x, xt, *heads]), l, x[-1, 1] > 0, box, right=1.25,
            handles=handles, labels=labels, legend_below=True)
    ax.set_xlabel(r"$x_1$ [mm]")
    ax.set_ylabel(r"$x_2$ [mm]")
    ax.set_title(f"The clamped elastica, l = {l:g} mm, B = {data['rod']['B']:g} N m² "
                 f"({list119(data, 'list 119')})", fontsize=8.5)
    # small loads
    lim = data["linear_limit"]
    pts = lim["points"]
    e = np.array([p["factor"] for p in pts])
    ax2 = fig.add_subplot(gs[0, 1])
    ax2.loglog(e, np.abs([p["rel_shooting"] for p in pts]), "o", color="k", ms=6,
               label="geometrically exact: shooting")
    ax2.loglog(e, np.abs([p["rel_collocation"] for p in pts]), "x", color="C3", ms=7,
               label="geometrically exact: collocation")
    ee = np.geomspace(e.min(), e.max(), 50)
    ax2.loglog(ee, abs(lim["coefficient"]) * ee**2, color="C0", lw=1.0,
               label=rf"third-order perturbation: $|c|\,\epsilon^2$, c = {lim['coefficient']:.4f}")
    ax2.set_xlabel(r"load factor $\epsilon$ (loads $\epsilon P_2$, $\epsilon q_2$; "
                   r"$P_1 = q_1 = 0$) [-]")
    ax2.set_ylabel(r"$|u_2(l)/u_2^{\rm lin}(l) - 1|$ [-]")
    ax2.legend(fontsize=7.5, loc="upper left")
    ax2.set_title("Small loads: the linear cantilever\n"
                  r"$u_2^{\rm lin}(l) = -P_2 l^3/(3B) + q_2 l^4/(8B)$; "
                  f"measured order {lim['order']:.4f}", fontsize=8.5)
    fig.suptitle("Fig. 9: the clamped elastica under the end forces P1, P2 and the forces "
                 "per unit length q1, q2 (geometrically exact) " + OUR_LOADS, fontsize=10)
    return fig
