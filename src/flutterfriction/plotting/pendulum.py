"""Drawing of the Ziegler double pendulum (Figs. 2 and 4): rods, hinges, springs, masses, loads."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.patches import Circle, FancyArrowPatch, Polygon
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox

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
                  transform=None) -> None:
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
    for key, where in (("m1", D), ("m2", C), ("m3", E)):
        m = masses.get(key, 0.0)
        if m > 0:
            r = 0.075 * scale * (m / mmax) ** (1 / 3)
            ax.add_patch(Circle(where, max(r, 0.03 * scale), fc=MASS, ec="black", lw=0.5,
                                zorder=7))
    if loads:
        t = (C - B) / np.linalg.norm(C - B)
        if loads.get("P"):
            tip = C - 0.05 * scale * t
            ax.add_patch(FancyArrowPatch(tip + loads["P"] * t, tip, arrowstyle="-|>",
                                         mutation_scale=10, color="#c0392b", lw=1.6, zorder=8))
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


def label_at(ax: Axes, text: str, anchor, offset, points: bool = False, **kwargs):
    """``ax.annotate(text, anchor + offset)``, remembering the anchor: :func:`declutter` may
    move the label around it. ``points``: ``offset`` in points from ``anchor`` (in data
    coordinates), for a label beside a point whatever the axes' scales."""
    anchor = np.asarray(anchor, dtype=float)
    offset = np.asarray(offset, dtype=float)
    if points:  # positions in points from the anchor: the origin of the label's coordinates
        t = ax.annotate(text, tuple(anchor), xytext=tuple(offset), textcoords="offset points",
                        **kwargs)
        t.anchor = (np.zeros(2), float(np.linalg.norm(offset)), tuple(offset))
        return t
    first = anchor + offset
    t = ax.annotate(text, first, **kwargs)
    t.anchor = (anchor, float(np.linalg.norm(offset)), tuple(first))
    return t


def declutter(ax: Axes, pad: float = 1.25) -> None:
    """Keep the labels placed by :func:`label_at` on ``ax`` clear of each other, of its other
    texts and of its legend: at every draw, after the layout engine and the aspect have set
    the axes' final size, each label that overlaps one of them (boxes grown by ``pad``) moves
    to the first of 24 directions around its anchor, at 1, 1.6 or 2.3 times its distance,
    where it overlaps nothing and stays inside the axes (else it stays: the figure check then
    names it). A sketch of one's own pendulum puts its points where the chapter's labels did
    not expect them (outside audits: B under D, m1 under alpha1, B under the wheel's note)."""
    ax.add_artist(_Declutter(ax, pad))


class _Declutter(Artist):
    """Drawn first among the axes' children (:func:`declutter`): it draws nothing, it moves."""

    def __init__(self, ax: Axes, pad: float) -> None:
        super().__init__()
        self._ax, self._pad = ax, pad
        self.set_zorder(-1e9)

    def get_window_extent(self, renderer=None):
        return Bbox.null()

    def get_tightbbox(self, renderer=None):
        return None

    def draw(self, renderer) -> None:
        ax, pad = self._ax, self._pad
        frame = ax.get_window_extent(renderer)

        def box(t):
            # the text alone, as the figure check measures it (an annotation's own extent
            # also holds its arrow)
            return Text.get_window_extent(t, renderer).expanded(pad, pad)

        def clear(t) -> bool:
            b = box(t)
            inside = (frame.x0 <= b.x0 and b.x1 <= frame.x1 and frame.y0 <= b.y0
                      and b.y1 <= frame.y1)
            legend = ax.get_legend()
            obstacles = [box(o) for o in ax.texts if o is not t and o.get_visible()]
            if legend is not None:
                obstacles.append(legend.get_window_extent(renderer))
            # and the hinges and masses, against the text's own box (a label "B = D" ran under
            # the mass at D)
            own = Text.get_window_extent(t, renderer)
            discs = [c.get_window_extent(renderer) for c in ax.patches if isinstance(c, Circle)]
            return (inside and not any(b.overlaps(o) for o in obstacles)
                    and not any(own.overlaps(c) for c in discs))

        for t in ax.texts:  # an annotation gets its coordinates' transform when drawn
            if isinstance(t, Annotation):
                t.update_positions(renderer)
        movable = [t for t in ax.texts if hasattr(t, "anchor")]
        for t in movable:  # every draw starts from the labels' own places: the same result
            t.set_position(t.anchor[2])
        for t in movable:
            if clear(t):
                continue
            anchor, dist, first = t.anchor
            start = np.asarray(first, dtype=float) - anchor
            phi0 = float(np.arctan2(start[1], start[0])) if dist > 0 else 0.0
            dist = dist or 0.05 * float(np.ptp(ax.get_xlim()))
            for factor in (1.0, 1.6, 2.3):
                for k in range(24):
                    # alternately either side of the label's own direction: nearest first
                    phi = phi0 + (-1) ** k * ((k + 1) // 2) * np.pi / 12
                    t.set_position(anchor + factor * dist * np.array([np.cos(phi),
                                                                      np.sin(phi)]))
                    if clear(t):
                        break
                else:
                    continue
                break
            else:
                t.set_position(first)  # nowhere free: its own place (the figure check says so)
