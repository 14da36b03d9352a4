"""The work-precision figure: error against wall time, one panel per solver family."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from flutterfriction.benchmarks import FAMILY_ERRORS, FAMILY_SETTINGS, NAMED_POINTS, UNJOINED
from flutterfriction.plotting import INTEGRATOR_COLOURS, MESH_STYLES, tidy_log_axis

FLOOR = 1e-17  # errors of exactly 0 (agreement to the last bit) are drawn here
#: Legend names for the studies' short method names (a review read "routh", "beck_damped")
READABLE = {"routh": "Routh–Hurwitz", "eigenvalues": "eigenvalues", "FE, beck": "FE, Beck rod",
            "FE, beck_damped": "FE, damped Beck rod", "FE, pfluger": "FE, Pflüger rod"}


def plot_work_precision(runs: list[dict[str, Any]]) -> Figure:
    families = list(dict.fromkeys(r["family"] for r in runs))
    # two columns, 9.6 in wide: the legends legible with the figure 1200 px wide (three, 13 in
    # wide, drew them at 7.9 px: the figure check's `small` rule)
    ncols = 2
    nrows = int(np.ceil(len(families) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(9.6, 3.6 * nrows), squeeze=False)
    for ax, family in zip(axes.flat, families, strict=False):
        rows = [r for r in runs if r["family"] == family and r["error"] is not None]
        # an integrator's colour as in its own study's figure, its mesh ("LSODA, 8 el.") by
        # the line style; other methods by their order
        meshes = sorted({m.partition(", ")[2] for m in (r["method"] for r in rows)
                         if m.partition(", ")[0] in INTEGRATOR_COLOURS},
                        key=lambda w: float(w.split()[0]) if w else 0.0)
        for k, method in enumerate(dict.fromkeys(r["method"] for r in rows)):
            base, _, mesh = method.partition(", ")
            colour = INTEGRATOR_COLOURS.get(base, f"C{k % 10}")
            style = MESH_STYLES[meshes.index(mesh) % len(MESH_STYLES)] if mesh in meshes \
                else "-"
            # In the order of the setting (what varies along the line), else of the cost.
            mine = sorted((r for r in rows if r["method"] == method),
                          key=lambda r: (r["setting"] is None, r["setting"] or 0.0,
                                         r["wall_s"]))
            x, y = [r["wall_s"] for r in mine], [max(r["error"], FLOOR) for r in mine]
            ax.loglog(x, y, "o", ls="none" if family in UNJOINED else style, ms=3.5, lw=1,
                      color=colour, label=READABLE.get(method, method))
            if family in NAMED_POINTS:
                for i, (r, xi, yi) in enumerate(zip(mine, x, y, strict=True)):
                    # below right of a point, below left of the last (inside the axes)
                    last = i == len(mine) - 1
                    ax.annotate(NAMED_POINTS[family].format(r["setting"]), (xi, yi),
                                xytext=(-6, -3) if last else (6, -3), textcoords="offset points",
                                fontsize=7, ha="right" if last else "left", va="top")
                ax.margins(y=0.15)  # room for the labels inside the frame
        tidy_log_axis(ax.xaxis, [r["wall_s"] for r in rows])
        tidy_log_axis(ax.yaxis, [max(r["error"], FLOOR) for r in rows])
        sweep = FAMILY_SETTINGS.get(family)
        along = "each point" if family in UNJOINED else "along each line"
        ax.set_title(family + (f"\n{along}: {sweep}" if sweep else ""), fontsize=8)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel(FAMILY_ERRORS.get(family, "relative error [-]"))
        if len(ax.get_lines()) > 4:  # under the panel: inside, eight methods covered lines
            ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.2))
        else:
            ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(families):]:
        ax.set_visible(False)
    fig.suptitle("Work-precision of every solver family (shared 2-core machine; "
                 f"errors of 0 drawn at {FLOOR:g})", fontsize=9)
    fig.tight_layout()
    return fig
