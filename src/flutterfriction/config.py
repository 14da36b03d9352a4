"""Reading ``workflow/config.yaml``: one scene's parameters with the fidelity preset applied."""

from __future__ import annotations

import copy
import json
import math
from collections import OrderedDict
from collections.abc import Callable, Iterable, Iterator, Mapping
from fractions import Fraction
from pathlib import Path
from typing import Any

import yaml

from flutterfriction.errors import (
    PLAIN_INTEGER,
    PLAIN_NUMBER,
    ConvergenceError,
    ParameterError,
    underflows,
)

TOP_LEVEL_KEYS = {"fidelity", "fidelity_presets", "scenes", "stress", "sweep_parts"}
#: The workflow's configuration schema (in a checkout, beside the package): the configuration
#: check reads it, and so do the scenes' Python entry points (:func:`scene_problems`).
CONFIG_SCHEMA = Path(__file__).resolve().parents[2] / "workflow" / "schemas" / \
    "config.schema.yaml"

_MERGE_TAG = "tag:yaml.org,2002:merge"
_FLOAT_TAG = "tag:yaml.org,2002:float"

#: PyYAML's libyaml-backed safe loader where the installation has it, else the pure-Python
#: one: the same documents (the same SafeConstructor and resolver), ~10x faster on the
#: reference file, which every ``snakemake`` start reads and checks (0.15 s -> 0.012 s).
SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def safe_load(stream: Any) -> Any:
    """``yaml.safe_load`` with :data:`SAFE_LOADER`."""
    return yaml.load(stream, Loader=SAFE_LOADER)  # noqa: S506 (a safe loader)


def yaml_file_problems(path: str | Path) -> list[str]:
    """What the YAML (or JSON) file at ``path`` says that its parsed values no longer show,
    one line each naming where it sits: a mapping key written twice (PyYAML and Snakemake
    keep the last value silently: ``fidelity: quick`` then ``fidelity: paper`` would run the
    paper preset; a key that overrides one merged in by ``<<: *anchor`` is not a duplicate),
    and a number that underflows to 0 (``1.0e-400`` is read as 0.0: a damping taken as none;
    :func:`flutterfriction.errors.underflows`). A file that does not parse gives no line here
    (its parser reports it)."""
    try:
        with open(path, encoding="utf-8") as fh:
            root = yaml.compose(fh, Loader=SAFE_LOADER)
    except (OSError, yaml.YAMLError):
        return []
    lines: list[str] = []
    visited: set[int] = set()  # an alias is the anchored node itself: reported once

    def walk(node: Any, where: tuple) -> None:
        if node is None or id(node) in visited:
            return
        visited.add(id(node))
        if isinstance(node, yaml.MappingNode):
            first: dict[tuple[str, str], int] = {}
            for key, value in node.value:
                if key.tag == _MERGE_TAG:
                    continue
                if isinstance(key, yaml.ScalarNode):
                    line = key.start_mark.line + 1
                    ident = (key.tag, key.value)
                    if ident in first:
                        lines.append(f"{path}: {_where(where)}: key {key.value!r} given twice "
                                     f"at line {line} (first at line {first[ident]}; YAML "
                                     f"would keep the last silently)")
                    else:
                        first[ident] = line
                    walk(value, (*where, key.value))
                else:
                    walk(value, (*where, "?"))
        elif isinstance(node, yaml.SequenceNode):
            for i, item in enumerate(node.value):
                walk(item, (*where, i))
        elif isinstance(node, yaml.ScalarNode) and node.tag == _FLOAT_TAG \
                and PLAIN_NUMBER.fullmatch(node.value.strip()) and underflows(node.value):
            lines.append(f"{path}: {_where(where)}: {node.value} (line "
                         f"{node.start_mark.line + 1}) underflows to 0 in double precision "
                         f"(below 2.5e-324): give a value in the parameter's range")

    walk(root, ())
    return lines


