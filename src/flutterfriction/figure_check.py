"""The figure check: every figure the workflow draws is legible and explained, or the run fails.

A figure is checked as matplotlib draws it: the check draws it once (without rasterising,
:meth:`~matplotlib.figure.Figure.draw_without_rendering`, or into the Agg canvas the PNG is cut
from) and records every text, legend and
axes actually drawn, in drawing order; extents are matplotlib's own
(:meth:`~matplotlib.text.Text.get_window_extent` with the canvas renderer). Offences name the
figure's text and the axes (its number in ``fig.axes`` and its title or labels). The rules, each
an :class:`~flutterfriction.figure_offences.Offence` kind:

``overlap``
    Two drawn texts (titles, axis labels, tick labels, annotations, legend texts, colorbar
    labels, figure texts) whose boxes intersect by more than :data:`OVERLAP_PT2`.
``clipped``
    A text cut by its clip box or clip path (``clip_on=True``), or reaching beyond the saved
    area (the tight bounding box the figures are saved with, or the canvas).
``covered``
    A text under a legend's opaque frame, or under an opaque axes (an inset, a colorbar, a
    neighbouring panel) drawn after it.
``small``
    A text smaller than :data:`MIN_TEXT_PX` when the figure is shown :data:`REPORT_WIDTH_PX`
    wide (the report's figures fill the window up to 1800 px; 1200 px is a laptop's), or at
    its PNG's :data:`PNG_DPI` if that is narrower: a wide figure needs larger type (a figure
    review read 6.5 pt in a 14-inch figure as 8 px, unreadable).
``unit``
    An axis showing values (it draws tick labels that are numbers) without a label, or whose
    label has no unit: the repository's convention is a unit in square brackets, ``[N]``,
    ``[m/s]``, ``[-]`` for a dimensionless quantity (or the word "dimensionless"). An axis whose
    tick labels are names (categories) needs no unit. And an axis labelled with a unit that
    shows no value (a log axis holding no power of ten), unless an axis sharing it does.
``unexplained``
    In one axes, more than one line style (colour, line style, marker) of data that no legend
    of the figure shows (by its style, or by its colour and by its line style and marker in
    two entries) and no text of the same colour in the axes names; a colour-mapped
    collection whose colour map no colorbar shows; an artist given a label that no legend
    shows. Reference lines (straight horizontal or vertical lines: a zero line, a critical
    load) are left to their annotations, and filled regions to their text.
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib import colors as mcolors
from matplotlib.axes._base import _AxesBase
from matplotlib.axis import Axis
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import Collection, LineCollection, PathCollection
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from flutterfriction.figure_offences import Offence

#: Two texts overlap when their boxes share more than this area [pt²] (a 1 pt square: a box
#: holds its glyphs' side bearings and descent, so a corner this size touches no ink). On every
#: figure of the workflow no two text boxes intersect at all; the closest pair is 1.0 pt apart.
OVERLAP_PT2 = 1.0
#: A text is clipped or covered when it reaches further than this [pt] into what clips or
#: covers it (a rounding margin: extents are measured at the PNG's dpi, the PDF's are at 72).
TOLERANCE_PT = 0.5

#: The ``small`` rule: the width [px] a figure is read at (at most; a narrower figure is shown
#: at its PNG's resolution, :data:`PNG_DPI`), and the least height [px] of its texts' font
#: there (10 px: 7.5 pt on a printed page at 96 px per inch).
REPORT_WIDTH_PX, PNG_DPI, MIN_TEXT_PX = 1200.0, 200.0, 10.0

#: The unit convention of the axis labels: a unit in square brackets, or "dimensionless".
UNIT = re.compile(r"\[[^\[\]]*\S[^\[\]]*\]|dimensionless", re.IGNORECASE)


@dataclass
class _Drawn:
    """What one draw of the figure drew, in order."""

    texts: list[tuple[int, Text, Any, Legend | None]]
    legends: list[tuple[int, Legend, Any]]
    axes: list[tuple[int, Any]]


@contextlib.contextmanager
def _recording() -> Iterator[_Drawn]:
    """Record every Text, Legend and Axes matplotlib draws (the draw methods wrapped for the
    duration; a text counts when drawn as Text.draw draws it: visible and not empty)."""
    drawn = _Drawn([], [], [])
    counter = iter(range(1 << 62))
    axes_stack: list[Any] = []
    legend_stack: list[Legend] = []
    text_draw, legend_draw, axes_draw = Text.draw, Legend.draw, _AxesBase.draw

    def draw_text(self: Text, renderer: Any) -> Any:
        if self.get_visible() and self.get_text() != "":
            drawn.texts.append((next(counter), self, axes_stack[-1] if axes_stack else None,
                                legend_stack[-1] if legend_stack else None))
        return text_draw(self, renderer)

    def draw_legend(self: Legend, renderer: Any) -> Any:
        if self.get_visible():
            drawn.legends.append((next(counter), self, axes_stack[-1] if axes_stack else None))
        legend_stack.append(self)
        try:
            return legend_draw(self, renderer)
        finally:
            legend_stack.pop()

    def draw_axes(self: Any, renderer: Any) -> Any:
        if self.get_visible():
            drawn.axes.append((next(counter), self))
        axes_stack.append(self)
        try:
            return axes_draw(self, renderer)
        finally:
            axes_stack.pop()

    Text.draw, Legend.draw, _AxesBase.draw = draw_text, draw_legend, draw_axes
    try:
        yield drawn
    finally:
        Text.draw, Legend.draw, _AxesBase.draw = text_draw, legend_draw, axes_draw


def _short(s: str, n: int = 60) -> str:
    s = " ".join(s.split())
    return s if len(s) <= n else s[:n - 1] + "…"


def _axes_name(ax: Any, index: dict[int, str]) -> str:
    if ax is None:
        return "figure"
    titles = [getattr(ax, a, None) for a in ("title", "_left_title", "_right_title")]
    name = next((t.get_text() for t in titles if t is not None and t.get_text()), "")
    if not name:
        labels = [ax.yaxis.label.get_text(), ax.xaxis.label.get_text()]
        name = " / ".join(_short(s, 30) for s in labels if s)
    return f"axes {index.get(id(ax), '?')}" + (f": {_short(name, 50)}" if name else "")


def _area(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Intersection areas of boxes a (n, 4) with boxes b (m, 4), x0 y0 x1 y1: (n, m)."""
    w = np.minimum(a[:, None, 2], b[None, :, 2]) - np.maximum(a[:, None, 0], b[None, :, 0])
    h = np.minimum(a[:, None, 3], b[None, :, 3]) - np.maximum(a[:, None, 1], b[None, :, 1])
    return np.clip(w, 0, None) * np.clip(h, 0, None)


