"""The tolerance check: every number the chapter quotes against what we reproduce.

``workflow/reference.yaml`` lists

- ``quantities``: id, source, quoted value, unit, the scene and key that reproduce it, a
  ``tolerance`` (``atol``, ``rtol`` and ``why``: where the digits come from) and an
  ``agreement`` tolerance between the primary and the independent method;
- ``errata``: printed form, corrected form, evidence, and the scene/key whose data hold the
  printed, corrected and independent values.

An entry whose value depends on resolution (a regression of our own converged value, e.g. a
limit cycle's amplitude) may carry a ``quick`` block with looser ``tolerance``/``agreement``
(each with its ``why``: measured at the quick preset's settings); they apply only when the
workflow runs with ``fidelity: quick``, and the summary marks the rows that used them.

One normalised error is used throughout (as scipy's ODE tests do):
``e = |x - ref| / (atol + rtol |ref|)``; a comparison passes when ``e <= 1``.
An erratum is *verified* when the corrected form agrees with the independent computation and
the printed form does not.

Each quoted value belongs to the chapter's parameters: ``workflow/reference_parameters.json``
records, per preset, the parameters of every scene as the shipped configuration resolves them
(:func:`record_parameters`; a test keeps it equal to the shipped configuration). A scene run
with other parameters (a researcher's own pendulum, rod or soil) is not the chapter's: its
entries are reported *not applicable*, naming the changed keys, instead of failing the run.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import yaml

from flutterfriction.config import safe_load
from flutterfriction.errors import ParameterError, check_nonnegative, check_real
from flutterfriction.figure_offences import Offence, figure_checks_markdown, figure_checks_summary
from flutterfriction.io import markdown_table, write_json, write_text


@dataclass
class CheckRow:
    id: str
    kind: str  # "quantity" | "erratum"
    source: str
    quoted: Any
    unit: str
    reproduced: Any
    independent: Any
    method: str
    independent_method: str
    error: float | None  # normalised error vs the quoted value (or printed vs independent)
    agreement: float | None  # normalised error primary vs independent (or corrected vs indep.)
    status: str  # "pass" | "FAIL" | "verified erratum" | "UNVERIFIED erratum" | NOT_APPLICABLE
    note: str = ""
    origin: str = ""  # a quantity's: a key of ORIGINS ("" for an erratum)

    @property
    def shown_status(self) -> str:
        """The status as tables show it, with the note (e.g. a quick-preset tolerance)."""
        return f"{self.status} ({self.note})" if self.note else self.status


#: Where a quantity's reference value comes from (``origin`` in ``workflow/reference.yaml``;
#: its schema lists the same keys), with the words the summaries use for each.
ORIGINS = {
    "printed": "numbers printed in the chapter",
    "formula": "closed forms of the chapter evaluated where it prints no number",
    "stated": "statements or identities of the chapter (the value each implies)",
    "ours": "values of our own beyond the chapter",
}

QUICK_NOTE = "quick-preset tolerance"
NOT_APPLICABLE = "not applicable"
#: The parameters every quoted value belongs to (see the module's docstring).
REFERENCE_PARAMETERS = Path("workflow/reference_parameters.json")


#: Numerical settings (discretisation, tolerances, iteration and sample counts, plotted
#: ranges) in any scene: a change leaves the chapter's values applicable, checked at the
#: entry's tolerances (an outside audit: fe_elements 32 -> 48, load_steps, n_search and
#: fig05's plotted gamma_max made 28 entries "not applicable" with unchanged values). The keys
#: a preset overrides are added per scene (:func:`record_parameters`).
NUMERICAL_SETTINGS = frozenset({
    "n_points", "n_grid", "n_samples", "n_search", "n_modes", "n_elements", "n_lines",
    "fe_elements", "elements", "meshes", "load_steps", "max_points", "repeats", "tol", "rtol",
    "newton_tol", "variational_rtol", "transient_rtol", "transient_tol", "samples_per_period",
    "error_target", "check_elements", "check_extremes", "dt", "gamma_max"})


def record_parameters(config: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """``{preset: {scene: parameters}}`` as ``config`` (loaded, chapter lists resolved)
    resolves them for each preset: what the workflow's solve jobs record in the data; and
    ``resolution_keys``: ``{scene: keys a preset overrides}``, the resolution keys (``n_points``,
    meshes, tolerances), whose change leaves the chapter's values applicable (checked at the
    entry's tolerances: more resolution passes, less may not)."""
    from flutterfriction.config import scene_params

    presets = config.get("fidelity_presets") or {}
    scenes = sorted(config.get("scenes", {}))
    out: dict[str, Any] = {}
    for fidelity in sorted(presets):
        resolved = dict(config, fidelity=fidelity)
        out[fidelity] = {s: scene_params(resolved, s) for s in scenes}
    keys: dict[str, set] = {s: set() for s in scenes}
    for preset in presets.values():
        preset = dict(preset or {})
        per_scene = preset.pop("scenes", None) or {}
        for s in scenes:
            params = config["scenes"].get(s) or {}
            keys[s] |= {k for k in preset if k in params} | set(per_scene.get(s) or {})
    for s in scenes:
        keys[s] |= NUMERICAL_SETTINGS & set(config["scenes"].get(s) or {})
    out["resolution_keys"] = {s: sorted(k) for s, k in keys.items() if k}
    return out


