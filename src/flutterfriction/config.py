"""Reading ``workflow/config.yaml``: one scene's parameters with the fidelity preset applied."""

from __future__ import annotations

import copy
import math
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

import yaml

from flutterfriction.errors import ParameterError

TOP_LEVEL_KEYS = {"fidelity", "fidelity_presets", "scenes", "sweep_parts"}


def expand_parameter_lists(config: dict[str, Any]) -> list[str]:
    """Replace, in place, every chapter list named in a scene section (``pendulum: list47``,
    ``rod: list119``; :data:`flutterfriction.parameters.LISTS`) by its values; one line per
    unknown name (empty when all resolve)."""
    from flutterfriction.parameters import NAMED_KEYS, parameter_list

    problems = []
    for scene, section in (config.get("scenes") or {}).items():
        for key, kind in NAMED_KEYS.items():
            if isinstance(section, dict) and isinstance(section.get(key), str):
                try:
                    section[key] = parameter_list(section[key], kind)
                except ParameterError as exc:
                    problems.append(f"config: scenes.{scene}.{key}: {exc}")
    return problems


def load_config(path: str | Path) -> dict[str, Any]:
    """Load the workflow configuration (chapter lists named in it resolved) and reject
    unknown top-level keys by name."""
    with open(path, encoding="utf-8") as fh:
        config = yaml.safe_load(fh)
    if not isinstance(config, dict):
        raise ParameterError(f"{path}: the configuration must be a mapping")
    problems = expand_parameter_lists(config)
    if problems:
        raise ParameterError(problems[0])
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
    scenes = config.get("scenes") or {}
    fidelity = config.get("fidelity", "paper")
    presets = config.get("fidelity_presets", {})
    if fidelity not in presets:
        raise ParameterError(f"fidelity must be one of {sorted(presets)}, got {fidelity!r}")
    params = dict(scenes.get(scene) or {})  # a scene without a section: its own defaults
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


# --------------------------------------------------------------------------- validation
def _where(path) -> str:
    return ".".join(str(p) for p in path) or "(top level)"


def _schema_problems(config: dict[str, Any], schema: dict[str, Any], prefix: str) -> list[str]:
    """One short line per schema violation (the offending instance is not dumped: a whole
    scene section would print hundreds of lines)."""
    import jsonschema
    from jsonschema import validators

    # An integer is an int: JSON Schema counts 101.0 as one, and the scenes would refuse it.
    strict = validators.extend(jsonschema.Draft202012Validator,
                               type_checker=jsonschema.Draft202012Validator.TYPE_CHECKER.redefine(
                                   "integer", lambda _, x: isinstance(x, int)
                                   and not isinstance(x, bool)))
    validator = strict(schema)
    lines = []
    for err in sorted(validator.iter_errors(config), key=lambda e: list(map(str, e.path))):
        if err.validator == "additionalProperties":
            allowed = sorted(err.schema.get("properties", {}))
            extra = sorted(set(err.instance) - set(allowed))
            message = f"unknown key(s) {extra}; allowed: {allowed}"
        elif err.validator in ("required", "enum", "minimum", "maximum", "exclusiveMinimum",
                               "exclusiveMaximum", "minItems", "maxItems", "type"):
            message = err.message
        else:
            message = f"invalid value ({err.validator} {err.validator_value!r})"
        if len(message) > 300:
            message = message[:300] + " ..."
        lines.append(f"{prefix}{_where(err.path)}: {message}")
    return lines


