"""Labels that keep clear of each other: a label remembers the point it names
(:func:`label_at`), and :func:`declutter` moves it around that point, at draw time, where it
overlaps another text, the key or a disc (a sketch of one's own pendulum puts its points where
the chapter's labels did not expect them)."""

from __future__ import annotations

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.patches import Circle
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox


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