def parameter_changes(recorded: Any, used: Any, where: str = "") -> list[str]:
    """The keys where ``used`` differs from ``recorded``, one short line each."""
    if isinstance(recorded, dict) and isinstance(used, dict):
        return [line for k in sorted(set(recorded) | set(used))
                for line in parameter_changes(recorded.get(k), used.get(k),
                                              f"{where}.{k}" if where else str(k))]
    return [] if recorded == used else [f"{where or '(all)'}: {recorded!r} -> {used!r}"]


def _not_applicable(entry: dict[str, Any], changes: list[str],
                    data: Mapping[str, Any], fidelity: str = "paper") -> CheckRow:
    """The entry's row for a scene run with other parameters: the values this run computed
    (your own), not compared with the chapter's, the changed keys named. The two methods are
    still compared with each other, at the entry's agreement tolerance: a disagreement FAILs
    (an outside audit: dropping that check too let a viscous pendulum computed as undamped
    pass, its regime "flutter" against the independent "stable")."""
    shown = "; ".join(changes[:3]) + (f"; {len(changes) - 3} more" if len(changes) > 3 else "")
    kind = "quantities" if "quoted" in entry else "errata"
    q = ((data.get(entry["scene"]) or {}).get(kind) or {}).get(entry["key"]) or {}
    value, independent = q.get("value", q.get("corrected")), q.get("independent")
    agreement, agrees = None, True
    if isinstance(value, str) or isinstance(independent, str):
        # a categorical statement: the same word, unless the chapter's two differ by design
        agrees = "quoted_independent" in entry or value == independent
    elif all(isinstance(v, int | float) and not isinstance(v, bool)
             for v in (value, independent)):
        agr_tol = entry["agreement"] if kind == "errata" else _tolerances(entry, fidelity)[1]
        agreement = normalised_error(value, independent, agr_tol)
        agrees = agreement <= 1.0
    note = f"scene {entry['scene']!r} ran with other parameters than the chapter's: {shown}"
    if not agrees:
        note += (f"; its two methods disagree: {value!r} against the independent "
                 f"{independent!r} (where one is a coarser discretisation, your parameters "
                 f"may need the scene's finer resolution: its elements, meshes or "
                 f"tolerances)")
    return CheckRow(id=entry["id"], kind="quantity" if kind == "quantities" else "erratum",
                    source=entry["source"], quoted=entry.get("quoted", entry.get("printed")),
                    unit=entry.get("unit", q.get("unit", "")),
                    reproduced=value, independent=independent, method=q.get("method", ""),
                    independent_method=q.get("independent_method", ""), error=None,
                    agreement=agreement, status=NOT_APPLICABLE if agrees else "FAIL",
                    note=note, origin=entry.get("origin", ""))


def normalised_error(x: float, ref: float, tol: Mapping[str, float]) -> float:
    """``|x - ref| / (atol + rtol |ref|)``; pass when ``<= 1``. The values and the tolerance
    are checked by name (an outside review: NaN and inf gave NaN; "1", True and unknown
    tolerance keys were accepted)."""
    x, ref = check_real("x", x), check_real("ref", ref)
    if not isinstance(tol, Mapping):
        raise ParameterError(f"tol must be a mapping with atol and/or rtol, got {tol!r}")
    unknown = sorted(set(tol) - {"atol", "rtol", "why"})
    if unknown:
        raise ParameterError(f"tol: unknown key(s) {unknown}; allowed: atol, rtol, why")
    atol = check_nonnegative("atol", tol.get("atol", 0.0))
    rtol = check_nonnegative("rtol", tol.get("rtol", 0.0))
    scale = atol + rtol * abs(ref)
    if scale <= 0.0:
        raise ParameterError("a tolerance needs atol > 0 or rtol > 0")
    return abs(x - ref) / scale


REFERENCE_SCHEMA = Path(__file__).resolve().parents[2] / "workflow" / "schemas" / \
    "reference.schema.yaml"