def load_yaml(path: str | Path) -> Any:
    """``yaml.safe_load`` of the file at ``path``, refusing a key written twice in a mapping
    and an underflowing number (:func:`yaml_file_problems`; :class:`ParameterError` listing
    them, one line each)."""
    problems = yaml_file_problems(path)
    if problems:
        raise ParameterError("\n".join(problems))
    with open(path, encoding="utf-8") as fh:
        return safe_load(fh)


def expand_parameter_lists(config: dict[str, Any]) -> list[str]:
    """Replace, in place, every chapter list named in a scene section (``pendulum: list47``,
    ``rod: list119``; :data:`flutterfriction.parameters.LISTS`) by its values; one line per
    unknown name (empty when all resolve)."""
    from flutterfriction.parameters import NAMED_KEYS, parameter_list

    problems = []
    scenes = config.get("scenes") or {}
    if not isinstance(scenes, dict):  # the schema names it (a mapping of scene sections)
        return problems
    for scene, section in scenes.items():
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
    config = load_yaml(path)
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
        elif err.validator == "type" and isinstance(err.instance, str) \
                and _reads_as(err.instance, err.validator_value):
            message = _string_number_message(err.instance, err.validator_value)
        elif err.validator in ("required", "enum", "minimum", "maximum", "exclusiveMinimum",
                               "exclusiveMaximum", "minItems", "maxItems", "type"):
            message = err.message
        else:
            message = f"invalid value ({err.validator} {err.validator_value!r})"
        if len(message) > 300:
            message = message[:300] + " ..."
        lines.append(f"{prefix}{_where(err.path)}: {message}")
    return lines




def _reads_as(text: str, expected: Any) -> bool:
    """Whether the string ``text`` spells a value of the JSON-schema type(s) ``expected``."""
    kinds = [expected] if isinstance(expected, str) else list(expected)
    text = text.strip()
    return (("number" in kinds and bool(PLAIN_NUMBER.fullmatch(text)))
            or ("integer" in kinds and bool(PLAIN_INTEGER.fullmatch(text)))
            or ("boolean" in kinds and text.lower() in ("true", "false")))


def _string_number_message(text: str, expected: Any) -> str:
    """Why a number (or boolean) arrived as a string, and how to give it (the two ways it
    happens: ``snakemake --config`` nested values, and YAML 1.1's floats)."""
    kind = expected if isinstance(expected, str) else " or ".join(expected)
    message = (f"{text!r} is a string, not a {kind} (quoted in a YAML file, or nested in "
               f"snakemake --config, which passes scenes={{...}} as strings: give nested values "
               f"unquoted in a --configfile)")
    mantissa, e, exponent = text.strip().lower().partition("e")
    if e and ("." not in mantissa or exponent[:1] not in "+-"):
        fixed = (mantissa if "." in mantissa else mantissa + ".0") + "e" + \
            (exponent if exponent[:1] in "+-" else "+" + exponent)
        message += (f"; in a YAML file write {fixed} (YAML 1.1 reads an exponent without a "
                    f"decimal point or without its sign as a string)")
    return message


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
                # the model's numerical range too (ratios, mass matrix, viscosities): the
                # scenes' solvers refuse a pendulum outside it when their job runs
                ZieglerPendulum(**value).check_numerical_range()
            elif key == "rod" and isinstance(value, dict):
                _rod_groups(Rod(**value))
        except _MODEL_ERRORS as exc:
            lines.append(f"{where}: {' '.join(str(exc).split())}")
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
        if isinstance(value, dict) and all(isinstance(value.get(k), int | float)
                                           for k in ("lam", "mu")):
            # an isotropic solid: positive definite (the acoustic tensor's numerical range)
            from flutterfriction.analysis.acoustic import LAM_OVER_MU_MAX

            lam, mu = value["lam"], value["mu"]
            if not mu > 0 or not -2.0 / 3.0 < lam / mu <= LAM_OVER_MU_MAX:
                lines.append(f"{where}: needs mu > 0 and -2/3 < lam/mu <= {LAM_OVER_MU_MAX:g} "
                             f"(positive definite isotropic elasticity), got lam = {lam}, "
                             f"mu = {mu}")
        if isinstance(key, str) and key.endswith("_min") and isinstance(value, int | float):
            upper = _lookup(params, (*path[:-1], key[:-4] + "_max"))
            if isinstance(upper, int | float) and not value < upper:
                lines.append(f"{where}: must be < {key[:-4]}_max = {upper}, got {value}")
    return lines + _scene_specific_problems(scene, params, prefix)