def _walk(value: Any, path: tuple = ()) -> Iterator[tuple[tuple, Any]]:
    yield path, value
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _walk(v, (*path, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _walk(v, (*path, i))


def _physical_problems(scene: str, params: dict[str, Any], prefix: str) -> list[str]:
    """Constraints a JSON schema cannot state: the geometry of a pendulum (d <= l1, h <= l2)
    and a rod, non-finite numbers, and ranges whose ends must be ordered."""
    from flutterfriction.models.rod import Rod
    from flutterfriction.models.ziegler import ZieglerPendulum

    lines = []
    for path, value in _walk(params):
        where = f"{prefix}scenes.{scene}.{_where(path)}" if path else f"{prefix}scenes.{scene}"
        if isinstance(value, float) and not math.isfinite(value):
            lines.append(f"{where}: must be a finite number, got {value}")
            continue
        key = path[-1] if path else ""
        try:
            if key in ("pendulum", "cycle_pendulum") and isinstance(value, dict):
                ZieglerPendulum(**value)
            elif key == "rod" and isinstance(value, dict):
                Rod(**value)
        except (ParameterError, TypeError) as exc:
            lines.append(f"{where}: {exc}")
        if isinstance(key, str) and (key.endswith("_range") or key == "bracket") \
                and isinstance(value, list) and len(value) == 2 \
                and all(isinstance(v, int | float) for v in value) and not value[0] < value[1]:
            lines.append(f"{where}: the range must be increasing, got {value}")
        if key == "n" and isinstance(value, list) and value \
                and all(isinstance(v, int | float) for v in value) and not any(value):
            lines.append(f"{where}: must be a non-zero direction, got {value}")
        if key in ("meshes", "elements", "part") and isinstance(value, list) \
                and all(isinstance(v, int | float) for v in value) \
                and not all(a < b for a, b in zip(value, value[1:], strict=False)):
            lines.append(f"{where}: must be strictly increasing, got {value}")
        if isinstance(key, str) and key.endswith("_min") and isinstance(value, int | float):
            upper = _lookup(params, (*path[:-1], key[:-4] + "_max"))
            if isinstance(upper, int | float) and not value < upper:
                lines.append(f"{where}: must be < {key[:-4]}_max = {upper}, got {value}")
    return lines


def _lookup(tree: Any, path: tuple) -> Any:
    for p in path:
        if not isinstance(tree, dict) or p not in tree:
            return None
        tree = tree[p]
    return tree


def validate_config(config: dict[str, Any], schema_path: str | Path,
                    scenes: Iterable[str] | None = None) -> list[str]:
    """Every problem of a workflow configuration, one line each, before any job runs: the JSON
    schema on the file as written; unknown top-level keys and preset overrides naming unknown
    scenes or keys; then, for *every* fidelity preset, the schema and the physical constraints
    (pendulum and rod geometry, finite numbers, ordered ranges) on each scene's parameters as
    that preset resolves them, so a misspelled or out-of-range override fails whichever preset
    is active. With ``scenes`` (the registered scene names), a section naming no registered
    scene is refused too. An empty list means valid."""
    with open(schema_path, encoding="utf-8") as fh:
        schema = yaml.safe_load(fh)
    config = copy.deepcopy(config)
    # An unknown list name is one problem among the others (it hid them all); the schema's
    # complaint about the same key (a string where a mapping belongs) is left out.
    problems = expand_parameter_lists(config)
    unresolved = {line.split(": ", 2)[1] for line in problems}
    problems += [line for line in _schema_problems(config, schema, "config: ")
                 if line.split(": ", 2)[1] not in unresolved]
    if scenes is not None:
        known = set(scenes)
        problems += [f"config: scenes.{name}: no such scene; registered scenes: {sorted(known)}"
                     for name in sorted(set(config.get("scenes") or {}) - known)]
    for path, value in _walk(config):
        if isinstance(value, float) and not math.isfinite(value):
            problems.append(f"config: {_where(path)}: must be a finite number, got {value}")
    if problems:
        return problems
    try:
        _check_preset_scenes(config)
    except ParameterError as exc:
        return [f"config: {exc}"]
    for fidelity in sorted(config.get("fidelity_presets", {})):
        resolved = copy.deepcopy(config)
        resolved["fidelity"] = fidelity
        resolved["scenes"] = {s: scene_params(resolved, s) for s in config["scenes"]}
        prefix = f"config (fidelity {fidelity}): "
        lines = _schema_problems(resolved, schema, prefix)
        for scene, params in resolved["scenes"].items():
            lines += _physical_problems(scene, params, prefix)
        seen = {p.split(": ", 1)[1] for p in problems}
        problems += [line for line in lines if line.split(": ", 1)[1] not in seen]
    return problems