#: Largest relative tolerance of an entry (the file's largest is 0.05, a quick preset's): a
#: tolerance of 100 % or more passes any value of the right sign, so it checks nothing.
MAX_RTOL = 0.5
#: The same bound on ``atol``, relative to a quoted number: ``atol >= 0.5 |quoted|`` checks
#: as little as that rtol (the file's largest is 0.08 |quoted|, an onset exponent's). A quoted
#: 0 has no scale of its own: its ``atol`` may be at most 0.5 (the file's largest: half a unit
#: of a count of directions; its residuals use 1e-12 to 0.03). An audit: ``atol: 1.0e+300``
#: passed any value.
MAX_ATOL_OF_ZERO = 0.5


def reference_problems(ref: Any, schema_path: str | Path = REFERENCE_SCHEMA,
                       scenes: Any = None) -> list[str]:
    """Every problem of a reference file, one line each naming the entry by its id: the schema
    (required keys, no unknown or misspelled key, tolerances with atol, rtol, why), finite
    non-negative tolerances that are not both zero and rtol below :data:`MAX_RTOL`, a finite
    quoted number, unique ids, ``origin`` "ours" where the source says "beyond" the chapter
    and, given ``scenes`` (names), a registered scene."""
    import jsonschema

    with open(schema_path, encoding="utf-8") as fh:
        schema = safe_load(fh)
    if not isinstance(ref, dict):
        return ["the reference file must be a mapping with 'quantities' and 'errata'"]

    def name(path) -> str:
        path = list(path)
        if len(path) >= 2 and path[0] in ("quantities", "errata") and isinstance(path[1], int):
            entries = ref.get(path[0]) if isinstance(ref.get(path[0]), list) else []
            entry = entries[path[1]] if path[1] < len(entries) else {}
            ident = entry.get("id", "?") if isinstance(entry, dict) else "?"
            rest = ".".join(map(str, path[2:]))
            return f"{path[0]}[{path[1]}] (id {ident})" + (f": {rest}" if rest else "")
        return ".".join(map(str, path)) or "(top level)"

    problems = []
    for err in jsonschema.Draft202012Validator(schema).iter_errors(ref):
        if err.validator == "additionalProperties":
            # keys of a patternProperties (the '_' anchors of shared tolerances) are allowed
            extra = sorted(k for k in set(err.instance) - set(err.schema.get("properties", {}))
                           if not any(re.search(p, str(k))
                                      for p in err.schema.get("patternProperties", {})))
            anchors = " and keys starting with '_' (YAML anchors)" \
                if err.schema.get("patternProperties") else ""
            message = (f"unknown key(s) {extra}; allowed: {sorted(err.schema['properties'])}"
                       f"{anchors}")
        elif err.validator == "anyOf" and list(err.path)[-1:] == ["quoted"] \
                and isinstance(err.instance, str):
            message = (f"{err.instance!r} is a number written as a string: write it unquoted "
                       f"(a string is a categorical statement such as 'flutter', compared "
                       f"word for word, with no tolerance)")
        else:
            message = err.message if len(err.message) < 200 else f"invalid ({err.validator})"
        problems.append(f"{name(err.path)}: {message}")
    if all(isinstance(ref.get(k), list) and not ref[k] for k in ("quantities", "errata")):
        problems.append("quantities and errata are both empty: the check would check nothing "
                        "(list at least one entry)")
    seen: set[str] = set()
    for section in ("quantities", "errata"):
        entries = ref.get(section)
        for i, entry in enumerate(entries if isinstance(entries, list) else []):
            if not isinstance(entry, dict):
                continue
            if entry.get("id") in seen:
                problems.append(f"{name((section, i))}: duplicate id")
            seen.add(entry.get("id"))
            quoted = entry.get("quoted")
            if isinstance(quoted, float) and not math.isfinite(quoted):
                problems.append(f"{name((section, i))}: quoted must be a finite number, "
                                f"got {quoted}")
            source, origin = entry.get("source"), entry.get("origin")
            if section == "quantities" and isinstance(source, str) and "beyond" in source \
                    and origin in ORIGINS and origin != "ours":
                # (the source's own words say the chapter gives no value: the summaries must
                # not count it among the chapter's)
                problems.append(f"{name((section, i))}: origin must be 'ours' for a source "
                                f"beyond the chapter ({source!r}), got {origin!r}")
            for field in ("scene", "key"):  # an empty key would name no quantity
                if isinstance(entry.get(field), str) and not entry[field].strip():
                    problems.append(f"{name((section, i))}: {field} must be a non-empty string")
            if scenes is not None and isinstance(entry.get("scene"), str) \
                    and entry["scene"] not in scenes:
                problems.append(f"{name((section, i))}: scene {entry['scene']!r} is not a "
                                f"registered scene (src/flutterfriction/registry.py)")
            blocks = [("tolerance", entry.get("tolerance")), ("agreement", entry.get("agreement"))]
            blocks += [(f"quick.{k}", v) for k, v in (entry.get("quick") or {}).items()]
            for label, tol in blocks:
                if not isinstance(tol, dict):
                    continue
                values = [tol.get("atol"), tol.get("rtol")]
                if not all(isinstance(v, int | float) and math.isfinite(v) for v in values):
                    problems.append(f"{name((section, i))}: {label}: atol and rtol must be "
                                    f"finite numbers (an infinite tolerance passes anything), "
                                    f"got {values}")
                elif not (values[0] > 0 or values[1] > 0):
                    problems.append(f"{name((section, i))}: {label}: needs atol > 0 or rtol > 0")
                elif values[1] >= MAX_RTOL:
                    problems.append(f"{name((section, i))}: {label}: rtol must be < "
                                    f"{MAX_RTOL:g} (a tolerance that wide checks nothing), "
                                    f"got {values[1]:g}")
                elif isinstance(quoted, int | float) and not isinstance(quoted, bool) \
                        and math.isfinite(quoted):
                    if quoted != 0 and not values[0] < MAX_RTOL * abs(quoted):
                        problems.append(
                            f"{name((section, i))}: {label}: atol must be < {MAX_RTOL:g} "
                            f"|quoted| = {MAX_RTOL * abs(quoted):.6g} (a tolerance that wide "
                            f"checks nothing), got {values[0]:g}")
                    elif quoted == 0 and not values[0] <= MAX_ATOL_OF_ZERO:
                        problems.append(
                            f"{name((section, i))}: {label}: atol must be <= "
                            f"{MAX_ATOL_OF_ZERO:g} for a quoted 0 (half a unit of a count), "
                            f"got {values[0]:g}")
    return problems


