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
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import yaml

from flutterfriction.io import write_json, write_text


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
    status: str  # "pass" | "FAIL" | "verified erratum" | "UNVERIFIED erratum"
    note: str = ""

    @property
    def shown_status(self) -> str:
        """The status as tables show it, with the note (e.g. a quick-preset tolerance)."""
        return f"{self.status} ({self.note})" if self.note else self.status


QUICK_NOTE = "quick-preset tolerance"


def normalised_error(x: float, ref: float, tol: Mapping[str, float]) -> float:
    """``|x - ref| / (atol + rtol |ref|)``; pass when ``<= 1``."""
    scale = float(tol.get("atol", 0.0)) + float(tol.get("rtol", 0.0)) * abs(float(ref))
    if scale <= 0.0:
        raise ValueError("a tolerance needs atol > 0 or rtol > 0")
    return abs(float(x) - float(ref)) / scale


def load_reference(path: str | Path) -> dict[str, Any]:
    with open(path, encoding="utf-8") as fh:
        ref = yaml.safe_load(fh)
    for section in ("quantities", "errata"):
        for entry in ref.get(section, []):
            for key in ("id", "source", "scene", "key"):
                if key not in entry:
                    raise ValueError(f"reference entry {entry.get('id', '?')} lacks '{key}'")
            quick = entry.get("quick")
            if quick is not None and (not isinstance(quick, dict)
                                      or set(quick) - {"tolerance", "agreement"}
                                      or not all("why" in t for t in quick.values())):
                raise ValueError(f"reference entry {entry['id']}: 'quick' may hold only "
                                     "'tolerance' and 'agreement', each with its 'why'")
    return ref


def _tolerances(entry: dict[str, Any], fidelity: str) -> tuple[dict, dict, str]:
    """``(tolerance, agreement, note)`` for this fidelity (a ``quick`` block overrides)."""
    tol, agr = entry.get("tolerance"), entry.get("agreement")
    override = entry.get("quick") if fidelity == "quick" else None
    if not override:
        return tol, agr, ""
    return override.get("tolerance", tol), override.get("agreement", agr), QUICK_NOTE


def _check_quantity(entry: dict[str, Any], data: Mapping[str, Any],
                    fidelity: str = "paper") -> CheckRow:
    q = data[entry["scene"]]["quantities"][entry["key"]]
    quoted = entry["quoted"]
    common = dict(id=entry["id"], kind="quantity", source=entry["source"], quoted=quoted,
                  unit=entry.get("unit", q.get("unit", "")), reproduced=q["value"],
                  independent=q["independent"], method=q["method"],
                  independent_method=q["independent_method"])
    if isinstance(quoted, str):  # a categorical statement, e.g. "flutter"
        expected_independent = entry.get("quoted_independent", quoted)
        ok = q["value"] == quoted and q["independent"] == expected_independent
        return CheckRow(**common, error=None, agreement=None, status="pass" if ok else "FAIL")
    tol, agr_tol, note = _tolerances(entry, fidelity)
    err = normalised_error(q["value"], quoted, tol)
    agr = normalised_error(q["value"], q["independent"], agr_tol)
    return CheckRow(**common, error=err, agreement=agr,
                    status="pass" if err <= 1.0 and agr <= 1.0 else "FAIL", note=note)


def _check_erratum(entry: dict[str, Any], data: Mapping[str, Any]) -> CheckRow:
    e = data[entry["scene"]]["errata"][entry["key"]]
    tol = entry["agreement"]
    printed_err = normalised_error(e["printed"], e["independent"], tol)
    corrected_err = normalised_error(e["corrected"], e["independent"], tol)
    verified = corrected_err <= 1.0 and printed_err > 1.0
    return CheckRow(
        id=entry["id"], kind="erratum", source=entry["source"],
        quoted=f"printed: {entry['printed']} -> {e['printed']:.10g}", unit=e.get("quantity", ""),
        reproduced=e["corrected"], independent=e["independent"],
        method=f"corrected: {entry['corrected']}", independent_method=e["independent_method"],
        error=printed_err, agreement=corrected_err,
        status="verified erratum" if verified else "UNVERIFIED erratum")


def run_check(reference: dict[str, Any], data: Mapping[str, Any],
              fidelity: str = "paper") -> list[CheckRow]:
    """Compare every reference entry with the scene data (``{scene: data}``) at the
    tolerances of ``fidelity`` (an entry's ``quick`` block applies at ``"quick"`` only)."""
    rows = [_check_quantity(e, data, fidelity) for e in reference.get("quantities", [])]
    rows += [_check_erratum(e, data) for e in reference.get("errata", [])]
    return rows


def failed(rows: list[CheckRow]) -> list[CheckRow]:
    return [r for r in rows if r.status not in ("pass", "verified erratum")]


def _fmt(x: Any) -> str:
    if isinstance(x, float):
        return f"{x:.12g}"
    return str(x)


def summary_markdown(rows: list[CheckRow]) -> str:
    bad = failed(rows)
    loose = sum(r.note == QUICK_NOTE for r in rows)
    lines = [
        "# Reference check",
        "",
        f"{len(rows) - len(bad)} of {len(rows)} entries pass "
        f"({sum(r.kind == 'erratum' for r in rows)} errata verified against an independent "
        "computation)." if not bad else f"**{len(bad)} of {len(rows)} entries FAIL.**",
        "",
        "Normalised error e = |x - ref| / (atol + rtol |ref|), pass when e <= 1: `error` compares "
        "the reproduced value with the quoted one, `agreement` the primary with the "
        "independent method. For an erratum, `error` is printed-vs-independent (must be > 1) and "
        "`agreement` corrected-vs-independent (must be <= 1).",
        "",
        *([f"{loose} entries were checked at the quick preset's looser tolerances (marked); "
           "run at paper fidelity for the stated digits.", ""] if loose else []),
        "| id | source | quoted | unit | reproduced | independent | method / independent "
        "method | error | agreement | status |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append("| " + " | ".join([
            r.id, r.source, _fmt(r.quoted), r.unit, _fmt(r.reproduced), _fmt(r.independent),
            f"{r.method} / {r.independent_method}",
            "" if r.error is None else f"{r.error:.2e}",
            "" if r.agreement is None else f"{r.agreement:.2e}", r.shown_status]) + " |")
    return "\n".join(lines) + "\n"


def write_summary(rows: list[CheckRow], json_path: str | Path, md_path: str | Path) -> None:
    write_json(json_path, {"n_entries": len(rows), "n_failed": len(failed(rows)),
                           "entries": [asdict(r) for r in rows]})
    write_text(md_path, summary_markdown(rows))


def load_scene_data(paths: list[str | Path]) -> dict[str, Any]:
    """``{scene name: data}`` from the scene JSON files written by the workflow."""
    out = {}
    for p in paths:
        with open(p, encoding="utf-8") as fh:
            d = json.load(fh)
        out[d["scene"]] = d
    return out