def _scene_specific_problems(scene: str, params: dict[str, Any], prefix: str) -> list[str]:
    """Constraints between one scene's keys that its job would otherwise fail on (an outside
    audit: each ended in a traceback in a job's log): Fig. 4's drawing interval within each
    case's duration; Fig. 18's lever not wedged (mu r < l1 + l2)."""
    where = f"{prefix}scenes.{scene}"
    lines = []
    if scene == "fig04" and isinstance(params.get("dt"), int | float) \
            and isinstance(params.get("cases"), dict):
        for name, case in params["cases"].items():
            duration = case.get("duration") if isinstance(case, dict) else None
            if isinstance(duration, int | float) and not params["dt"] <= duration:
                lines.append(f"{where}.dt: must be <= cases.{name}.duration = {duration} s "
                             f"(a frame at least), got {params['dt']}")
            elif isinstance(duration, int | float) and params["dt"] > 0 \
                    and duration / params["dt"] > FIG04_MAX_FRAMES:
                # (a duration of 1e300 s ended in numpy's "Maximum allowed size exceeded")
                lines.append(f"{where}.cases.{name}.duration: at most {FIG04_MAX_FRAMES} frames "
                             f"of dt = {params['dt']} s, got {duration / params['dt']:.3g}")
    if scene in UNDAMPED_SCENES:
        pend = _pendulum_of(params)
        viscous = {k: pend[k] for k in ("c1", "c2")
                   if isinstance(pend, dict) and isinstance(pend.get(k), int | float)
                   and pend[k] != 0}
        if viscous:
            lines.append(f"{where}.pendulum: c1 = c2 = 0 here (this scene's closed forms and "
                         "critical loads are the undamped ones, eqs. (19)-(48); viscous hinges "
                         "are §2.4's scenes), got "
                         + ", ".join(f"{k} = {v:g} N m s" for k, v in viscous.items()))
    if scene == "fig18":
        pend = _pendulum_of(params)
        mu, r = params.get("mu", 0.25), params.get("wheel_radius", 0.02)
        if isinstance(pend, dict) and all(isinstance(pend.get(k), int | float)
                                          for k in ("l1", "l2")) \
                and isinstance(mu, int | float) and isinstance(r, int | float) \
                and all(math.isfinite(x) for x in (mu, r, pend["l1"] + pend["l2"])) \
                and not Fraction(pend["l1"] + pend["l2"]) - Fraction(mu) * Fraction(r) > 0:
            # decided as the lever decides it, exactly (models.apparatus.FrictionLever)
            lines.append(f"{where}.wheel_radius: mu * wheel_radius = {mu * r:g} m must be < "
                         f"l1 + l2 = {pend['l1'] + pend['l2']:g} m (else the friction's moment "
                         "wedges the lever)")
    return lines


#: Fig. 4's frames per case (duration / dt): the chapter draws 12 and 6.
FIG04_MAX_FRAMES = 1000
#: The scenes of the undamped pendulum (§2.2-2.3): a viscous pendulum there was computed as
#: undamped and its regime checks compared damped and undamped verdicts (an outside audit).
UNDAMPED_SCENES = ("fig03", "fig04", "eq25", "eq46", "eq47", "eq48", "errata_ziegler")


def _pendulum_of(params: dict[str, Any]) -> Any:
    """A scene's pendulum as a dict (a chapter list by name resolved), else as given."""
    pend = params.get("pendulum")
    if isinstance(pend, str):
        from flutterfriction.parameters import LISTS, parameter_list

        pend = parameter_list(pend) if pend in LISTS else None
    return pend

# (ConvergenceError too: a scene's check that solves, e.g. the flutter load of the linearised
# rod or the acoustic tensor's interval, says so in one line instead of a traceback that
# stopped every scene; the review of this session's change)
_MODEL_ERRORS = (ParameterError, ConvergenceError, TypeError, ValueError, ZeroDivisionError,
                 OverflowError)