def reference_file_problems(path: str | Path, scenes: Any = None) -> list[str]:
    """:func:`reference_problems` of the file at ``path`` (a YAML error is one problem; so is
    each key written twice in a mapping, which YAML would resolve silently to the last)."""
    from flutterfriction.config import yaml_file_problems

    try:
        with open(path, encoding="utf-8") as fh:
            ref = safe_load(fh)
    except (OSError, yaml.YAMLError) as exc:
        return [f"{path}: {' '.join(str(exc).split())}"]
    return yaml_file_problems(path) + [f"{path}: {p}"
                                           for p in reference_problems(ref, scenes=scenes)]


def load_reference(path: str | Path) -> dict[str, Any]:
    """Read and validate a reference file (see :func:`reference_problems`; a key written twice
    is refused too); raises :class:`ParameterError` listing every problem, one line each."""
    from flutterfriction.config import yaml_file_problems

    try:
        with open(path, encoding="utf-8") as fh:
            ref = safe_load(fh)
    except yaml.YAMLError as exc:  # one line naming the file and the line, not a yaml trace
        raise ParameterError(f"{path}: invalid reference file: {_yaml_error(exc)}") from None
    problems = yaml_file_problems(path) + reference_problems(ref)
    if problems:
        raise ParameterError(f"{path}: invalid reference file:\n  " + "\n  ".join(problems))
    return ref


def _yaml_error(exc: yaml.YAMLError) -> str:
    """A YAML error in one line: ``line L, column C: problem``."""
    mark = getattr(exc, "problem_mark", None)
    where = f"line {mark.line + 1}, column {mark.column + 1}: " if mark is not None else ""
    what = getattr(exc, "problem", None) or " ".join(str(exc).split())
    return f"{where}YAML syntax error: {what}"


def _tolerances(entry: dict[str, Any], fidelity: str) -> tuple[dict, dict, str]:
    """``(tolerance, agreement, note)`` for this fidelity (a ``quick`` block overrides)."""
    tol, agr = entry.get("tolerance"), entry.get("agreement")
    override = entry.get("quick") if fidelity == "quick" else None
    if not override:
        return tol, agr, ""
    return override.get("tolerance", tol), override.get("agreement", agr), QUICK_NOTE


def _missing(entry: dict[str, Any], data: Mapping[str, Any], kind: str) -> CheckRow | None:
    """A FAIL row when the scene's data hold no ``kind`` ("quantities" or "errata") under the
    entry's key (a misspelled key, or one of another scene): one clear line in the summary,
    not a KeyError after all the work."""
    scene, key = entry["scene"], entry["key"]
    if scene not in data:
        note = f"scene {scene!r} has no data in this run"
    else:
        held = data[scene].get(kind) or {}
        if key in held:
            return None
        others = sorted(held)
        listed = ", ".join(others[:12]) + (", ..." if len(others) > 12 else "")
        owners = sorted(name for name, d in data.items()
                        if name != scene and key in (d.get(kind) or {}))
        note = (f"key {key!r} is not among the {kind} of scene {scene!r} "
                f"({listed or 'it has none'})"
                + (f"; it is one of scene {', '.join(map(repr, owners))}" if owners else ""))
    return CheckRow(id=entry["id"], kind="quantity" if kind == "quantities" else "erratum",
                    source=entry["source"], quoted=entry.get("quoted", entry.get("printed")),
                    unit=entry.get("unit", ""), reproduced=None, independent=None, method="",
                    independent_method="", error=None, agreement=None, status="FAIL",
                    note=note, origin=entry.get("origin", ""))


