"""One function per figure: data in, matplotlib Figure out (no solving here)."""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import colors as mcolors  # noqa: E402
from matplotlib import image as mimage  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.transforms import Bbox  # noqa: E402

from flutterfriction.figure_check import check_figure, saved_pad_inches  # noqa: E402
from flutterfriction.figure_offences import offences_json  # noqa: E402
from flutterfriction.io import atomic_path, write_json  # noqa: E402
from flutterfriction.parameter_text import (  # noqa: E402, F401  (the figures' words)
    OWN_VALUES_WIDTH,
    chapter_list,
    list47,
    list47_viscous,
    list119,
    own_parameters_note,
    pendulum_case,
    pendulum_text,
    rod_text,
    wrap_items,
)
from flutterfriction.plotting.font_subsets import embedded_font_subsets  # noqa: E402
from flutterfriction.plotting.mathtext_parses import shared_mathtext_parses  # noqa: E402

plt.rcParams.update({
    "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "legend.fontsize": 8,
    "figure.dpi": 150, "savefig.dpi": 200, "axes.grid": True, "grid.alpha": 0.3,
    "pdf.fonttype": 42,
})

REGIME_COLOURS = {"stable": "#d8ecd3", "flutter": "#fbe0b8", "divergence": "#f4c7c3"}
#: One colour per time integrator in every work-precision figure (a review: the same solver
#: had two colours in work_precision and beck_work_precision); the meshes by line style.
INTEGRATOR_COLOURS = {"LSODA": "C0", "BDF": "C1", "Radau": "C2", "generalized-alpha": "C3",
                      "DOP853": "C4", "RK45": "C5"}
MESH_STYLES = ("-", "--", ":")


def tidy_log_axis(axis, values) -> None:
    """Log-axis ticks that never crowd: when the values hold fewer than two powers of ten
    (measured wall times, say), two to five labelled ticks inside the values' range, in short
    plain numbers (matplotlib would otherwise label the minor ticks, and their long labels,
    2×10⁻², 3×10⁻², overprint each other, or label one tick only, or fall back to every
    integer multiple: 0.002 ... 0.009 overprinted). The first of 1-3, 1-2-5, 1-1.5-2-3-5-7
    times powers of ten that gives two to five ticks; else a few linear steps. (1-2-5 over
    1.2e-4 to 8.6e-3 s gave seven labels that overprinted on CI's machine: the values are
    timings, so the rule must hold for any of them.)"""
    from matplotlib.ticker import FixedLocator, FuncFormatter, MaxNLocator, NullFormatter

    v = np.asarray([x for x in values if x > 0], dtype=float)
    if v.size == 0:
        return
    axis.set_minor_formatter(NullFormatter())
    lo, hi = v.min(), v.max()
    if np.floor(np.log10(hi)) - np.ceil(np.log10(lo)) >= 1:
        return  # two powers of ten or more: matplotlib's decades are fine
    powers = 10.0 ** np.arange(np.floor(np.log10(lo)), np.floor(np.log10(hi)) + 1)
    for subs in ((1.0, 3.0), (1.0, 2.0, 5.0), (1.0, 1.5, 2.0, 3.0, 5.0, 7.0)):
        ticks = [m * p for p in powers for m in subs if lo <= m * p <= hi]
        if 2 <= len(ticks) <= 5:
            break
    else:
        ticks = [t for t in MaxNLocator(3).tick_values(lo, hi) if lo <= t <= hi]
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))


def _canvas_cut(fig: Figure, tight: Bbox, pad: float) -> np.ndarray | None:
    """The PNG of ``fig`` saved with ``bbox_inches=tight.padded(pad)`` [in], cut from its
    rendered Agg canvas (RGBA rows, top first); the pad beyond the canvas is the figure's
    background. None where something drawn reaches beyond the canvas (``tight`` is not inside
    it) or the saved background is not the figure's: savefig must draw that. The size is
    savefig's; the box's corner is rounded to a whole pixel (savefig shifts the drawing by its
    fraction of a pixel instead)."""
    if plt.rcParams["savefig.transparent"] or plt.rcParams["savefig.facecolor"] != "auto":
        return None
    rgba = np.asarray(fig.canvas.buffer_rgba())
    height, width = rgba.shape[:2]
    if (tight.x0 * fig.dpi < 0 or tight.y0 * fig.dpi < 0 or tight.x1 * fig.dpi > width
            or tight.y1 * fig.dpi > height):
        return None
    box = tight.padded(pad)
    # savefig's size: its canvas truncates the box's size to whole pixels, with 1e-8 px for
    # rounding (FigureCanvasBase.get_width_height)
    x0, y0 = round(box.x0 * fig.dpi), round(box.y0 * fig.dpi)
    x1, y1 = (x0 + int(box.width * fig.dpi + 1e-8), y0 + int(box.height * fig.dpi + 1e-8))
    out = np.empty((y1 - y0, x1 - x0, 4), dtype=np.uint8)
    out[...] = np.round(255 * np.asarray(mcolors.to_rgba(fig.get_facecolor())))
    cx0, cy0, cx1, cy1 = max(x0, 0), max(y0, 0), min(x1, width), min(y1, height)
    out[y1 - cy1:y1 - cy0, cx0 - x0:cx1 - x0] = rgba[height - cy1:height - cy0, cx0:cx1]
    return out


