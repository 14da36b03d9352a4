"""Scene builders: each returns exactly the data one figure or table shows, as a JSON-able dict.

A scene builder takes the scene's parameters (a section of ``workflow/config.yaml``, SI units)
and returns plain data. Workflow scripts, notebooks and the regression test all call
:func:`build_scene` (by name: :func:`flutterfriction.registry.build_scene`), so the numbers
checked in CI are the numbers drawn in the figures.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from flutterfriction.scenes.sweep import Sweep, combine_parts, compute_part

SceneBuilder = Callable[[dict[str, Any]], dict[str, Any]]


def build_scene(name: str, params: dict[str, Any], compute: SceneBuilder) -> dict[str, Any]:
    """Scene ``name`` computed by ``compute`` from its parameters; the result records the
    parameters it used. (By name: :func:`flutterfriction.registry.build_scene`.)"""
    return {"scene": name, "params": params, **compute(dict(params))}


def build_scene_part(name: str, params: dict[str, Any], part: int, n_parts: int,
                     sweep: Sweep) -> dict[str, Any]:
    """Block ``part`` of ``n_parts`` of the sweep scene ``name``."""
    return {"scene": name, **compute_part(sweep, dict(params), part, n_parts)}


def combine_scene_parts(name: str, params: dict[str, Any], parts: list[dict[str, Any]],
                        sweep: Sweep) -> dict[str, Any]:
    """The sweep scene ``name`` gathered from its parts (same data as :func:`build_scene`)."""
    return {"scene": name, "params": params, **combine_parts(sweep, dict(params), parts)}
