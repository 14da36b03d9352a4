"""Animations (GIF) of computed motions, drawn with the same code as the figures."""

from __future__ import annotations

import os
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from PIL import Image

from flutterfriction.io import atomic_path
from flutterfriction.models.ziegler import ZieglerPendulum
from flutterfriction.plotting.pendulum import draw_pendulum

# A GIF is viewed on screen: 100 dpi (not the figures' print resolution, 200) renders a quarter
# of the pixels, about twice as fast, and the file is smaller.
GIF_DPI = 100


def _write_gif(fig, frame, n_frames: int, path: str | os.PathLike, fps: int) -> None:
    """Render ``frame(i)`` for each frame into a GIF written atomically to ``path``: one Agg
    draw per frame, the frames saved by Pillow as matplotlib's ``PillowWriter`` saves them
    (which drew every frame twice, once for the screen and once for the file). With the
    artists replaced instead of the axes cleared, measured: the pendulum's 60 frames 14.0 ->
    3.2 CPU-s, the rod's 41 frames 5.4 -> 1.3, the frames the same pixels."""
    fig.set_dpi(GIF_DPI)
    canvas = FigureCanvasAgg(fig)
    images = []
    try:
        for i in range(n_frames):
            frame(i)
            canvas.draw()
            images.append(Image.fromarray(np.asarray(canvas.buffer_rgba()).copy(), "RGBA"))
        with atomic_path(path) as tmp:
            images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                           duration=int(1000 / fps), loop=0)
    finally:
        plt.close(fig)


def _fixed_axes(ax, xlim, ylim) -> None:
    """Limits, equal aspect and no axis, set once: each frame then only replaces its artists
    (clearing the axes rebuilt their ticks every frame)."""
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal")
    ax.set_axis_off()


def _remove_drawn(ax) -> None:
    """Remove the previous frame's artists (lines, patches, texts, collections), keep the
    axes."""
    for artist in [*ax.lines, *ax.patches, *ax.texts, *ax.collections]:
        artist.remove()


def pendulum_cycle_gif(data: dict[str, Any], path: str | os.PathLike, n_periods: float = 2.0,
                       frames: int = 60, fps: int = 20) -> None:
    """The pendulum on its limit cycle (the last ``n_periods`` of the Fig. 14 data), written
    atomically to ``path``."""
    p = ZieglerPendulum.from_mapping(data["params"]["pendulum"])
    t = np.array(data["t"])
    alpha = np.array(data["alpha"])
    T = data["limit_cycle"]["period_s"]
    pick = np.searchsorted(t, np.linspace(t[-1] - n_periods * T, t[-1], frames))
    pick = np.clip(pick, 0, len(t) - 1)
    fig, ax = plt.subplots(figsize=(3.6, 4.4))
    L = p.l1 + p.l2
    masses = {"m1": p.m1, "m2": p.m2, "m3": p.m3}

    _fixed_axes(ax, (-0.25 * L, 1.05 * L), (-1.0 * L, 1.0 * L))

    def frame(i):
        _remove_drawn(ax)
        k = pick[i]
        pos = p.positions(alpha[0, k], alpha[1, k])
        draw_pendulum(ax, {key: v for key, v in pos.items()}, masses, scale=0.5 * p.l1)
        ax.set_title(f"limit cycle, t = {t[k]:.2f} s", fontsize=8)

    _write_gif(fig, frame, len(pick), path, fps)


def rod_cycle_gif(data: dict[str, Any], path: str | os.PathLike, fps: int = 15,
                  frames: int | None = None) -> None:
    """The nonlinear Beck rod on its limit cycle (one period), written atomically to ``path``;
    ``frames``: at most that many of the stored shapes, evenly spaced (all by default)."""
    shapes = [np.array(s) for s in data["shapes"]]
    if frames is not None and frames < len(shapes):
        shapes = [shapes[int(k)] for k in np.linspace(0, len(shapes) - 1, frames).round()]
    L = float(data["params"]["rod"]["length"])
    fig, ax = plt.subplots(figsize=(3.6, 4.6))

    _fixed_axes(ax, (-0.3 * L, 1.15 * L), (-1.05 * L, 1.05 * L))
    ax.set_title(f"Beck rod on its limit cycle, P = {data['P']:g} N "
                 f"({data['shapes_mesh']} elements)", fontsize=8)

    def frame(i):
        _remove_drawn(ax)
        xy = shapes[i]
        ax.plot(xy[:, 0], xy[:, 1], color="#333333", lw=2.2, solid_capstyle="round")
        ax.plot([0, 0], [-0.06 * L, 0.06 * L], color="#333333", lw=4)  # the clamp
        t = xy[-1] - xy[-2]
        t = t / np.linalg.norm(t)
        ax.annotate("", xy[-1], xy[-1] + 0.25 * L * t,
                    arrowprops={"arrowstyle": "-|>", "color": "#c0392b", "lw": 1.6})

    _write_gif(fig, frame, len(shapes), path, fps)