def _box(bb: Bbox) -> list[float]:
    return [min(bb.x0, bb.x1), min(bb.y0, bb.y1), max(bb.x0, bb.x1), max(bb.y0, bb.y1)]


def _inside(inner: list[float], outer: list[float], tol: float) -> bool:
    return (inner[0] >= outer[0] - tol and inner[1] >= outer[1] - tol
            and inner[2] <= outer[2] + tol and inner[3] <= outer[3] + tol)


def _is_number(label: str) -> bool:
    s = label.replace("$", "").replace("\u2212", "-").replace("\\mathdefault", "")
    s = re.sub(r"[{}\s]", "", s).replace("\\times", "x").replace("^", "e")
    return bool(s) and re.fullmatch(r"[-+0-9.,e%x]*[0-9][-+0-9.,e%x]*", s) is not None


def _style(colour: Any, linestyle: Any = "None", marker: Any = "None") -> tuple[str, str, str]:
    ls = str(linestyle)
    ls = "none" if ls in ("None", "none", "", " ") else ls
    mk = str(marker)
    mk = "none" if mk in ("None", "none", "", " ") else mk
    return (mcolors.to_hex(colour, keep_alpha=False), ls, mk)


def _describe(style: tuple[str, str, str]) -> str:
    colour, ls, mk = style
    return colour + ("" if ls == "none" else f" {ls}") + ("" if mk == "none" else f" marker {mk}")