#: Eq. (106)'s groups and the rod parameter that makes each non-zero.
_GROUP_SOURCES = {"eta": ("D", "eta = D/(B l^2) sqrt(B/rho)"),
                  "gamma": ("kappa", "gamma = kappa l^2/sqrt(rho B)"),
                  "tan_alpha": ("tip_mass", "tan(alpha) = M/(rho l)")}


def _rod_groups(rod: Any) -> Any:
    """The rod's groups of eq. (106) within the rod solver's range
    (:func:`flutterfriction.analysis.rod.check_groups`); a group that rounds to 0 although
    its parameter is positive (below the double range) is refused too."""
    from flutterfriction.analysis.rod import check_groups

    g = rod.groups()
    for group, (source, formula) in _GROUP_SOURCES.items():
        if getattr(rod, source) > 0 and getattr(g, group) == 0:
            raise ParameterError(f"{source} = {getattr(rod, source)!r} > 0 but {formula} "
                                 f"rounds to 0 (below the double range): rescale the rod")
    try:
        check_groups(g)
    except ParameterError as exc:
        group = str(exc).split(" ", 1)[0]
        formula = _GROUP_SOURCES.get(group, ("", group))[1]
        raise ParameterError(f"{exc}; {formula} of this rod (eq. 106)") from None
    return g


def _number_at(params: dict[str, Any], key: str) -> float | None:
    value = params.get(key)
    if isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value):
        return value
    return None


#: Scenes' tip-mass ratios tan(alpha) given directly (the rod solver refuses > 1e4).
_TAN_ALPHA_KEYS = {"fig10": ("pfluger_tan_alpha",), "fig12": ("tan_alpha", "stated_tan_alpha"),
                   "errata_rods": ("stated_tan_alpha",)}
#: Scenes whose finite-element twin (analysis.rod.fe_critical_loads) solves the damped rod.
_FE_DAMPED_ROD_SCENES = ("fig11", "fig12")


