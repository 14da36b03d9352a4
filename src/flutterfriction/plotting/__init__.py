"""One function per figure: data in, matplotlib Figure out (no solving here)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from flutterfriction.io import make_readable  # noqa: E402

plt.rcParams.update({
    "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "legend.fontsize": 8,
    "figure.dpi": 150, "savefig.dpi": 200, "axes.grid": True, "grid.alpha": 0.3,
    "pdf.fonttype": 42,
})

REGIME_COLOURS = {"stable": "#d8ecd3", "flutter": "#fbe0b8", "divergence": "#f4c7c3"}


def save_figure(fig: Figure, *paths: str | os.PathLike) -> None:
    """Write ``fig`` to each path atomically (temp file + rename), without dates in metadata."""
    for path in map(Path, paths):
        path.parent.mkdir(parents=True, exist_ok=True)
        fmt = path.suffix.lstrip(".")
        meta = {"CreationDate": None} if fmt == "pdf" else {"Software": None}
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=path.suffix)
        os.close(fd)
        try:
            fig.savefig(tmp, format=fmt, metadata=meta, bbox_inches="tight")
            make_readable(tmp)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
    plt.close(fig)
