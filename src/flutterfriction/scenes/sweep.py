"""Parameter sweeps that scatter over jobs (stability maps, bifurcation diagrams).

A sweep scene is three pure functions: the list of its ``points`` (from the parameters), the
``compute`` of a contiguous block of points (a list of JSON-able results, one per point), and
the ``combine`` of all results, in order, into the scene's data. :func:`build_scene` runs the
whole sweep in one process; the workflow runs :func:`compute_part` as ``n_parts`` independent
jobs (one per block, e.g. one SLURM job each) and :func:`combine_parts` gathers them, so both
paths give the same data. Blocks are contiguous so that a sweep may continue each point from
the previous one within a block.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from flutterfriction.errors import ParameterError, check_integer

#: Most parts a sweep is cut into (as `sweep_parts` and `--set-scatter sweep=N` allow).
MAX_PARTS = 10000


@dataclass(frozen=True)
class Sweep:
    points: Callable[[dict[str, Any]], list[Any]]
    compute: Callable[[dict[str, Any], list[Any]], list[Any]]
    combine: Callable[[dict[str, Any], list[Any]], dict[str, Any]]

    def run(self, params: dict[str, Any]) -> dict[str, Any]:
        return self.combine(params, self.compute(params, self.points(params)))


def _blocks(n_points: int, n_parts: int) -> list[range]:
    edges = np.linspace(0, n_points, n_parts + 1).round().astype(int)
    return [range(a, b) for a, b in zip(edges[:-1], edges[1:], strict=True)]


def compute_part(sweep: Sweep, params: dict[str, Any], part: int, n_parts: int) -> dict[str, Any]:
    """Results of block ``part`` (0-based) of ``n_parts``: ``{"part", "n_parts", "indices",
    "results"}``. A block may be empty when there are more parts than points."""
    # integers as given, never truncated (an outside audit: part = 0.9 ran as part 0,
    # n_parts = "10000000" was taken, part = NaN raised a bare ValueError); at most the
    # workflow's sweep parts (workflow/rules/scenes.smk)
    n_parts = check_integer("n_parts", n_parts, 1, MAX_PARTS)
    part = check_integer("part", part, 0, n_parts - 1)
    points = sweep.points(params)
    block = _blocks(len(points), n_parts)[part]
    results = sweep.compute(params, [points[i] for i in block]) if len(block) else []
    return {"part": part, "n_parts": n_parts, "indices": list(block), "results": results}


def combine_parts(sweep: Sweep, params: dict[str, Any], parts: list[dict[str, Any]]
                  ) -> dict[str, Any]:
    """The scene's data from every block's results; refuses a missing or repeated point."""
    n = len(sweep.points(params))
    results: list[Any] = [None] * n
    seen: set[int] = set()
    for p in parts:
        for i, r in zip(p["indices"], p["results"], strict=True):
            if i in seen or not 0 <= i < n:
                raise ParameterError(f"sweep part {p['part']}: point {i} repeated or unknown")
            seen.add(i)
            results[i] = r
    if len(seen) != n:
        raise ParameterError(f"sweep parts cover {len(seen)} of {n} points")
    return sweep.combine(params, results)
