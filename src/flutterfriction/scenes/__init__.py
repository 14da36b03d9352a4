"""Scene builders: each returns exactly the data one figure or table shows, as a JSON-able dict.

A scene builder takes the scene's parameters (a section of ``workflow/config.yaml``, SI units)
and returns plain data. Workflow scripts, notebooks and the regression test all call
:func:`build_scene`, so the numbers checked in CI are the numbers drawn in the figures.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from flutterfriction.errors import ParameterError
from flutterfriction.scenes.sweep import Sweep, combine_parts, compute_part

SceneBuilder = Callable[[dict[str, Any]], dict[str, Any]]

#: Scene name -> "module:function" in this package, imported on first use: a workflow job
#: imports only its own scene's module (and its solvers), not every one (saves ~1 s a job).
SCENES: dict[str, str] = {
    "eq25": "ziegler:eq25",
    "eq46": "ziegler:follower_load_scene",
    "eq47": "ziegler:follower_load_scene",
    "eq48": "ziegler:follower_load_scene",
    "fig02": "ziegler:fig02",
    "fig03": "ziegler:fig03",
    "fig04": "ziegler:fig04",
    "errata_ziegler": "ziegler:errata",
    "fig05": "ziegler_damped:fig05",
    "paradox_limit": "ziegler_damped:paradox_limit",
    "fig19_theory": "ziegler_damped:fig19_theory",
    "paradox_map": "ziegler_damped:paradox_map",
    "damped_dead_load": "ziegler_damped:damped_dead_load",
    "errata_damped": "ziegler_damped:errata_damped",
    "fig11": "rod:fig11",
    "fig12": "rod:fig12",
    "errata_rods": "rod:errata_rods",
    "rod_fe_convergence": "rod:rod_fe_convergence",
    "rod_stability_map": "rod:rod_stability_map",
    "self_adjoint": "rod:self_adjoint",
    "fig22": "solids:fig22",
    "acoustic_eigenvalues": "solids:acoustic_eigenvalues",
    "localization_directions": "solids:localization_directions",
    "flutter_map": "solids:flutter_map",
    "solids_statements": "solids:solids_statements",
    "errata_solids": "solids:errata_solids",
    "fig13": "ziegler_nonlinear:fig13",
    "fig14": "ziegler_nonlinear:fig14",
    "fig20": "ziegler_nonlinear:fig20",
    "fig21": "ziegler_nonlinear:fig21",
    "beck_limit_cycle": "rod:beck_limit_cycle",
    "beck_work_precision": "rod:beck_work_precision",
    "beck_linearisation": "rod:beck_linearisation",
    "beck_hopf": "rod:beck_hopf",
    "limit_cycle_amplitude": "ziegler_nonlinear:limit_cycle_amplitude",
    "pendulum_work_precision": "ziegler_nonlinear:pendulum_work_precision",
}


#: Scenes computed as sweeps: the workflow scatters their points over ``sweep_parts`` jobs.
SWEEPS: dict[str, str] = {
    "limit_cycle_amplitude": "ziegler_nonlinear:LIMIT_CYCLE_AMPLITUDE",
    "rod_stability_map": "rod:ROD_STABILITY_MAP",
}


def _resolve(spec: str):
    module, attr = spec.split(":")
    return getattr(importlib.import_module(f"flutterfriction.scenes.{module}"), attr)


def scene_builder(name: str) -> SceneBuilder:
    """The function that computes scene ``name``."""
    if name not in SCENES:
        raise ParameterError(f"unknown scene {name!r}; known scenes: {sorted(SCENES)}")
    return _resolve(SCENES[name])


def _sweep(name: str) -> Sweep:
    if name not in SWEEPS:
        raise ParameterError(f"{name!r} is not a sweep; sweeps: {sorted(SWEEPS)}")
    return _resolve(SWEEPS[name])


def build_scene_part(name: str, params: dict[str, Any], part: int, n_parts: int
                     ) -> dict[str, Any]:
    """Block ``part`` of ``n_parts`` of the sweep scene ``name``."""
    return {"scene": name, **compute_part(_sweep(name), dict(params), part, n_parts)}


def combine_scene_parts(name: str, params: dict[str, Any], parts: list[dict[str, Any]]
                        ) -> dict[str, Any]:
    """The sweep scene ``name`` gathered from its parts (same data as :func:`build_scene`)."""
    return {"scene": name, "params": params,
            **combine_parts(_sweep(name), dict(params), parts)}


def build_scene(name: str, params: dict[str, Any]) -> dict[str, Any]:
    """Compute scene ``name`` from its parameters; the result records the parameters it used."""
    data = scene_builder(name)(dict(params))
    return {"scene": name, "params": params, **data}
