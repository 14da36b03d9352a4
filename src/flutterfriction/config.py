"""Reading ``workflow/config.yaml``: one scene's parameters with the fidelity preset applied."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from flutterfriction.errors import ParameterError

TOP_LEVEL_KEYS = {"fidelity", "fidelity_presets", "scenes", "sweep_parts"}


def load_config(path: str | Path) -> dict[str, Any]:
    """Load the workflow configuration and reject unknown top-level keys by name."""
    with open(path, encoding="utf-8") as fh:
        config = yaml.safe_load(fh)
    if not isinstance(config, dict):
        raise ParameterError(f"{path}: the configuration must be a mapping")
    unknown = sorted(set(config) - TOP_LEVEL_KEYS)
    if unknown:
        raise ParameterError(f"{path}: unknown key(s) {unknown}; allowed: {sorted(TOP_LEVEL_KEYS)}")
    return config


def scene_params(config: dict[str, Any], scene: str) -> dict[str, Any]:
    """Parameters of ``scene``, with the active fidelity preset overriding the keys it names.

    A preset only overrides keys the scene already has (e.g. ``n_points``), so a scene computes
    only what it shows and presets never add parameters a scene does not accept.
    """
    scenes = config.get("scenes", {})
    if scene not in scenes:
        raise ParameterError(f"no scene {scene!r} in the configuration; known: {sorted(scenes)}")
    fidelity = config.get("fidelity", "paper")
    presets = config.get("fidelity_presets", {})
    if fidelity not in presets:
        raise ParameterError(f"fidelity must be one of {sorted(presets)}, got {fidelity!r}")
    params = dict(scenes[scene])
    params.update({k: v for k, v in presets[fidelity].items() if k in params})
    return _canonical(params)


def _canonical(value: Any) -> Any:
    """Recursively key-sorted copy: Snakemake's params rerun trigger compares representations,
    so the same parameters written in another key order must not look changed."""
    if isinstance(value, dict):
        return {k: _canonical(value[k]) for k in sorted(value)}
    if isinstance(value, list):
        return [_canonical(v) for v in value]
    return value