def _legend_styles(legend: Legend) -> set[tuple[str, str, str]]:
    out = set()
    for h in legend.legend_handles:
        if h is None:
            continue
        with contextlib.suppress(ValueError, TypeError, IndexError):
            if isinstance(h, Line2D):
                out.add(_style(h.get_color(), h.get_linestyle(), h.get_marker()))
                out.add(_style(h.get_color(), h.get_linestyle(), "none"))
            elif isinstance(h, Patch):
                out.add(_style(h.get_facecolor()))
                out.add(_style(h.get_edgecolor(), h.get_linestyle()))
            elif isinstance(h, Collection):
                for c in (*h.get_facecolor()[:1], *h.get_edgecolor()[:1]):
                    out.add(_style(c))
                    out.add(_style(c, h.get_linestyle()[0] if h.get_linestyle() else "-"))
    return out


def _is_reference_line(line: Line2D) -> bool:
    """A straight horizontal or vertical line (a zero line, a critical value): explained by its
    annotation, not by the legend."""
    x, y = (np.asarray(v, dtype=float).ravel() for v in line.get_data(orig=False))
    if x.size < 2:
        return False
    return bool(np.ptp(x) == 0 or np.ptp(y) == 0)


def _collection_style(c: Collection) -> tuple[str, str, str] | None:
    colours = c.get_edgecolor() if isinstance(c, LineCollection) else c.get_facecolor()
    if len(colours) == 0:
        colours = c.get_edgecolor()
    if len(colours) == 0:
        return None
    if isinstance(c, LineCollection):
        ls = c.get_linestyle()
        return _style(colours[0], "-" if not ls or ls[0][1] is None else "--")
    return _style(colours[0], "none", "o")