def _check_quantity(entry: dict[str, Any], data: Mapping[str, Any],
                    fidelity: str = "paper") -> CheckRow:
    missing = _missing(entry, data, "quantities")
    if missing is not None:
        return missing
    q = data[entry["scene"]]["quantities"][entry["key"]]
    quoted = entry["quoted"]
    common = dict(id=entry["id"], kind="quantity", source=entry["source"], quoted=quoted,
                  origin=entry.get("origin", ""),
                  unit=entry.get("unit", q.get("unit", "")), reproduced=q["value"],
                  independent=q["independent"], method=q["method"],
                  independent_method=q["independent_method"])
    if isinstance(quoted, str):  # a categorical statement, e.g. "flutter"
        expected_independent = entry.get("quoted_independent", quoted)
        ok = q["value"] == quoted and q["independent"] == expected_independent
        return CheckRow(**common, error=None, agreement=None, status="pass" if ok else "FAIL")
    words = [f"{k} {q[k]!r}" for k in ("value", "independent")
             if isinstance(q[k], bool) or not isinstance(q[k], int | float)]
    if words:  # a word where a number is quoted: a failed row, not a ValueError after the run
        return CheckRow(**common, error=None, agreement=None, status="FAIL",
                        note=f"the reference quotes a number, the scene's {' and '.join(words)} "
                             f"is not one (key {entry['key']!r} of scene {entry['scene']!r})")
    tol, agr_tol, note = _tolerances(entry, fidelity)
    err = normalised_error(q["value"], quoted, tol)
    agr = normalised_error(q["value"], q["independent"], agr_tol)
    return CheckRow(**common, error=err, agreement=agr,
                    status="pass" if err <= 1.0 and agr <= 1.0 else "FAIL", note=note)


def _check_erratum(entry: dict[str, Any], data: Mapping[str, Any]) -> CheckRow:
    missing = _missing(entry, data, "errata")
    if missing is not None:
        return missing
    e = data[entry["scene"]]["errata"][entry["key"]]
    tol = entry["agreement"]
    # (None: the printed form has no value here at all, e.g. no interval: as wrong as can be)
    printed_err = (math.inf if e["printed"] is None
                   else normalised_error(e["printed"], e["independent"], tol))
    corrected_err = normalised_error(e["corrected"], e["independent"], tol)
    verified = corrected_err <= 1.0 and printed_err > 1.0
    return CheckRow(
        id=entry["id"], kind="erratum", source=entry["source"],
        quoted=f"printed: {entry['printed']} -> "
               f"{'none' if e['printed'] is None else format(e['printed'], '.10g')}",
        unit=e.get("quantity", ""),
        reproduced=e["corrected"], independent=e["independent"],
        method=f"corrected: {entry['corrected']}", independent_method=e["independent_method"],
        error=printed_err, agreement=corrected_err,
        status="verified erratum" if verified else "UNVERIFIED erratum")


def scene_parameter_changes(parameters: Mapping[str, Any] | None, fidelity: str, scene: str,
                            params: Mapping[str, Any] | None) -> list[str]:
    """The physical keys where a scene's ``params`` differ from those the chapter's values
    belong to (:func:`record_parameters`' record for ``fidelity``), one line each; its
    resolution keys are left out (the chapter's values still apply). Empty for a scene not
    recorded or without parameters."""
    recorded = (parameters or {}).get(fidelity, {})
    if scene not in recorded or not isinstance(params, Mapping):
        return []
    skip = set((parameters or {}).get("resolution_keys", {}).get(scene, []))
    return parameter_changes({k: v for k, v in recorded[scene].items() if k not in skip},
                             {k: v for k, v in params.items() if k not in skip})


def own_parameters_note(read: Mapping[str, Mapping[str, Any] | None],
                        record: str | Path = REFERENCE_PARAMETERS) -> str:
    """A notebook's note (Markdown, empty when none) on the scenes it read (``{scene:
    params}``, the data's ``params``) that ran with other physical parameters than the
    chapter's, under whichever preset's record they are closest to: their changed keys, and
    that the notebook's hand-written prose describes the chapter's parameters while its
    computed numbers and figures are the user's."""
    recorded = load_parameters(record)
    fidelities = [f for f in recorded if f != "resolution_keys"]
    lines = []
    for name in sorted(read):
        changes = min((scene_parameter_changes(recorded, f, name, read[name])
                       for f in fidelities), key=len, default=[])
        if changes:
            lines.append(f"- `{name}`: " + "; ".join(changes))
    if not lines:
        return ""
    return ("**Computed with your own parameters.** These scenes ran with physical parameters "
            "other than the chapter's; this notebook's computed numbers, tables and figures "
            "are yours, but its hand-written prose still describes the chapter's case, and "
            "the chapter's quoted values do not apply to them:\n\n" + "\n".join(lines))


