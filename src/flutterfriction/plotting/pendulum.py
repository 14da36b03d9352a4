"""Drawing of the Ziegler double pendulum (Figs. 2 and 4): rods, hinges, springs, masses, loads."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.patches import Circle, FancyArrowPatch, Polygon

from flutterfriction.plotting.labels import label_at

ROD = "#333333"
MASS = "#1f5fa8"
SPRING = "#b23b3b"


def draw_ground(ax: Axes, at: np.ndarray, size: float, angle: float) -> None:
    """Hatched support under the fixed hinge A, perpendicular to ``angle`` (rad)."""
    t = np.array([np.cos(angle), np.sin(angle)])
    n = np.array([-t[1], t[0]])
    base = at - 0.9 * size * t
    ax.add_patch(Polygon([at, base + size * n, base - size * n], closed=True, fc="white",
                         ec=ROD, lw=1.0, zorder=2))
    for s in np.linspace(-1, 1, 6):
        p = base + s * size * n
        ax.plot(*np.array([p, p - 0.4 * size * (t + 0.6 * n)]).T, color=ROD, lw=0.7)


def _spiral(ax: Axes, at: np.ndarray, size: float, turns: float = 2.2) -> None:
    """A rotational spring drawn as a small spiral around a hinge."""
    th = np.linspace(0.0, 2 * np.pi * turns, 200)
    r = size * (0.35 + 0.65 * th / th[-1])
    ax.plot(at[0] + r * np.cos(th), at[1] + r * np.sin(th), color=SPRING, lw=0.8, zorder=3)


def draw_pendulum(ax: Axes, points: dict[str, Any], masses: dict[str, float],
                  scale: float, *, springs: bool = True, loads: dict[str, float] | None = None,
                  labels: bool | str = False, ground_angle: float = np.pi, offset=(0.0, 0.0),
                  transform=None, arrow_head: float = 10.0, arrow_gap: float = 2.0) -> None:
    """Draw one configuration.

    Parameters
    ----------
    points : dict
        Positions ``A, D, B, E, C`` (each ``[x, y]``), as returned by
        :meth:`~flutterfriction.models.ziegler.ZieglerPendulum.positions`.
    masses : dict
        ``m1, m2, m3`` [kg]; marker areas scale with mass, m3 = 0 is not drawn.
    scale : float
        Drawing size unit (e.g. the rod length), for hinges, springs and arrows.
    loads : dict, optional
        ``{"P": length, "H": length}`` to draw the follower and dead loads at C.
    labels : bool or str, optional
        Name the points (and the loads): True for all, or the names to write (e.g. ``"ABDE"``
        where a figure labels C itself).
    transform : callable, optional
        Maps an (n, 2) array of model coordinates to drawing coordinates (e.g. a rotation).
    """
    tf = (lambda x: np.asarray(x, dtype=float)) if transform is None else transform
    pts = {k: tf(np.asarray(v, dtype=float)) + np.asarray(offset) for k, v in points.items()}
    A, B, C, D, E = (pts[k] for k in "ABCDE")
    draw_ground(ax, A, 0.12 * scale, np.arctan2(*(B - A)[::-1]))
    ax.plot(*np.array([A, B, C]).T, color=ROD, lw=2.0, solid_capstyle="round", zorder=4)
    for hinge in (A, B):
        ax.add_patch(Circle(hinge, 0.035 * scale, fc="white", ec=ROD, lw=1.0, zorder=6))
    if springs:
        _spiral(ax, A, 0.07 * scale)
        _spiral(ax, B, 0.07 * scale)
    mmax = max(masses.values())
    r_C = 0.0  # the drawn radius of the mass at C: the load's arrowhead ends on it
    for key, where in (("m1", D), ("m2", C), ("m3", E)):
        m = masses.get(key, 0.0)
        if m > 0:
            r = max(0.075 * scale * (m / mmax) ** (1 / 3), 0.03 * scale)
            ax.add_patch(Circle(where, r, fc=MASS, ec="black", lw=0.5, zorder=7))
            r_C = r if key == "m2" else r_C
    if loads:
        t = (C - B) / np.linalg.norm(C - B)
        if loads.get("P"):
            # the head touches the mass at C from outside (ending inside it, the head hid the
            # mass in Fig. 4's small frames; a figure review)
            tip = C + r_C * t
            # arrow_head, arrow_gap [points]: in small frames (Fig. 4) a 10-point head and
            # the 2-point gaps left no shaft, a detached triangle (a figure review)
            ax.add_patch(FancyArrowPatch(tip + loads["P"] * t, tip, arrowstyle="-|>",
                                         mutation_scale=arrow_head, color="#c0392b", lw=1.6,
                                         zorder=8, shrinkA=arrow_gap, shrinkB=arrow_gap))
            if labels:
                ax.annotate(r"$\mathbf{P}$", tip + 1.05 * loads["P"] * t, color="#c0392b",
                            ha="center", va="center", fontsize=11)
        if loads.get("H"):
            e1 = tf(np.array([1.0, 0.0])) - tf(np.array([0.0, 0.0]))
            e1 = e1 / np.linalg.norm(e1)
            tip = C + 0.05 * scale * e1
            ax.add_patch(FancyArrowPatch(tip + loads["H"] * e1, tip, arrowstyle="-|>",
                                         mutation_scale=10, color="#7d3c98", lw=1.6, zorder=8))
            if labels:
                ax.annotate(r"$\mathbf{H}$", tip + 1.1 * loads["H"] * e1, color="#7d3c98",
                            ha="center", va="center", fontsize=11)
    if labels:
        n = np.array([-(B - A)[1], (B - A)[0]]) / np.linalg.norm(B - A)
        n2 = np.array([-(C - B)[1], (C - B)[0]]) / np.linalg.norm(C - B)
        names = "ABCDE" if labels is True else labels
        # Points that coincide (D = B for d = l1, E = B for h = 0, as eq. 46's pendulum has)
        # get one label, "B = D": two labels there overlapped (an outside audit's own pendulum)
        shown: list[tuple[list[str], np.ndarray, np.ndarray]] = []
        for name, p, nn in (("A", A, n), ("B", B, n), ("C", C, n2), ("D", D, n), ("E", E, n2)):
            if name not in names:
                continue
            same = next((g for g in shown if np.linalg.norm(g[1] - p) < 0.02 * scale), None)
            if same is None:
                shown.append(([name], p, nn))
            else:
                same[0].append(name)
        for group, p, nn in shown:
            label_at(ax, " = ".join(group), p, 0.13 * scale * nn, ha="center", va="center",
                     fontsize=10)