def check_figure(fig: Figure, *, tight: bool = True, render: bool = False) -> list[Offence]:
    """The offences of ``fig`` (empty when it passes), drawn as it is saved: ``tight`` when
    saved with ``bbox_inches="tight"`` (the saved area is then the tight bounding box, else
    the canvas). Its one draw (the layout engine included) is the one
    :func:`flutterfriction.plotting.save_figure` lays the figure out and measures it by, at
    the PNG's resolution: without rendering, or with ``render`` into the Agg canvas (whose
    pixels the PNG is then cut from)."""
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    with _recording() as drawn:
        if render:
            fig.canvas.draw()
        else:
            fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    pt = 72.0 / fig.dpi  # points per pixel
    # axes by their number in fig.axes; an inset or a secondary axis as <its parent's>.<n>
    index = {id(ax): str(k) for k, ax in enumerate(fig.axes)}
    for k, ax in enumerate(fig.axes):
        for j, child in enumerate(ax.child_axes):
            index.setdefault(id(child), f"{k}.{j + 1}")
    offences: list[Offence] = []

    def where(ax: Any) -> str:
        return _axes_name(ax, index)

    texts = [(o, t, ax, leg) for o, t, ax, leg in drawn.texts]
    boxes = np.array([_box(Text.get_window_extent(t, renderer)) for _, t, _, _ in texts]
                     ).reshape(-1, 4)
    keep = (boxes[:, 2] - boxes[:, 0] > 0) & (boxes[:, 3] - boxes[:, 1] > 0)
    texts = [x for x, k in zip(texts, keep, strict=True) if k]
    boxes = boxes[keep]
    names = [_short(t.get_text()) for _, t, _, _ in texts]

    # overlap: every pair of drawn texts
    bad = _area(boxes, boxes) * pt * pt > OVERLAP_PT2
    for i, j in zip(*np.nonzero(np.triu(bad, 1)), strict=True):
        offences.append(Offence("overlap", names[i], repr(names[j]), where(texts[i][2])))

    # clipped: by the text's own clip box or path, or by the saved area
    tol = TOLERANCE_PT / pt
    area = _box(fig.bbox)
    if tight and any(not t.get_in_layout() for _, t, _, _ in texts):
        # (a text in the layout is inside the tight box by construction)
        pad = fig.get_tightbbox(renderer).padded(saved_pad_inches())
        pad = pad.transformed(fig.dpi_scale_trans)
        area = _box(pad)
    for (_, t, ax, _), box, name in zip(texts, boxes, names, strict=True):
        if t.get_clip_on():
            clip = t.get_clip_box()
            path = t.get_clip_path()
            limits = [_box(clip)] if clip is not None else []
            if path is not None:
                limits.append(_box(path.get_fully_transformed_path().get_extents()))
            if any(not _inside(list(box), lim, tol) for lim in limits):
                offences.append(Offence("clipped", name, "its clip box", where(ax)))
                continue
        if (not tight or not t.get_in_layout()) and not _inside(list(box), area, tol):
            offences.append(Offence("clipped", name, "the saved area", where(ax)))

    # covered: by a legend's opaque frame or an opaque axes drawn after the text
    covers: list[tuple[int, list[float], str, Any]] = []
    for order, leg, _ in drawn.legends:
        frame = leg.get_frame()
        if leg.get_frame_on() and frame.get_visible() and mcolors.to_rgba(
                frame.get_facecolor())[3] > 0:
            covers.append((order, _box(frame.get_window_extent(renderer)), "a legend", leg))
    for order, ax in drawn.axes:
        if ax.axison and ax.get_frame_on() and ax.patch.get_visible() and mcolors.to_rgba(
                ax.patch.get_facecolor())[3] > 0:
            covers.append((order, _box(ax.patch.get_window_extent(renderer)), where(ax), ax))
    for order, box, what, artist in covers:
        for (o, _, ax, leg), tbox, name in zip(texts, boxes, names, strict=True):
            if o > order or artist is leg or artist is ax:
                continue
            overlap = _area(tbox[None, :], np.array([box]))[0, 0]
            w = min(tbox[2], box[2]) - max(tbox[0], box[0])
            h = min(tbox[3], box[3]) - max(tbox[1], box[1])
            if overlap * pt * pt > OVERLAP_PT2 and min(w, h) > tol:
                offences.append(Offence("covered", name, what, where(ax)))

    # small: every text legible at the report's width (the saved width from the drawn texts'
    # and axes' extents: the figure's tight box without a second layout pass)
    frames = [_box(ax.patch.get_window_extent(renderer)) for _, ax in drawn.axes]
    extent = np.vstack([boxes, np.array(frames).reshape(-1, 4)])
    if tight and extent.size:
        width_in = (extent[:, 2].max() - extent[:, 0].min()) / fig.dpi
    else:
        width_in = fig.get_figwidth()
    px_per_pt = min(PNG_DPI, REPORT_WIDTH_PX / max(width_in, 1e-9)) / 72.0
    for (_, t, ax, _), name in zip(texts, names, strict=True):
        px = t.get_fontsize() * px_per_pt
        if px < MIN_TEXT_PX:
            offences.append(Offence("small", name, f"{t.get_fontsize():g} pt: {px:.1f} px in "
                                    f"a {width_in:.1f}-inch figure shown "
                                    f"{min(REPORT_WIDTH_PX, PNG_DPI * width_in):.0f} px wide",
                                    where(ax)))

    # unit: every axis that draws numbers has a label with a unit
    drawn_ids = {id(t) for _, t, _, _ in texts}
    for _, ax in drawn.axes:
        for axis in _axes_axes(ax):
            offences += _unit_offences(axis, drawn_ids, where(ax))

    # unexplained: colours and line styles
    legends = [leg for _, leg, _ in drawn.legends]
    legend_styles = set().union(*(_legend_styles(leg) for leg in legends)) if legends else set()
    legend_labels = {t.get_text() for leg in legends for t in leg.get_texts()}
    colorbar_cmaps = {ax._colorbar.cmap.name for _, ax in drawn.axes
                      if getattr(ax, "_colorbar", None) is not None}
    text_colours: dict[int, set[str]] = {}
    for _, t, ax, _ in texts:
        text_colours.setdefault(id(ax), set()).add(mcolors.to_hex(t.get_color()))
    for _, ax in drawn.axes:
        offences += _style_offences(ax, legend_styles, legend_labels, colorbar_cmaps,
                                    text_colours.get(id(ax), set()), where(ax))
    return offences