def own_parameters_summary(read: Mapping[str, Mapping[str, Any] | None],
                           record: str | Path = REFERENCE_PARAMETERS) -> str:
    """:func:`own_parameters_note`, or where no scene ran with other parameters a line saying
    so (a notebook's "Your parameters" section had ended without output; a reader's review)."""
    return own_parameters_note(read, record) or (
        "None: every scene this notebook read ran with the chapter's parameters.")


def run_check(reference: dict[str, Any], data: Mapping[str, Any],
              fidelity: str = "paper",
              parameters: Mapping[str, Any] | None = None) -> list[CheckRow]:
    """Compare every reference entry with the scene data (``{scene: data}``) at the
    tolerances of ``fidelity`` (an entry's ``quick`` block applies at ``"quick"`` only).
    With ``parameters`` (:func:`record_parameters`' record), an entry whose scene ran with
    other parameters than those recorded for ``fidelity`` is not applicable."""
    if parameters is not None and (problem := _parameters_problem(parameters)):
        raise ParameterError(f"parameters (the recorded parameters): {problem}")

    def changes(entry: dict[str, Any]) -> list[str]:
        scene = entry["scene"]
        return scene_parameter_changes(parameters, fidelity, scene,
                                       (data.get(scene) or {}).get("params"))

    rows = []
    for kind, check in (("quantities", lambda e: _check_quantity(e, data, fidelity)),
                        ("errata", lambda e: _check_erratum(e, data))):
        for e in reference.get(kind, []):
            moved = changes(e)
            rows.append(_not_applicable(e, moved, data, fidelity) if moved else check(e))
    return rows


def failed(rows: list[CheckRow]) -> list[CheckRow]:
    return [r for r in rows if r.status not in ("pass", "verified erratum", NOT_APPLICABLE)]


def not_applicable(rows: list[CheckRow]) -> list[CheckRow]:
    return [r for r in rows if r.status == NOT_APPLICABLE]


def load_parameters(path: str | Path = REFERENCE_PARAMETERS) -> dict[str, Any]:
    """The recorded parameters (:data:`REFERENCE_PARAMETERS`), checked: a mapping of preset ->
    {scene name -> mapping of parameters} with finite numbers, and ``resolution_keys``: scene
    -> list of key names; else one :class:`ParameterError` line naming the file and the place
    (an audit: NaN and a list were accepted, then an AttributeError in :func:`run_check`;
    garbage gave a bare JSONDecodeError)."""
    try:
        with open(path, encoding="utf-8") as fh:
            recorded = json.load(fh, object_pairs_hook=_unique_keys)
    except json.JSONDecodeError as exc:
        raise ParameterError(f"{path}: not valid JSON: line {exc.lineno}, column {exc.colno}: "
                             f"{exc.msg}") from None
    except ParameterError as exc:
        raise ParameterError(f"{path}: {exc}") from None
    problem = _parameters_problem(recorded)
    if problem:
        raise ParameterError(f"{path}: invalid recorded parameters: {problem} (re-record them "
                             f"with python -m flutterfriction.reference)")
    return recorded


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object's pairs as a dict, refusing a key written twice (json keeps the last)."""
    out: dict[str, Any] = {}
    for k, v in pairs:
        if k in out:
            raise ParameterError(f"key {k!r} written twice in one object")
        out[k] = v
    return out