def _rod_scene_problems(scene: str, params: dict[str, Any], prefix: str) -> list[str]:
    """What the rod scenes hand the rod solver, checked against its ranges before any job:
    tip-mass ratios (and the stability map's range of them) within
    :data:`~flutterfriction.analysis.rod.GROUP_RANGES`, ``p_max`` within ``P_MAX_LIMIT``,
    and a damping the finite-element twin resolves (0 or at least ``DAMPING_FLOOR``)."""
    from flutterfriction.analysis.rod import (
        DAMPING_FLOOR,
        GROUP_RANGES,
        P_MAX_LIMIT,
        check_groups,
    )
    from flutterfriction.models.rod import Rod, RodGroups

    lines: list[str] = []

    def bad(key: str, message: str) -> None:
        lines.append(f"{prefix}scenes.{scene}.{key}: {message}")

    tan_max, eta_max = GROUP_RANGES["tan_alpha"][1], GROUP_RANGES["eta"][1]
    tan_note = ("tan(alpha) = M/(rho l), the rod solver's numerical range, "
                "analysis.rod.GROUP_RANGES")
    for key in _TAN_ALPHA_KEYS.get(scene, ()):
        v = _number_at(params, key)
        if v is not None and v > tan_max:
            bad(key, f"must be in [0, {tan_max:g}] ({tan_note}), got {v!r}")
    bracket = params.get("bracket")
    if scene == "errata_rods" and isinstance(bracket, list) \
            and all(isinstance(v, int | float) for v in bracket) \
            and any(not 0 <= v <= tan_max for v in bracket):
        bad("bracket", f"the tan(alpha) bracket must lie in [0, {tan_max:g}] ({tan_note}), "
                       f"got {bracket}")
    p_max = _number_at(params, "p_max")
    if scene in ("fig10", "fig11", "fig12") and p_max is not None and p_max > P_MAX_LIMIT:
        bad("p_max", f"must be in (0, {P_MAX_LIMIT:g}] (the rod solver's load range, "
                     f"analysis.rod.P_MAX_LIMIT), got {p_max!r}")

    def fe_damping(key: str, g: Any) -> None:
        damping = max(g.eta, g.gamma)
        if 0 < damping < DAMPING_FLOOR:
            bad(key, f"the damping max(eta, gamma) = {damping:.3g} (eq. 106) must be 0 or >= "
                     f"{DAMPING_FLOOR:g}: the scene's finite-element twin cannot resolve the "
                     f"flutter crossing below analysis.rod.DAMPING_FLOOR")

    if scene in _FE_DAMPED_ROD_SCENES and isinstance(params.get("rod"), dict):
        try:
            g = _rod_groups(Rod(**params["rod"]))
        except _MODEL_ERRORS:
            pass  # reported with the rod itself
        else:
            fe_damping("rod", g)
    if scene == "rod_fe_convergence" and isinstance(params.get("cases"), dict):
        for name, spec in params["cases"].items():
            if not isinstance(spec, dict):
                continue
            try:
                g = check_groups(RodGroups(**spec))
            except _MODEL_ERRORS as exc:
                bad(f"cases.{name}", " ".join(str(exc).split()))
            else:
                fe_damping(f"cases.{name}", g)
    if scene == "rod_stability_map":
        rng = params.get("log10_ratio_range")
        if isinstance(rng, list) and len(rng) == 2 \
                and all(isinstance(v, int | float) for v in rng) \
                and rng[1] > math.log10(tan_max):
            bad("log10_ratio_range", f"the largest tip-mass ratio 10^{rng[1]:g} must be <= "
                                     f"{tan_max:g} ({tan_note}): the upper end must be <= "
                                     f"{math.log10(tan_max):g}, got {rng}")
        eta = _number_at(params, "eta_small")
        if eta is not None and not DAMPING_FLOOR <= eta <= eta_max:
            bad("eta_small", f"must be in [{DAMPING_FLOOR:g}, {eta_max:g}]: at least "
                             f"analysis.rod.DAMPING_FLOOR (the scene's 64-element "
                             f"finite-element check cannot resolve the flutter crossing "
                             f"below it) and at most the rod solver's eta range "
                             f"(analysis.rod.GROUP_RANGES), got {eta!r}")
    return lines


def _scene_value_problems(scene: str, params: dict[str, Any], prefix: str,
                          check: Callable[[dict[str, Any]], None] | None) -> list[str]:
    """One scene's parameters past its schema: non-finite numbers, the physical constraints
    (:func:`_physical_problems`), the rod solver's ranges (:func:`_rod_scene_problems`) and,
    if those pass, the scene's own ``check`` (its refusals of what it would find out only
    after costly work)."""
    found = _physical_problems(scene, params, prefix)
    found += _rod_scene_problems(scene, params, prefix)
    if check is not None and not found:
        verdict = _check_verdict(check, params)
        if verdict is not None:
            found.append(f"{prefix}scenes.{scene}: {verdict}")
    return found


_SCHEMAS: dict[tuple[str, float], dict[str, Any]] = {}


def _schema_at(path: str | Path) -> dict[str, Any]:
    """The schema file ``path``, parsed once per process and version of the file."""
    path = Path(path)
    key = (str(path.resolve()), path.stat().st_mtime)
    if key not in _SCHEMAS:
        with open(path, encoding="utf-8") as fh:
            _SCHEMAS[key] = safe_load(fh)
    return _SCHEMAS[key]


