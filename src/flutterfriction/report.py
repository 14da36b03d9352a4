"""One HTML report for everything the workflow builds: ``results/reports/index.html``.

It opens with the coverage table (every chapter figure: reproduced, in part or not, by which
of our figures, from which computation, and why not; ``workflow/coverage.yaml``) and the table of
the chapter's parameter lists; then every figure at full width with its caption (what it
draws), the chapter's printed caption of the figure it reproduces, links to its PNG, PDF and
data, the checked values its data carry and the parameters it was drawn with; every executed
notebook, the stress report and the tolerance check (quoted value, reproduced value,
independent method, status), with the errata highlighted next to their evidence. All links are
relative, so the ``results/`` folder can be moved or archived as a whole; :func:`broken_links`
checks that every one of them resolves. :func:`coverage_markdown` and
:func:`parameter_lists_markdown` render the two tables for the README.
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

from flutterfriction.config import safe_load
from flutterfriction.errors import ParameterError
from flutterfriction.figure_offences import RULES as FIGURE_RULES
from flutterfriction.figure_offences import Offence
from flutterfriction.notebook_export import math_to_mathml
from flutterfriction.reference import NOT_APPLICABLE, CheckRow, origins_sentence

STYLE = """
body { font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em;
       color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(270px, 1fr)); gap: 1em; }
