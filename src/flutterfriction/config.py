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
    _check_preset_scenes(config)
    return config


def _check_preset_scenes(config: dict[str, Any]) -> None:
    """A preset's per-scene overrides must name existing scenes and keys they already have."""
    scenes = config.get("scenes", {})
    for name, preset in (config.get("fidelity_presets") or {}).items():
        for scene, over in ((preset or {}).get("scenes") or {}).items():
            if scene not in scenes:
                raise ParameterError(f"fidelity_presets.{name}.scenes: unknown scene {scene!r}")
            extra = sorted(set(over) - set(scenes[scene]))
            if extra:
                raise ParameterError(f"fidelity_presets.{name}.scenes.{scene}: keys {extra} "
                                     f"are not parameters of {scene!r}")


def scene_params(config: dict[str, Any], scene: str) -> dict[str, Any]:
    """Parameters of ``scene``, with the active fidelity preset overriding the keys it names.

    A preset only overrides keys the scene already has (e.g. ``n_points``), so a scene computes
    only what it shows and presets never add parameters a scene does not accept. A preset's
    ``scenes`` section overrides keys of one scene only (e.g. the meshes of the rod's cycle).
    """
    scenes = config.get("scenes", {})
    if scene not in scenes:
        raise ParameterError(f"no scene {scene!r} in the configuration; known: {sorted(scenes)}")
    fidelity = config.get("fidelity", "paper")
    presets = config.get("fidelity_presets", {})
    if fidelity not in presets:
        raise ParameterError(f"fidelity must be one of {sorted(presets)}, got {fidelity!r}")
    params = dict(scenes[scene])
    preset = dict(presets[fidelity])
    per_scene = preset.pop("scenes", {}) or {}
    params.update({k: v for k, v in preset.items() if k in params})
    params.update({k: v for k, v in per_scene.get(scene, {}).items() if k in params})
    return _canonical(params)


def _canonical(value: Any) -> Any:
    """Recursively key-sorted copy: Snakemake's params rerun trigger compares representations,
    so the same parameters written in another key order must not look changed."""
    if isinstance(value, dict):
        return {k: _canonical(value[k]) for k in sorted(value)}
    if isinstance(value, list):
        return [_canonical(v) for v in value]
    return value