def scene_problems(scene: str, params: dict[str, Any],
                   check: Callable[[dict[str, Any]], None] | None = None,
                   schema_path: str | Path = CONFIG_SCHEMA) -> list[str]:
    """Every problem of one scene's parameters as the configuration check finds it, one line
    each naming the key (``scenes.<scene>.<key>: ...``): the scene's section of the schema
    (types: an integer is not 2.5, True or "3"; ranges; unknown keys), non-finite numbers,
    the physical constraints and the solvers' ranges, then ``check`` (the scene's own
    refusals of costly work). The scenes' Python entry points
    (:func:`flutterfriction.registry.build_scene`) run it before any work, as the workflow
    does before any job. Without the schema file (a package installed without its
    checkout) the schema part is skipped. An empty list means valid."""
    if not isinstance(params, dict):
        return [f"scenes.{scene}: the parameters must be a mapping, got {type(params).__name__}"]
    if Path(schema_path).is_file():
        schema = _schema_at(schema_path)
        section = ((schema.get("properties") or {}).get("scenes") or {}).get(
            "properties", {}).get(scene)
        if section is not None:
            wrapped = {"$defs": schema.get("$defs", {}), "type": "object",
                       "properties": {scene: section}}
            lines = _schema_problems({scene: params}, wrapped, "scenes.")
            if lines:
                return lines
    return _scene_value_problems(scene, params, "", check)


def _lookup(tree: Any, path: tuple) -> Any:
    for p in path:
        if not isinstance(tree, dict) or p not in tree:
            return None
        tree = tree[p]
    return tree


#: A scene check's verdict (None: passed; else its one-line refusal) per check and parameters,
#: for the process: the checks are pure functions of their parameters, and every preset that
#: leaves a scene alone, Figs. 13 and 14 (which share theirs), and each configuration checked
#: again (a test suite: ~90 checks of the same configuration) would otherwise solve the same
#: small problems again. The newest :data:`CHECK_VERDICTS_KEPT` are kept.
_CHECK_VERDICTS: OrderedDict[tuple[Any, str], str | None] = OrderedDict()
CHECK_VERDICTS_KEPT = 1024


def _check_verdict(check: Callable[[dict[str, Any]], None], params: dict[str, Any]
                   ) -> str | None:
    """``check(params)``'s verdict, computed once per distinct parameters (an error other
    than the models' refusals propagates and is not kept)."""
    key = (check, json.dumps(params, sort_keys=True, default=str))
    if key in _CHECK_VERDICTS:
        _CHECK_VERDICTS.move_to_end(key)
        return _CHECK_VERDICTS[key]
    try:
        check(copy.deepcopy(params))
        verdict = None
    except _MODEL_ERRORS as exc:
        verdict = " ".join(str(exc).split())
    _CHECK_VERDICTS[key] = verdict
    while len(_CHECK_VERDICTS) > CHECK_VERDICTS_KEPT:
        _CHECK_VERDICTS.popitem(last=False)
    return verdict


def validate_config(config: dict[str, Any], schema_path: str | Path,
                    scenes: Iterable[str] | None = None) -> list[str]:
    """Every problem of a workflow configuration, one line each, before any job runs: the JSON
    schema on the file as written; unknown top-level keys and preset overrides naming unknown
    scenes or keys; then, for *every* fidelity preset, the schema and the physical constraints
    (pendulum and rod geometry, finite numbers, ordered ranges) on each scene's parameters as
    that preset resolves them, so a misspelled or out-of-range override fails whichever preset
    is active. With ``scenes`` (the registered scene names), a section naming no registered
    scene is refused too; given as the registry's mapping (name -> Scene), each scene's own
    ``check`` runs on its resolved parameters as well (a load outside the interval where its
    cycle exists, a motion too long to integrate: refusals its job would reach only after
    costly work). An empty list means valid."""
    with open(schema_path, encoding="utf-8") as fh:
        schema = safe_load(fh)
    config = copy.deepcopy(config)
    # An unknown list name is one problem among the others (it hid them all); the schema's
    # complaint about the same key (a string where a mapping belongs) is left out.
    problems = expand_parameter_lists(config)
    unresolved = {line.split(": ", 2)[1] for line in problems}
    problems += [line for line in _schema_problems(config, schema, "config: ")
                 if line.split(": ", 2)[1] not in unresolved]
    if scenes is not None and isinstance(config.get("scenes") or {}, dict):
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
            check = getattr(scenes.get(scene), "check", None) \
                if isinstance(scenes, Mapping) else None
            lines += _scene_value_problems(scene, params, prefix, check)
        seen = {p.split(": ", 1)[1] for p in problems}
        problems += [line for line in lines if line.split(": ", 1)[1] not in seen]
    return problems