figure { margin: 0; border: 1px solid #ddd; border-radius: 4px; padding: .5em; background: #fff; }
figure img { width: 100%; height: 190px; object-fit: contain; }
figcaption { font-size: .85em; } figcaption a { margin-right: .6em; }
figure.big { margin: 1.5em 0; padding: .8em; box-sizing: border-box;
             /* wider than the text column (up to 1800 px), so that wide figures' 7-pt
                labels show near their print size; centred on the column */
             width: min(1800px, 96vw); position: relative; left: 50%;
             transform: translateX(-50%); }
figure.big img { height: auto; max-height: none; display: block; width: auto; max-width: 100%;
                 margin: 0 auto; }
figure.big figcaption { font-size: .95em; max-width: 1150px; margin: 0 auto; }
figure.big .links { font-size: .85em; }
figure.big table { width: auto; margin-top: .4em; } figure.big th { position: static; }
table.coverage td:first-child { min-width: 0; }
table.coverage td:nth-child(3), table.coverage td:nth-child(4) { white-space: nowrap; }
table.coverage td:nth-child(5) { overflow-wrap: normal; }
table.coverage td.st-reproduced { background: #e6f4e6; }
table.coverage td.st-part { background: #fff6d6; } table.coverage td.st-not { background: #f3f3f3; }
.params { font-size: .8em; color: #444; }
.own { font-size: .9em; color: #8a4b00; }
.printed { font-size: .9em; color: #333; border-left: 3px solid #bbb; padding-left: .5em; }
figure.anim img { height: auto; }
table { border-collapse: collapse; font-size: .8em; width: 100%; }
th, td { border: 1px solid #ddd; padding: .25em .4em; vertical-align: top; text-align: left; }
th { background: #f3f3f3; position: sticky; top: 0; }
tr.pass td.status { color: #176117; } tr.fail td { background: #fde2e2; }
tr.na td { color: #666; } .summary.na { background: #eeeeee; }
tr.erratum td { background: #fff6d6; }
td.num { font-family: monospace; font-size: 1.1em; white-space: nowrap; }
.summary { font-size: 1.1em; padding: .6em; background: #eef6ee; border-radius: 4px; }
.summary.bad { background: #fde2e2; }
details { margin: .3em 0; } .wide { overflow-x: auto; }
td { overflow-wrap: anywhere; } td.num { overflow-wrap: normal; }
td:first-child { min-width: 12em; } code { font-size: .9em; }
"""


@dataclass(frozen=True)
class FigureEntry:
    scene: str
    caption: str
    data_scene: str  # the scene whose data the figure draws


def load_layout(path: str | Path,
                figures: Mapping[str, Mapping[str, str]] | None = None) -> dict[str, Any]:
    """Read ``workflow/report.yaml``: the sections of the report and their notebooks; each
    section's figures (name -> caption) are those of its notebook's chapter part.

    Parameters
    ----------
    figures
        Part -> {figure: caption}; by default from :mod:`flutterfriction.registry`.
    """
    import jsonschema

    with open(path, encoding="utf-8") as fh:
        layout = safe_load(fh)
    with open(REPORT_SCHEMA, encoding="utf-8") as fh:
        schema = safe_load(fh)
    problems = [f"{'.'.join(map(str, e.path)) or '(top level)'}: "
                f"{e.message if len(e.message) < 200 else e.validator}"
                for e in jsonschema.Draft202012Validator(schema).iter_errors(layout)]
    if problems:
        raise ParameterError(f"report layout {path}: unknown keys or invalid values:\n  "
                             + "\n  ".join(problems))
    if figures is None:
        from flutterfriction.registry import PARTS, scenes_of

        figures = {part: {f: spec.caption for s in scenes_of(part)
                          for f, spec in s.figures.items()} for part in PARTS}
    for section in layout.get("sections", []):
        if "notebook" in section:
            section["figures"] = dict(figures.get(section["notebook"], {}))
    return layout


def layout_figures(layout: Mapping[str, Any]) -> list[str]:
    """Every figure scene the layout shows, in order."""
    return [f for s in layout.get("sections", []) for f in s.get("figures", {})]


def _cell(x: Any, unit: str = "") -> str:
    """A table cell: numbers in monospace on one line, text (formulas, categories) wrapped."""
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        return f'<td class="num">{x:.10g}{html.escape(unit)}</td>'
    return f"<td>{html.escape(str(x))}{html.escape(unit)}</td>"


def _row_class(r: CheckRow) -> str:
    """A check row's table class: erratum, pass, not applicable (another scene's parameters)
    or fail."""
    if r.status == NOT_APPLICABLE:
        return "na"
    if r.status not in ("pass", "verified erratum"):
        return "fail"
    return "erratum" if r.kind == "erratum" else "pass"


def _check_table(rows: Iterable[CheckRow], errata: Mapping[str, Mapping[str, Any]]) -> str:
    out = ['<div class="wide"><table><thead><tr><th>id</th><th>source</th><th>origin</th>'
           "<th>reference</th>"
           "<th>reproduced</th>"
           "<th>method</th><th>independent</th><th>independent method</th>"
           "<th>error / agreement</th><th>status</th></tr></thead><tbody>"]
    for r in rows:
        cls = _row_class(r)
        err = "" if r.error is None else f"{r.error:.3g}"
        agr = "" if r.agreement is None else f"{r.agreement:.3g}"
        ident = f'<a id="{html.escape(r.id)}"></a>{html.escape(r.id)}'
        method = html.escape(r.method)
        if r.kind == "erratum" and r.id in errata:
            e = errata[r.id]
            method += ("<details><summary>evidence</summary>"
                       f"<p><b>printed</b>: <code>{html.escape(str(e['printed']))}</code><br>"
                       f"<b>corrected</b>: <code>{html.escape(str(e['corrected']))}</code></p>"
                       f"<p>{html.escape(str(e['evidence']))}</p></details>")
        unit = f" {r.unit}" if r.unit and r.kind == "quantity" else ""
        out.append(
            f'<tr class="{cls}"><td>{ident}</td><td>{html.escape(r.source)}</td>'
            f"<td>{html.escape(r.origin or r.kind)}</td>"
            f"{_cell(r.quoted, unit)}{_cell(r.reproduced)}"
            f"<td>{method}</td>{_cell(r.independent)}"
            f"<td>{html.escape(r.independent_method)}</td><td class=\"num\">{err} / {agr}</td>"
            f'<td class="status">{html.escape(r.shown_status)}</td></tr>')
    out.append("</tbody></table></div>")
    return "\n".join(out)


#: The chapter's figures (Figs. 1-24): ``workflow/coverage.yaml`` lists each once.
CHAPTER_FIGURES = 24
_WORKFLOW = Path(__file__).resolve().parents[2] / "workflow"
COVERAGE = _WORKFLOW / "coverage.yaml"
COVERAGE_SCHEMA = _WORKFLOW / "schemas" / "coverage.schema.yaml"
REPORT_SCHEMA = _WORKFLOW / "schemas" / "report.schema.yaml"
_STATUS_CLASS = {"reproduced": "st-reproduced", "reproduced in part": "st-part",
                 "not reproduced": "st-not"}


def load_coverage(path: str | Path = COVERAGE,
                  schema_path: str | Path = COVERAGE_SCHEMA) -> list[dict[str, Any]]:
    """Read and validate ``workflow/coverage.yaml``: the schema, and Figs. 1 to
    :data:`CHAPTER_FIGURES` each listed once, in order. Raises :class:`ParameterError` listing
    every problem, one line each."""
    import jsonschema

    with open(path, encoding="utf-8") as fh:
        cov = safe_load(fh)
    with open(schema_path, encoding="utf-8") as fh:
        schema = safe_load(fh)
    problems = []
    for err in jsonschema.Draft202012Validator(schema).iter_errors(cov):
        where = ".".join(map(str, err.path)) or "(top level)"
        problems.append(f"{where}: {err.message if len(err.message) < 200 else err.validator}")
    if not problems:
        numbers = [e["number"] for e in cov["figures"]]
        if numbers != list(range(1, CHAPTER_FIGURES + 1)):
            problems.append(f"figures must be numbered 1..{CHAPTER_FIGURES} in order, once each; "
                            f"got {numbers}")
    if problems:
        raise ParameterError(f"{path}: invalid coverage file:\n  " + "\n  ".join(problems))
    return cov["figures"]


def registry_figure_scenes() -> dict[str, str]:
    """Figure name -> the scene whose data it draws, from :mod:`flutterfriction.registry`."""
    from flutterfriction.registry import figures

    return {f: scene.name for f, (scene, _) in figures().items()}


def coverage_problems(entries: list[Mapping[str, Any]],
                      figure_scenes: Mapping[str, str]) -> list[str]:
    """What the coverage table claims that the registry does not draw (a figure it names that
    is not registered), and chapter figures the registry draws (``figNN``, ``figNN_...``) that
    the table does not list under Fig. NN; empty when the table is true."""
    import re

    problems = []
    listed: dict[str, int] = {}
    for e in entries:
        for f in e["figures"]:
            if f in listed:  # one drawing is one chapter figure's (an outside audit)
                problems.append(f"workflow/coverage.yaml: {f!r} is listed under Fig. "
                                f"{listed[f]} and Fig. {e['number']}")
            listed.setdefault(f, e["number"])
    for f, n in listed.items():
        if f not in figure_scenes:
            problems.append(f"workflow/coverage.yaml: Fig. {n} names {f!r}, which the registry "
                            "does not draw")
    for f in figure_scenes:
        m = re.fullmatch(r"fig(\d\d)(_.*)?", f)
        if m and int(m.group(1)) <= CHAPTER_FIGURES and listed.get(f) != int(m.group(1)):
            problems.append(f"workflow/coverage.yaml: the registry draws {f!r}, which Fig. "
                            f"{int(m.group(1))} does not list")
    return problems


def beyond_the_chapter(entries: list[Mapping[str, Any]],
                       figure_scenes: Mapping[str, str]) -> list[str]:
    """Registered figures that reproduce no chapter figure (in the registry's order)."""
    listed = {f for e in entries for f in e["figures"]}
    return [f for f in figure_scenes if f not in listed]


def coverage_counts(entries: list[Mapping[str, Any]]) -> dict[str, int]:
    return {s: sum(e["status"] == s for e in entries) for s in _STATUS_CLASS}


def coverage_markdown(path: str | Path = COVERAGE,
                      figure_scenes: Mapping[str, str] | None = None,
                      figure_dir: str = "results/figures") -> str:
    """The coverage table as markdown (for the README): one row per chapter figure (status, our
    figures linked to their PNG under ``figure_dir``, the computation each draws, what is
    shown, what is missing and why), a count, and the figures beyond the chapter."""
    entries = load_coverage(path)
    scenes = registry_figure_scenes() if figure_scenes is None else dict(figure_scenes)

    def esc(x: str) -> str:
        return x.replace("|", "\\|")

    def figs(names: Iterable[str]) -> str:
        return ", ".join(f"[{f}]({figure_dir}/{f}.png)" for f in names)

    lines = ["| Fig. | chapter figure | status | our figures | computation (scene) | shown | "
             "not reproduced (why) |", "|---|---|---|---|---|---|---|"]
    for e in entries:
        comp = ", ".join(dict.fromkeys(f"`{scenes[f]}`" for f in e["figures"] if f in scenes))
        lines.append(f"| {e['number']} | {esc(e['title'])} | {e['status']} | "
                     f"{figs(e['figures'])} | {comp} | {esc(e.get('shows', ''))} | "
                     f"{esc(e.get('missing', ''))} |")
    c = coverage_counts(entries)
    lines.append("")
    lines.append(f"Of the chapter's {len(entries)} figures: {c['reproduced']} reproduced, "
                 f"{c['reproduced in part']} reproduced in part, {c['not reproduced']} not "
                 "reproduced.")
    beyond = beyond_the_chapter(entries, scenes)
    if beyond:
        lines.append(f"Beyond the chapter ({len(beyond)} figures): {figs(beyond)}.")
    return "\n".join(lines) + "\n"


def coverage_html(entries: list[Mapping[str, Any]], figure_scenes: Mapping[str, str]) -> str:
    """The coverage table for the report: our figures link to their place in the report."""
    out = ['<div class="wide"><table class="coverage"><thead><tr><th>Fig.</th>'
           "<th>chapter figure</th><th>status</th><th>our figures</th><th>computation "
           "(scene)</th><th>shown</th><th>not reproduced (why)</th></tr></thead><tbody>"]
    for e in entries:
        figs = ", ".join(f'<a href="#fig-{html.escape(f)}">{html.escape(f)}</a>'
                         if f in figure_scenes else f"{html.escape(f)} (not drawn)"
                         for f in e["figures"])
        comp = ", ".join(dict.fromkeys(f"<code>{html.escape(figure_scenes[f])}</code>"
                                       for f in e["figures"] if f in figure_scenes))
        out.append(
            f'<tr id="chapter-fig{e["number"]}"><td>{e["number"]}</td>'
            f"<td>{html.escape(e['title'])}</td>"
            f'<td class="{_STATUS_CLASS[e["status"]]}">{html.escape(e["status"])}</td>'
            f"<td>{figs}</td><td>{comp}</td><td>{html.escape(e.get('shows', ''))}</td>"
            f"<td>{html.escape(e.get('missing', ''))}</td></tr>")
    out.append("</tbody></table></div>")
    c = coverage_counts(entries)
    beyond = beyond_the_chapter(entries, figure_scenes)
    out.append(f"<p>Of the chapter's {len(entries)} figures: <b>{c['reproduced']} reproduced"
               f"</b>, {c['reproduced in part']} reproduced in part, {c['not reproduced']} not "
               "reproduced." + (f" Beyond the chapter ({len(beyond)} figures): " + ", ".join(
                   f'<a href="#fig-{html.escape(f)}">{html.escape(f)}</a>' for f in beyond)
                   + "." if beyond else "") + "</p>")
    return "\n".join(out)


#: Units of the parameter-list keys (SI).
PARAMETER_UNITS = {"l1": "m", "l2": "m", "d": "m", "h": "m", "length": "m", "m1": "kg",
                   "m2": "kg", "m3": "kg", "k1": "N m", "k2": "N m", "c1": "N m s",
                   "c2": "N m s", "B": "N m²", "rho": "kg/m", "D": "N m² s", "lam": "Pa",
                   "mu": "Pa", "P": "(Voigt, dimensionless)", "Q": "(Voigt, dimensionless)"}


def _value(v: Any, unit: str = "") -> str:
    """A parameter value in a few significant digits (lists longer than 8 shortened)."""
    if isinstance(v, Mapping):
        text = "{" + ", ".join(f"{k}: {_value(x)}" for k, x in v.items()) + "}"
    elif isinstance(v, (tuple, list)):
        shown = [_value(x) for x in v[:8]]
        text = "(" + ", ".join(shown) + (f", … {len(v)} values" if len(v) > 8 else "") + ")"
    elif isinstance(v, float):
        text = f"{v:.4g}"
    else:
        text = str(v)
    return f"{text} {unit}".strip()


def parameter_list_rows(lists: Mapping[str, Any] | None = None) -> list[dict[str, str]]:
    """The chapter's parameter lists (:data:`flutterfriction.parameters.LISTS`) as rows: name,
    source, values with units, note; a list the chapter does not give (our choice) says so."""
    if lists is None:
        from flutterfriction.parameters import LISTS as lists
    rows = []
    for p in lists.values():
        ours = "our choice" in p.source
        rows.append({"name": p.name, "source": p.source, "kind": p.kind,
                     "values": ", ".join(f"{k} = {_value(v, PARAMETER_UNITS.get(k, ''))}"
                                         for k, v in p.values.items()),
                     "note": ("OUR CHOICE, not the chapter's: " if ours else "") + p.note,
                     "ours": ours})
    return rows


def parameter_lists_markdown() -> str:
    """The parameter lists as a markdown table (for the README)."""
    lines = ["| list | source | values (SI) | note |", "|---|---|---|---|"]
    for r in parameter_list_rows():
        name = f"**{r['name']}**" if r["ours"] else r["name"]
        lines.append(f"| {name} | {r['source']} | {r['values']} | {r['note']} |")
    return "\n".join(lines) + "\n"


def parameter_lists_html() -> str:
    out = ['<div class="wide"><table><thead><tr><th>list</th><th>source</th><th>values (SI)'
           "</th><th>note</th></tr></thead><tbody>"]
    for r in parameter_list_rows():
        cls = ' class="erratum"' if r["ours"] else ""
        note = html.escape(r["note"])
        if r["ours"]:
            note = "<b>our choice</b>, not the chapter's: " + html.escape(
                r["note"].removeprefix("OUR CHOICE, not the chapter's: "))
        out.append(f'<tr{cls} id="list-{html.escape(r["name"])}"><td>{html.escape(r["name"])}'
                   f"</td><td>{html.escape(r['source'])}</td><td>{html.escape(r['values'])}"
                   f"</td><td>{note}</td></tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


def row_scenes(reference: Mapping[str, Any]) -> dict[str, str]:
    """Check-row id -> the scene whose data it checks (from ``workflow/reference.yaml``)."""
    return {e["id"]: e["scene"] for section in ("quantities", "errata")
            for e in reference.get(section) or []}


def _short(x: Any) -> str:
    if isinstance(x, float):
        return f"{x:.6g}"
    return str(x)


def _figures_named(source: str) -> set[int]:
    """The chapter figures a check row's source names ("Fig. 12", "Figs. 15-17")."""
    import re

    out: set[int] = set()
    for m in re.finditer(r"Figs?\.\s*(\d+)(?:\s*[-–]\s*(\d+))?", source):
        first = int(m.group(1))
        out.update(range(first, int(m.group(2) or first) + 1))
    return out


def _caption_html(text: str) -> str:
    """A printed caption as HTML: the text escaped, its TeX math (``$...$``) as MathML (the
    TeX converted unescaped: an escaped ``<`` came out as "&lt;" inside the math)."""
    from flutterfriction.notebook_export import _MATH

    out, pos = [], 0
    for m in _MATH.finditer(text):
        out.append(html.escape(text[pos:m.start()], quote=False))
        out.append(math_to_mathml(m.group(0)))
        pos = m.end()
    out.append(html.escape(text[pos:], quote=False))
    return "".join(out)


def _chapter_number(figure: str) -> int | None:
    """The chapter figure our figure ``figNN`` (or ``figNN_...``) draws, else None."""
    import re

    m = re.fullmatch(r"fig(\d\d)(_.*)?", figure)
    return int(m.group(1)) if m else None


def _own_note(changes: list[str]) -> str:
    """Under a figure drawn with other parameters than the chapter's: its captions (ours and
    the printed one) describe the chapter's figure (an outside audit read chapter loads and
    lists in them next to a user's figure)."""
    if not changes:
        return ""
    return ('<p class="own"><b>Drawn with your own parameters</b> (' +
            html.escape("; ".join(changes[:6]) + ("; ..." if len(changes) > 6 else "")) +
            "): the captions above describe the chapter's figure; the figure, its title and "
            "the values below are yours.</p>")


def _value_cells(r: CheckRow, unit: str) -> str:
    """The reference, reproduced and independent cells of a figure's check row. An erratum's
    say what they hold (a reader's review: its printed formula filled the column, and the
    chapter's printed number sat under "independent" unexplained): the printed form in short
    (in full on hover and in the check table), the corrected value, the independent one."""
    if r.kind != "erratum":
        return (f'<td class="num">{html.escape(_short(r.quoted) + unit)}</td>'
                f'<td class="num">{html.escape(_short(r.reproduced))}</td>'
                f'<td class="num">{html.escape(_short(r.independent))}</td>')
    printed = _short(r.quoted).removeprefix("printed: ")
    brief = printed if len(printed) <= 48 else printed[:46] + "…"
    return (f'<td title="{html.escape(printed)}">erratum, printed: {html.escape(brief)}</td>'
            f'<td class="num">corrected: {html.escape(_short(r.reproduced))}</td>'
            f'<td class="num" title="{html.escape(r.independent_method)}">independent: '
            f'{html.escape(_short(r.independent))}</td>')


def _figure_checks(rows: list[CheckRow], own_scene: str | None = None,
                   row_scene: Mapping[str, str] | None = None) -> str:
    """The check rows of one figure's data, as a small table linking to the full check. With
    ``own_scene`` (the figure's data ran with other parameters), rows of another scene's data
    say so (they check that scene, not this figure)."""
    out = ["<table><thead><tr><th>checked value</th><th>source</th><th>reference</th>"
           "<th>reproduced</th><th>independent</th><th>status</th></tr></thead><tbody>"]
    for r in rows:
        cls = _row_class(r)
        unit = f" {r.unit}" if r.unit and r.kind == "quantity" else ""
        out.append(f'<tr class="{cls}"><td><a href="#{html.escape(r.id)}">{html.escape(r.id)}'
                   f"</a></td><td>{html.escape(r.source)}"
                   + (f" (checked on {html.escape(row_scene[r.id])}'s data, not this figure's)"
                      if own_scene and row_scene and row_scene.get(r.id, own_scene) != own_scene
                      else "") + "</td>"
                   + _value_cells(r, unit)
                   + f'<td class="status">{html.escape(r.shown_status)}</td></tr>')
    out.append("</tbody></table>")
    return "\n".join(out)


def _named_lists(params: Mapping[str, Any]) -> str:
    """A scene's parameters, one line: sub-mappings equal to a chapter list are named."""
    from flutterfriction.parameters import LISTS

    def same(a: Mapping[str, Any], b: Mapping[str, Any]) -> bool:
        def norm(v: Any) -> Any:
            return list(v) if isinstance(v, (tuple, list)) else v

        return set(a) == set(b) and all(norm(a[k]) == norm(b[k]) for k in a)

    parts = []
    for k, v in params.items():
        if isinstance(v, Mapping):
            name = next((p.name for p in LISTS.values() if same(v, p.values)), None)
            if name:
                parts.append(f'{k}: <a href="#list-{name}">{name}</a>')
                continue
            parts.append(f"{html.escape(k)}: {html.escape(_value(v))}")
        else:
            parts.append(f"{html.escape(k)} = {html.escape(_value(v))}")
    return "; ".join(parts)


def build_index(layout: Mapping[str, Any], rows: list[CheckRow],
                errata: Mapping[str, Mapping[str, Any]],
                figure_data: Mapping[str, str] | None = None,
                extra_links: Iterable[tuple[str, str]] = (),
                stress: list[Mapping[str, str]] | None = None,
                stress_skipped: Iterable[str] = (),
                problems: Iterable[str] = (),
                coverage: list[Mapping[str, Any]] | None = None,
                row_scene: Mapping[str, str] | None = None,
                figure_params: Mapping[str, Mapping[str, Any]] | None = None,
                own_parameters: Mapping[str, list[str]] | None = None,
                footer: str = "",
                figure_checks: Mapping[str, list[Offence]] | None = None,
                formats: Iterable[str] = ("pdf", "png")) -> str:
    """The report's HTML (written even when the check fails: then it says so at the top).
    Paths are relative to ``results/reports/``.

    Parameters
    ----------
    layout
        From :func:`load_layout`: sections with figures (scene -> caption), notebooks and
        animations.
    rows
        The tolerance check (:func:`flutterfriction.reference.run_check`).
    errata
        ``{id: reference entry}`` of the errata (printed, corrected, evidence).
    figure_data
        Figures drawn from another scene's data (``{figure: scene}``).
    extra_links
        ``(href, text)`` pairs listed at the top (benchmarks, ...).
    stress
        The stress tests (:mod:`flutterfriction.stress`, as dicts): what was tried, outcome.
    stress_skipped
        The stress areas this run left out (:func:`flutterfriction.stress.skipped_areas`).
    problems
        What failed the workflow's check (failed entries, figures missing from the layout),
        shown in a banner at the top.
    coverage
        :func:`load_coverage`'s entries: the table of the chapter's figures near the top (and
        the table of parameter lists after it).
    row_scene
        Check-row id -> the scene it checks (:func:`row_scenes`): each figure shows the rows
        of the scene it draws.
    figure_params
        Scene -> the parameters its data were computed with, shown under its figures.
    own_parameters
        Scene -> its changed physical keys (:func:`flutterfriction.reference.scene_parameter_
        changes`): its figures then say that their captions describe the chapter's figure and
        which check rows come from another scene's data.
    footer
        Provenance (commit, versions, date), shown at the bottom.
    figure_checks
        Figure -> its figure-check offences (:mod:`flutterfriction.figure_offences`): a line
        under the check's summary, and the offences in the check section.
    formats
        The figure files drawn (``("png",)`` in the quick preset: no PDF links then).
    """
    figure_data = dict(figure_data or {})
    row_scene = dict(row_scene or {})
    figure_params = dict(figure_params or {})
    rows_of: dict[str, list[CheckRow]] = {}
    for r in rows:
        if r.id in row_scene:
            rows_of.setdefault(row_scene[r.id], []).append(r)
    shown_checks: dict[str, str] = {}  # scene -> the first figure that shows its checks
    applicable = [r for r in rows if r.status != NOT_APPLICABLE]
    n_na = len(rows) - len(applicable)
    n_q = sum(r.kind == "quantity" for r in applicable)
    n_pass = sum(r.kind == "quantity" and r.status == "pass" for r in applicable)
    n_err = sum(r.kind == "erratum" for r in applicable)
    n_ver = sum(r.status == "verified erratum" for r in applicable)
    ok = n_pass == n_q and n_ver == n_err
    origins = origins_sentence(rows)
    title = html.escape(layout.get("title", "flutterfriction"))
    parts = [f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{title}"
             f"</title><style>{STYLE}</style></head><body><h1>{title}</h1>",
             f"<p>{layout.get('intro', '')}</p>",
             *(['<div class="summary bad"><b>The check FAILED</b>: the workflow stopped; '
                "what is wrong:<ul>" + "".join(f"<li>{html.escape(p)}</li>" for p in problems)
                + "</ul></div>"] if problems else []),
             f'<p class="summary{"" if ok else " bad"}"><b>Check</b>: {n_pass} of {n_q} '
             f"checked values (the chapter's quoted numbers, and values beyond it: each row "
             f"names its source and origin) reproduced within tolerance; {n_ver} of {n_err} "
             f"errata verified by an independent computation. {html.escape(origins)} "
             '<a href="#check">Check table</a> · '
             '<a href="../checks/summary.md">summary.md</a> · '
             '<a href="../checks/summary.json">summary.json</a></p>',
             *([f'<p class="summary na"><b>{n_na} checked values are not applicable</b>: '
                "their scenes ran with other parameters than the chapter's (your own), so the "
                "chapter's values do not apply; the check table names the changed keys.</p>"]
               if n_na else []),
             *([_figure_check_line(figure_checks)] if figure_checks is not None else [])]
    if extra_links:
        parts.append("<p>" + " · ".join(f'<a href="{html.escape(h)}">{html.escape(t)}</a>'
                                        for h, t in extra_links) + "</p>")
    parts.append("<nav><ul>" + ('<li><a href="#coverage">The chapter\'s figures: what is '
                                "reproduced</a></li><li><a href=\"#lists\">The parameter "
                                "lists</a></li>" if coverage is not None else "") + "".join(
        f'<li><a href="#s{k}">{html.escape(s["title"])}</a></li>'
        for k, s in enumerate(layout["sections"])) + '<li><a href="#check">The check</a></li>'
        + ('<li><a href="#stress">Stress tests</a></li>' if stress else "") + "</ul></nav>")
    if coverage is not None:
        scenes = {f: figure_data.get(f, f) for f in layout_figures(layout)}
        parts.append('<h2 id="coverage">The chapter\'s figures: what is reproduced</h2>'
                     "<p>Every figure of the chapter, which of our figures reproduces it and from "
                     "which computation, and what is not reproduced and why "
                     "(<code>workflow/coverage.yaml</code>).</p>")
        parts.append(coverage_html(coverage, scenes))
        parts.append('<h2 id="lists">The parameter lists</h2><p>The chapter\'s parameter '
                     "lists as the computations use them (<code>flutterfriction.parameters"
                     "</code>); the highlighted list is our choice: the chapter gives no "
                     "numbers there.</p>")
        parts.append(parameter_lists_html())
    # The chapter figures drawn from each data file (Figs. 6-9 share one): a row naming one of
    # them is shown under that figure, not under the first (a reader's review found Fig. 9's
    # values under Fig. 6 only).
    drawn_from: dict[str, set[int]] = {}
    for section in layout["sections"]:
        for scene in section.get("figures", {}):
            if (number := _chapter_number(scene)) is not None:
                drawn_from.setdefault(figure_data.get(scene, scene), set()).add(number)
    for k, section in enumerate(layout["sections"]):
        parts.append(f'<h2 id="s{k}">{html.escape(section["title"])}</h2>')
        if section.get("intro"):
            parts.append(f"<p>{section['intro']}</p>")
        if section.get("notebook"):
            nb = section["notebook"]
            parts.append(f'<p>Executed notebook: <a href="{nb}.html">{nb}.html</a> '
                         f"(source <code>notebooks/{nb}.py</code>)</p>")
        for scene, caption in section.get("figures", {}).items():
            data = figure_data.get(scene, scene)
            number = _chapter_number(scene)
            named = [r for r in rows if number in _figures_named(r.source)]
            others = drawn_from.get(data, set()) - {number}

            def elsewhere(r: CheckRow, others: set[int] = others, number=number) -> bool:
                names = _figures_named(r.source)
                return bool(names & others) and number not in names

            if data in shown_checks:
                mine = named
                checks = (f'<p class="links">Checked values of these data: with <a href="#fig-'
                          f'{shown_checks[data]}">{shown_checks[data]}</a>.</p>')
            else:
                own_rows = [r for r in rows_of.get(data, []) if not elsewhere(r)]
                mine = own_rows + [r for r in named if r not in own_rows]
                checks = ""
                if rows_of.get(data):
                    shown_checks[data] = scene
            own = (own_parameters or {}).get(data, [])
            if mine:
                checks = _figure_checks(mine, data if own else None, row_scene or {}) + checks
            params = (f'<p class="params">Drawn with: {_named_lists(figure_params[data])}</p>'
                      if figure_params.get(data) else "")
            printed = "".join(
                f'<p class="printed"><b>The chapter\'s Fig. {e["number"]}, as printed:</b> '
                f'{_caption_html(e["caption"])}</p>'
                for e in coverage or () if scene in e["figures"] and e.get("caption"))
            parts.append(
                f'<figure class="big" id="fig-{scene}"><a href="../figures/{scene}.png" '
                f'title="open the PNG"><img src="../figures/{scene}.png" alt="{scene}" '
                f'loading="lazy"></a><figcaption><b>{scene}</b>: {html.escape(caption)}'
                f'<div class="links"><a href="../figures/{scene}.png">PNG</a>'
                + (f'<a href="../figures/{scene}.pdf">PDF</a>' if "pdf" in formats else "")
                + f'<a href="../data/{data}.json">data ({html.escape(data)})</a></div>'
                f"{printed}{_own_note(own)}{checks}{params}</figcaption></figure>")
        for path, spec in section.get("images", {}).items():
            links = "".join(f'<a href="../{html.escape(h)}">{html.escape(t)}</a>'
                            for t, h in spec.get("links", {}).items()
                            if not h.endswith(".pdf") or "pdf" in formats)
            parts.append(
                f'<figure class="big"><a href="../{path}"><img src="../{path}" alt="{path}" '
                f'loading="lazy"></a><figcaption>{html.escape(spec["caption"])}'
                f'<div class="links">{links}</div></figcaption></figure>')
        parts.append('<div class="grid">')
        for gif, caption in section.get("animations", {}).items():
            parts.append(
                f'<figure class="anim"><a href="../figures/{gif}"><img src="../figures/{gif}" '
                f'alt="{gif}" '
                f'loading="lazy"></a><figcaption><b>{gif}</b>: {html.escape(caption)}'
                "</figcaption></figure>")
        parts.append("</div>")
    parts.append('<h2 id="check">The check: every quoted number, every erratum</h2>'
                 "<p>origin: where the reference value comes from: <i>printed</i> (a number "
                 "the chapter prints), <i>formula</i> (the chapter's closed form, evaluated "
                 "where it prints no number), <i>stated</i> (a statement or identity of the "
                 "chapter, as the value it implies: a sign, a regime, a zero residual) or "
                 "<i>ours</i> (beyond the chapter: our own exact, by-hand or computed value). "
                 "reference: that value; for an erratum, the printed form's value. "
                 "error: normalised error against the reference (for an erratum: printed "
                 "form against the independent computation, must exceed 1); agreement: primary "
                 "against independent method (must be at most 1). Errata rows are yellow; open "
                 "<i>evidence</i> for the printed and corrected forms.</p>")
    parts.append(_check_table(rows, errata))
    if figure_checks is not None:
        parts.append(_figure_check_section(figure_checks))
    if stress:
        parts.append(_stress_section(stress, tuple(stress_skipped)))
    if footer:
        parts.append(f'<hr><p class="params">{html.escape(footer)}</p>')
    parts.append("</body></html>")
    return "\n".join(parts)


def _figure_check_line(checks: Mapping[str, list[Offence]]) -> str:
    bad = sum(bool(o) for o in checks.values())
    return (f'<p class="summary{" bad" if bad else ""}"><b>Figure check</b>: '
            f"{len(checks) - bad} of {len(checks)} figures pass: {html.escape(FIGURE_RULES)}. "
            '<a href="#figure-check">Offences</a></p>')


def _figure_check_section(checks: Mapping[str, list[Offence]]) -> str:
    out = ['<h3 id="figure-check">The figure check</h3>',
           f"<p>Every figure the workflow draws, checked as matplotlib draws it "
           f"(<code>flutterfriction.figure_check</code>): {html.escape(FIGURE_RULES)}. "
           f"{sum(not o for o in checks.values())} of {len(checks)} figures pass.</p>"]
    bad = [(f, o) for f, offences in checks.items() for o in offences]
    if bad:
        out.append('<div class="wide"><table><thead><tr><th>figure</th><th>kind</th>'
                   "<th>text</th><th>with</th><th>axes</th></tr></thead><tbody>")
        out += [f'<tr class="fail"><td>{html.escape(f)}</td>' + "".join(
            f"<td>{html.escape(x)}</td>" for x in (o.kind, o.text, o.other, o.axes))
            + "</tr>" for f, o in bad]
        out.append("</tbody></table></div>")
    return "\n".join(out)


def _stress_section(stress: list[Mapping[str, str]], skipped: tuple[str, ...] = ()) -> str:
    counts = {k: sum(r["outcome"] == k for r in stress) for k in ("correct", "refused", "WRONG")}
    left_out = (f" Not run here: {html.escape(', '.join(skipped))} (<code>--config "
                "stress=full</code> runs every area; the tests run each)." if skipped else "")
    out = ['<h2 id="stress">Stress tests of numerical stability</h2>',
           f'<p class="summary{" bad" if counts["WRONG"] else ""}">{len(stress)} cases: '
           f'{counts["correct"]} correct, {counts["refused"]} refused clearly, '
           f'<b>{counts["WRONG"]} silent wrong answers</b>. Each solver pushed where numerics '
           "break, against an independent reference (50-digit mpmath, exact arithmetic)."
           f'{left_out} <a href="stress.md">stress.md</a></p>',
           '<div class="wide"><table><thead><tr><th>area</th><th>case</th><th>tried</th>'
           "<th>expected</th><th>got</th><th>outcome</th></tr></thead><tbody>"]
    for r in stress:
        cls = {"correct": "pass", "refused": "pass"}.get(r["outcome"], "fail")
        out.append(f'<tr class="{cls}">' + "".join(
            f"<td>{html.escape(str(r[k]))}</td>" for k in ("area", "case", "tried", "expected",
                                                          "got"))
            + f'<td class="status">{html.escape(r["outcome"])}</td></tr>')
    out.append("</tbody></table></div>")
    return "\n".join(out)


class _Links(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if name in ("href", "src") and value:
                self.links.append(value)
            if name == "id" and value:
                self.ids.add(value)


def broken_links(page: str | Path) -> list[str]:
    """Every relative link or in-page anchor of the HTML file ``page`` that does not resolve
    (external ``http(s)``/``mailto`` links are not followed)."""
    page = Path(page)
    parser = _Links()
    parser.feed(page.read_text(encoding="utf-8"))
    bad = []
    for link in parser.links:
        parts = urlsplit(link)
        if parts.scheme in ("http", "https", "mailto", "data"):
            continue
        if not parts.path:
            if parts.fragment and parts.fragment not in parser.ids:
                bad.append(link)
            continue
        if not (page.parent / unquote(parts.path)).exists():
            bad.append(link)
    return bad


def provenance(root: str | Path | None = None) -> str:
    """One line for the index page's footer (only there, so the data files stay byte-identical
    between runs): the commit (``+changes`` when the work tree differs from it), the versions
    of Python and the numerical packages, and the date."""
    import datetime
    import platform
    import subprocess
    from importlib.metadata import PackageNotFoundError, version

    root = Path(root) if root is not None else Path(__file__).resolve().parents[2]

    def git(*args: str) -> str:
        try:
            return subprocess.run(["git", *args], cwd=root, capture_output=True, text=True,
                                  timeout=10, check=True).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            return ""

    commit = git("rev-parse", "--short=12", "HEAD") or "unknown"
    if commit != "unknown" and git("status", "--porcelain", "--untracked-files=no"):
        commit += "+changes"
    versions = []
    for pkg in ("flutterfriction", "numpy", "scipy", "matplotlib", "scikit-fem", "sympy"):
        try:
            versions.append(f"{pkg} {version(pkg)}")
        except PackageNotFoundError:
            pass
    date = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    return (f"Built from commit {commit} with Python {platform.python_version()}, "
            f"{', '.join(versions)}, on {date}.")
