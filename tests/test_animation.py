"""The GIF writer: one frame per drawn state, the frame rate and size asked for, looping."""

import numpy as np
from PIL import Image

from flutterfriction.plotting.animation import GIF_DPI, rod_cycle_gif


def test_rod_gif_has_one_frame_per_shape_at_the_asked_rate(tmp_path):
    x = np.linspace(0.0, 1.0, 9)
    shapes = [np.column_stack([x, a * x**2]).tolist() for a in (-0.3, 0.0, 0.3)]
    data = {"shapes": shapes, "params": {"rod": {"length": 1.0}}, "P": 5.5, "shapes_mesh": 8}
    path = tmp_path / "rod.gif"
    rod_cycle_gif(data, path, fps=10)
    with Image.open(path) as gif:
        assert gif.n_frames == 3
        assert gif.size == (round(3.6 * GIF_DPI), round(4.6 * GIF_DPI))
        assert gif.info["duration"] == 100 and gif.info["loop"] == 0
        frames = []
        for k in range(gif.n_frames):
            gif.seek(k)
            frames.append(np.asarray(gif.convert("L"), dtype=int))
    # the rod bends one way, then lies straight, then bends the other way: every frame differs
    assert all(np.any(frames[i] != frames[j]) for i, j in ((0, 1), (1, 2), (0, 2)))
    assert not list(tmp_path.glob(".*"))  # written atomically: no temporary file left