def parameters_file_problems(path: str | Path = REFERENCE_PARAMETERS,
                             reference: str | Path = "workflow/reference.yaml",
                             shipped: str | Path = "workflow/config.yaml",
                             schema_path: str | Path = "workflow/schemas/config.schema.yaml",
                             scenes: Any = None) -> list[str]:
    """Every problem of the parameter record (:func:`record_parameters`), one line each, for
    the workflow's start (an outside audit: it was read only by the report and check jobs, at
    the end, and a string "801", an unknown preset or scene, a key written twice, a deleted
    scene or preset all passed): valid JSON without a key written twice; its structure
    (:func:`load_parameters`); the presets exactly those of the shipped configuration
    (``shipped``); in each, no unregistered scene (``scenes``: names), every scene that an
    entry of ``reference`` checks recorded (a scene not recorded would count as the chapter's
    whatever its parameters), and the values of the configuration's schema. Whether a value
    is the shipped configuration's is the test suite's to keep (a user may edit
    ``workflow/config.yaml`` itself: the record is what tells their parameters from the
    chapter's)."""
    from flutterfriction.config import _schema_problems, load_yaml

    try:
        with open(path, encoding="utf-8") as fh:
            recorded = json.load(fh, object_pairs_hook=_unique_keys)
    except OSError as exc:
        return [f"{path}: cannot be read: {exc.strerror or exc}"]
    except json.JSONDecodeError as exc:
        return [f"{path}: not valid JSON: line {exc.lineno}, column {exc.colno}: {exc.msg}"]
    except ParameterError as exc:
        return [f"{path}: {exc}"]
    problem = _parameters_problem(recorded)
    if problem:
        return [f"{path}: invalid recorded parameters: {problem}"]
    try:  # (a broken configuration or schema file is the configuration check's to name)
        config, schema = load_yaml(shipped), load_yaml(schema_path)
        presets = set(config.get("fidelity_presets") or {})
    except (OSError, yaml.YAMLError, ParameterError, AttributeError, TypeError):
        return []
    have = set(recorded) - {"resolution_keys"}
    problems = [f"{path}: unknown preset {p!r}; the configuration's presets: {sorted(presets)}"
                for p in sorted(have - presets)]
    problems += [f"{path}: preset {p!r} is not recorded" for p in sorted(presets - have)]
    try:  # (its own problems are reference_file_problems'; here only the scenes it checks)
        ref = load_yaml(reference)
    except (OSError, yaml.YAMLError, ParameterError):
        ref = None
    entries = [e for kind in ("quantities", "errata")
               for e in ((ref.get(kind) if isinstance(ref, dict) else None) or [])] \
        if isinstance(ref, dict) and all(isinstance(ref.get(k) or [], list)
                                         for k in ("quantities", "errata")) else []
    checked = sorted({e["scene"] for e in entries
                      if isinstance(e, dict) and isinstance(e.get("scene"), str)})
    known = None if scenes is None else set(scenes)
    for preset in sorted(have & presets):
        rec = recorded[preset]
        if known is not None:
            problems += [f"{path}: {preset}.{s}: no such scene" for s in sorted(set(rec) - known)]
        problems += [f"{path}: {preset}: scene {s!r}, which {reference} checks, is not recorded"
                     for s in checked if s not in rec]
        valid = {s: v for s, v in rec.items() if known is None or s in known}
        problems += _schema_problems({"fidelity": preset,
                                      "fidelity_presets": {p: {} for p in presets},
                                      "scenes": valid}, schema, f"{path}: {preset}: ")
    if known is not None:
        problems += [f"{path}: resolution_keys.{s}: no such scene"
                     for s in sorted(set(recorded.get("resolution_keys") or {}) - known)]
    return problems


def _parameters_problem(recorded: Any) -> str:
    """The first problem of a parameter record (:func:`record_parameters`), or ``""``."""
    if not isinstance(recorded, dict) or not recorded:
        return f"must be a non-empty mapping of preset -> scene -> parameters, got " \
               f"{type(recorded).__name__}"
    for preset, scenes in recorded.items():
        if not isinstance(scenes, dict):
            return f"{preset} must be a mapping of scene names, got {type(scenes).__name__}"
        for scene, params in scenes.items():
            if preset == "resolution_keys":
                if not (isinstance(params, list) and all(isinstance(k, str) for k in params)):
                    return f"resolution_keys.{scene} must be a list of key names, got {params!r}"
            elif not isinstance(params, dict):
                return f"{preset}.{scene} must be a mapping of parameters, got " \
                       f"{type(params).__name__}"
            elif (bad := _non_finite(params, f"{preset}.{scene}")):
                return bad
    return ""


def _non_finite(value: Any, where: str) -> str:
    """Where ``value`` (nested lists and mappings) holds a NaN or infinity, or ``""``."""
    if isinstance(value, float) and not math.isfinite(value):
        return f"{where} must be a finite number, got {value}"
    items = value.items() if isinstance(value, dict) else enumerate(value) \
        if isinstance(value, list) else ()
    for k, v in items:
        if (bad := _non_finite(v, f"{where}.{k}" if isinstance(value, dict) else f"{where}[{k}]")):
            return bad
    return ""


def _fmt(x: Any) -> str:
    if isinstance(x, float):
        return f"{x:.12g}"
    return str(x)


def origins_sentence(rows: list[CheckRow]) -> str:
    """One sentence counting the applicable quantities by the origin of their reference value
    (:data:`ORIGINS`), e.g. "24 numbers printed in the chapter; ...", or ``""`` if none has
    one."""
    shown = [r for r in rows if r.kind == "quantity" and r.status != NOT_APPLICABLE]
    counts = {k: sum(r.origin == k for r in shown) for k in ORIGINS}
    if not any(counts.values()):
        return ""
    parts = [f"{counts[k]} {words}" for k, words in ORIGINS.items() if counts[k]]
    return (f"The {sum(counts.values())} quantities by the origin of their reference value: "
            + "; ".join(parts) + ".")