def _save_pdf(fig: Figure, path: str | os.PathLike, metadata: dict) -> None:
    """``fig.savefig(path, format="pdf", bbox_inches="tight")`` without savefig's measuring
    draw: for a tight box savefig first draws the whole figure with drawing disabled (a layout
    pass), then measures the box and draws again into the PDF. The figure is laid out already
    (:func:`save_figure` drew it), so that first draw is skipped: the box is measured on the
    PDF's renderer as before, and the file is the same bytes (all 39 paper figures compared;
    ~0.15 s a figure). Where a matplotlib makes no measuring draw (the one skipped was then
    the drawing itself), the figure is saved again as savefig saves it."""
    draws = 0

    def draw(renderer: Any) -> None:
        nonlocal draws
        draws += 1
        if draws > 1:
            type(fig).draw(fig, renderer)

    fig.draw = draw  # (as matplotlib's own _get_renderer shadows it)
    try:
        fig.savefig(path, format="pdf", metadata=metadata, bbox_inches="tight")
    finally:
        del fig.draw
    if draws < 2:
        fig.savefig(path, format="pdf", metadata=metadata, bbox_inches="tight")


def save_figure(fig: Figure, *paths: str | os.PathLike, draft: bool = False,
                check: str | os.PathLike | None = None) -> None:
    """Write ``fig`` to each path atomically (temp file + rename), without dates in metadata,
    cropped to its tight bounding box (``bbox_inches="tight"``).

    ``draft`` (the quick preset): PNG at 100 dpi and PDF text as Type 3 glyphs, about half the
    cost of a save; the paper figures embed TrueType (Type 42, editable text, as journals ask)
    and render PNGs at 200 dpi. ``check``: then run the figure check
    (:func:`flutterfriction.figure_check.check_figure`) and write its offences to this JSON
    file (the workflow's check fails the run on any). A PDF's embedded font subsets leave out
    the OpenType layout tables no PDF reader uses, and are cut from per-process working copies
    of the fonts (the same bytes, cheaper; :mod:`flutterfriction.plotting.font_subsets`).

    The figure is laid out, measured and rendered once at the PNG's resolution, by one draw
    into the Agg canvas (the check's, when checked): its layout engine runs there, the PNG is
    that canvas cut to the padded tight box (:func:`_canvas_cut`; where a drawing reaches
    beyond the canvas, savefig draws the box instead), and every other format is rendered
    from that layout (a PDF measures its own box, at its 72 dpi, as text extents differ by
    resolution: up to 0.107 in wider there than at the PNG's 200 dpi in Figs. 15-17, more
    than the 0.1 in pad, measured; without savefig's layout pass, :func:`_save_pdf`). A checked
    PNG is drawn once (3 times before the check measured at the PNG's resolution, 2 before it
    was cut from the canvas), PDF + PNG twice (were 5, then 4, then 3). Cutting also keeps a
    figure legend where the check measured it: savefig anchored it to the padded box, 0.05 in
    lower. The files are the same with or without the check. Math text is parsed once per
    process for all the renderers of a save (:mod:`flutterfriction.plotting.mathtext_parses`)."""
    rc = {"pdf.fonttype": 3, "savefig.dpi": 100} if draft else {}
    engine = fig.get_layout_engine()
    with plt.rc_context(rc), shared_mathtext_parses():
        dpi = plt.rcParams["savefig.dpi"]
        shown_dpi = fig.dpi
        fig.set_dpi(fig.dpi if dpi == "figure" else dpi)  # measured as the PNG is drawn
        pngs = [Path(p) for p in paths if Path(p).suffix == ".png"]
        try:
            if check is not None:
                start = time.perf_counter()
                offences = check_figure(fig, tight=True, render=bool(pngs))
                write_json(check, offences_json(Path(check).stem, offences))
                print(f"{Path(check).stem}: figure check, {len(offences)} offences "
                      f"({1e3 * (time.perf_counter() - start):.0f} ms)", *offences,
                      sep="\n  ", flush=True)
            elif pngs:
                if not isinstance(fig.canvas, FigureCanvasAgg):
                    FigureCanvasAgg(fig)
                fig.canvas.draw()
            else:
                fig.draw_without_rendering()
            tight = fig.get_tightbbox()
            box = tight.padded(saved_pad_inches())
            # the PNG is cut from the canvas just rendered (one draw for the layout, the check
            # and the pixels), unless a drawing reaches beyond the canvas: savefig then draws
            # the larger area
            cut = _canvas_cut(fig, tight, saved_pad_inches()) if pngs else None
            if pngs and cut is None:
                print(f"{pngs[0].stem}: drawn beyond its canvas, saved by a second draw",
                      flush=True)
            for path in pngs if cut is not None else ():
                with atomic_path(path) as tmp:
                    mimage.imsave(tmp, cut, format="png", dpi=fig.dpi,
                                  metadata={"Software": None})
        finally:
            fig.set_dpi(shown_dpi)
        paths = tuple(p for p in paths if cut is None or Path(p) not in pngs)
        try:
            # laid out above; every format renders that layout (no engine at all: with
            # "none"'s placeholder engine, savefig would still draw once before rendering).
            # The rc holds no engine for the saves too: savefig puts "no engine" back with
            # set_layout_engine(None), which reads the rc (a user's constrained_layout.use
            # installed one there; an outside review)
            with plt.rc_context({"figure.autolayout": False,
                                 "figure.constrained_layout.use": False}), \
                    embedded_font_subsets():
                fig.set_layout_engine(None)
                for path in map(Path, paths):
                    fmt = path.suffix.lstrip(".")
                    meta = {"CreationDate": None} if fmt == "pdf" else {"Software": None}
                    with atomic_path(path) as tmp:
                        if fmt == "pdf":
                            _save_pdf(fig, tmp, meta)
                        else:
                            fig.savefig(tmp, format=fmt, metadata=meta,
                                        bbox_inches=box if fmt == "png" else "tight")
        finally:
            if engine is not None:
                fig.set_layout_engine(engine)
    plt.close(fig)