def saved_pad_inches() -> float:
    """The padding [in] around a tight bounding box as figures are saved (rc savefig.pad_inches)."""
    import matplotlib

    pad = matplotlib.rcParams["savefig.pad_inches"]
    return 0.1 if pad == "layout" else float(pad)


def _axes_axes(ax: Any) -> list[Axis]:
    return [a for a in (getattr(ax, "xaxis", None), getattr(ax, "yaxis", None))
            if a is not None and a.get_visible()]


def _tick_labels(axis: Axis, drawn: set[int]) -> list[str]:
    ticks = [*axis.get_major_ticks(), *axis.get_minor_ticks()]
    return [lab.get_text() for tick in ticks for lab in (tick.label1, tick.label2)
            if id(lab) in drawn]


def _unit_offences(axis: Axis, drawn: set[int], where: str) -> list[Offence]:
    shown = _tick_labels(axis, drawn)
    name = axis.axis_name if hasattr(axis, "axis_name") else "axis"
    label = axis.label.get_text() if id(axis.label) in drawn else ""
    if not shown and label and UNIT.search(label):
        # a quantity with a unit but no value on it (a log axis holding no power of ten),
        # unless an axis sharing it shows them
        shared = getattr(axis.axes, f"get_shared_{name}_axes", None)
        siblings = shared().get_siblings(axis.axes) if shared else []
        if not any(_tick_labels(getattr(a, f"{name}axis"), drawn) for a in siblings):
            return [Offence("unit", _short(label), f"{name} axis shows no values", where)]
    if not shown or not any(_is_number(s) for s in shown):
        return []  # no values drawn, or names (categories): no unit to give
    if not label:
        return [Offence("unit", f"{name} axis without a label",
                        f"ticks {_short(', '.join(shown[:3]), 30)}", where)]
    if not UNIT.search(label):
        return [Offence("unit", _short(label), f"{name} axis label without a unit [..]", where)]
    return []


def _explained(style: tuple[str, str, str], legend: set[tuple[str, str, str]]) -> bool:
    """A style is explained by a legend entry of the same style, or by one of its colour and
    one of its line style and marker (alpha_1 in blue and "instants drawn" as grey dots
    explain blue dots)."""
    return style in legend or (any(s[0] == style[0] for s in legend)
                               and any(s[1:] == style[1:] for s in legend))


def _style_offences(ax: Any, legend_styles: set, legend_labels: set[str], colorbar_cmaps: set,
                     text_colours: set[str], where: str) -> list[Offence]:
    if getattr(ax, "_colorbar", None) is not None:
        return []
    out = []
    loose: dict[tuple[str, str, str], str] = {}
    for line in ax.get_lines():
        if not line.get_visible() or _is_reference_line(line):
            continue
        x, _ = line.get_data(orig=False)
        if np.size(x) == 0:
            continue
        style = _style(line.get_color(), line.get_linestyle(), line.get_marker())
        if _explained(style, legend_styles):
            continue
        if style[0] in text_colours and style[0] not in ("#000000",):
            continue  # named by a text of its colour in the same axes
        loose.setdefault(style, line.get_label())
    for c in ax.collections:
        if not c.get_visible() or not isinstance(c, (LineCollection, PathCollection)):
            continue
        if c.get_array() is not None:
            if c.get_cmap().name not in colorbar_cmaps:
                out.append(Offence("unexplained", f"colour map {c.get_cmap().name}",
                                   "no colorbar shows it", where))
            continue
        style = _collection_style(c)
        if style is None or _explained(style, legend_styles):
            continue
        if style[0] in text_colours and style[0] != "#000000":
            continue
        loose.setdefault(style, c.get_label())
    for artist in (*ax.get_lines(), *ax.collections, *ax.patches):
        label = artist.get_label()  # None for an unlabelled fill
        if artist.get_visible() and label and not str(label).startswith("_") \
                and label not in legend_labels:
            out.append(Offence("unexplained", _short(str(label)),
                               "labelled, but no legend shows it", where))
    if len(loose) > 1:
        out += [Offence("unexplained", _describe(s), "no legend or text of its colour names "
                        f"it ({len(loose)} such styles)", where) for s in loose]
    return out