def summary_markdown(rows: list[CheckRow]) -> str:
    bad = failed(rows)
    loose = sum(r.note == QUICK_NOTE for r in rows)
    skipped = not_applicable(rows)
    checked = len(rows) - len(skipped)
    lines = [
        "# Reference check",
        "",
        f"{checked - len(bad)} of {checked} entries pass "
        f"({sum(r.kind == 'erratum' and r.status != NOT_APPLICABLE for r in rows)} errata "
        "verified against an independent computation)." if not bad
        else f"**{len(bad)} of {checked} entries FAIL.**",
        "",
        *([origins_sentence(rows), ""] if origins_sentence(rows) else []),
        *([f"{len(skipped)} entries are not applicable: their scenes ran with other "
           "parameters than the chapter's (your own; the rows name the changed keys), so the "
           "chapter's values do not apply to them.", ""] if skipped else []),
        "Normalised error e = |x - ref| / (atol + rtol |ref|), pass when e <= 1: `error` compares "
        "the reproduced value with the quoted one, `agreement` the primary with the "
        "independent method. For an erratum, `error` is printed-vs-independent (must be > 1) and "
        "`agreement` corrected-vs-independent (must be <= 1).",
        "",
        *([f"{loose} entries were checked at the quick preset's looser tolerances (marked); "
           "run at paper fidelity for the stated digits.", ""] if loose else []),
    ]
    lines += markdown_table(
        ["id", "source", "origin", "quoted", "unit", "reproduced", "independent",
         "method / independent method", "error", "agreement", "status"],
        [[r.id, r.source, r.origin or r.kind, _fmt(r.quoted), r.unit, _fmt(r.reproduced),
          _fmt(r.independent),
          f"{r.method} / {r.independent_method}",
          "" if r.error is None else f"{r.error:.2e}",
          "" if r.agreement is None else f"{r.agreement:.2e}", r.shown_status] for r in rows])
    return "\n".join(lines) + "\n"


def write_summary(rows: list[CheckRow], json_path: str | Path, md_path: str | Path,
                  figure_checks: Mapping[str, list[Offence]] | None = None) -> None:
    """The check summary (JSON and markdown); with ``figure_checks`` (figure -> offences,
    :mod:`flutterfriction.figure_offences`), the figure check's result too."""
    summary: dict[str, Any] = {"n_entries": len(rows), "n_failed": len(failed(rows)),
                               "n_not_applicable": len(not_applicable(rows)),
                               "entries": [asdict(r) for r in rows]}
    md = summary_markdown(rows)
    if figure_checks is not None:
        summary["figures"] = figure_checks_summary(figure_checks)
        md += "\n" + figure_checks_markdown(figure_checks)
    write_json(json_path, summary)
    write_text(md_path, md)


def load_scene_data(paths: list[str | Path]) -> dict[str, Any]:
    """``{scene name: data}`` from the scene JSON files written by the workflow."""
    out = {}
    for p in paths:
        with open(p, encoding="utf-8") as fh:
            d = json.load(fh)
        out[d["scene"]] = d
    return out


def _record_main(argv: list[str]) -> int:
    """``python -m flutterfriction.reference``: re-record the parameters from the repository's
    ``workflow/config.yaml`` (the maintainers' step after changing a shipped parameter). It
    takes no arguments; a configuration that does not validate is refused in one line each,
    exit 2, before anything is written (a record of a broken configuration would be the
    chapter's parameters for every later check)."""
    import sys

    from flutterfriction.config import load_config, load_yaml, validate_config
    from flutterfriction.io import write_json as _write
    from flutterfriction.registry import SCENES

    if argv:
        print(f"python -m flutterfriction.reference takes no arguments, got {argv}",
              file=sys.stderr)
        return 2
    config_path = Path("workflow/config.yaml")
    try:
        problems = validate_config(load_yaml(config_path),
                                   "workflow/schemas/config.schema.yaml", scenes=SCENES)
        config = None if problems else load_config(config_path)
    except (OSError, ParameterError, yaml.YAMLError) as exc:
        problems = [" ".join(str(exc).split())]
    if problems:
        print("not recorded: invalid configuration:\n  " + "\n  ".join(problems),
              file=sys.stderr)
        return 2
    _write(REFERENCE_PARAMETERS, record_parameters(config))
    print(f"recorded the parameters of every scene and preset in {REFERENCE_PARAMETERS}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":  # python -m flutterfriction.reference: re-record the parameters
    import sys

    sys.exit(_record_main(sys.argv[1:]))
