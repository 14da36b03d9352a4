"""One HTML report for everything the workflow builds: ``results/reports/index.html``.

It shows every figure (thumbnail, caption, links to the PDF and to the data it draws), every
executed notebook, the stress report and the tolerance check (quoted value, reproduced value,
independent method, status), with the errata highlighted next to their evidence. All links are
relative, so the ``results/`` folder can be moved or archived as a whole; :func:`broken_links`
checks that every one of them resolves.
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from html.parser import HTMLParser
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urlsplit

import yaml

from flutterfriction.errors import ParameterError
from flutterfriction.reference import CheckRow

STYLE = """
body { font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em;
       color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; padding-bottom: .2em; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(270px, 1fr)); gap: 1em; }
figure { margin: 0; border: 1px solid #ddd; border-radius: 4px; padding: .5em; background: #fff; }
figure img { width: 100%; height: 190px; object-fit: contain; }
figcaption { font-size: .85em; } figcaption a { margin-right: .6em; }
table { border-collapse: collapse; font-size: .8em; width: 100%; }
th, td { border: 1px solid #ddd; padding: .25em .4em; vertical-align: top; text-align: left; }
th { background: #f3f3f3; position: sticky; top: 0; }
tr.pass td.status { color: #176117; } tr.fail td { background: #fde2e2; }
tr.erratum td { background: #fff6d6; } td.num { font-family: monospace; white-space: nowrap; }
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
    with open(path, encoding="utf-8") as fh:
        layout = yaml.safe_load(fh)
    if figures is None:
        from flutterfriction.registry import PARTS, scenes_of

        figures = {part: {f: spec.caption for s in scenes_of(part)
                          for f, spec in s.figures.items()} for part in PARTS}
    for section in layout.get("sections", []):
        unknown = set(section) - {"title", "intro", "notebook", "animations", "images"}
        if unknown:
            raise ParameterError(f"report layout: unknown keys {sorted(unknown)} in section "
                                 f"{section.get('title')!r}")
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


def _check_table(rows: Iterable[CheckRow], errata: Mapping[str, Mapping[str, Any]]) -> str:
    out = ['<div class="wide"><table><thead><tr><th>id</th><th>source</th><th>quoted</th>'
           "<th>reproduced</th>"
           "<th>method</th><th>independent</th><th>independent method</th>"
           "<th>error / agreement</th><th>status</th></tr></thead><tbody>"]
    for r in rows:
        cls = "erratum" if r.kind == "erratum" else ("pass" if r.status == "pass" else "fail")
        if r.status not in ("pass", "verified erratum"):
            cls = "fail"
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
            f"{_cell(r.quoted, unit)}{_cell(r.reproduced)}"
            f"<td>{method}</td>{_cell(r.independent)}"
            f"<td>{html.escape(r.independent_method)}</td><td class=\"num\">{err} / {agr}</td>"
            f'<td class="status">{html.escape(r.shown_status)}</td></tr>')
    out.append("</tbody></table></div>")
    return "\n".join(out)


def build_index(layout: Mapping[str, Any], rows: list[CheckRow],
                errata: Mapping[str, Mapping[str, Any]],
                figure_data: Mapping[str, str] | None = None,
                extra_links: Iterable[tuple[str, str]] = (),
                stress: list[Mapping[str, str]] | None = None,
                problems: Iterable[str] = ()) -> str:
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
    problems
        What failed the workflow's check (failed entries, figures missing from the layout),
        shown in a banner at the top.
    """
    figure_data = dict(figure_data or {})
    n_q = sum(r.kind == "quantity" for r in rows)
    n_pass = sum(r.kind == "quantity" and r.status == "pass" for r in rows)
    n_err = sum(r.kind == "erratum" for r in rows)
    n_ver = sum(r.status == "verified erratum" for r in rows)
    ok = n_pass == n_q and n_ver == n_err
    title = html.escape(layout.get("title", "flutterfriction"))
    parts = [f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{title}"
             f"</title><style>{STYLE}</style></head><body><h1>{title}</h1>",
             f"<p>{layout.get('intro', '')}</p>",
             *(['<div class="summary bad"><b>The check FAILED</b>: the workflow stopped; '
                "what is wrong:<ul>" + "".join(f"<li>{html.escape(p)}</li>" for p in problems)
                + "</ul></div>"] if problems else []),
             f'<p class="summary{"" if ok else " bad"}"><b>Check</b>: {n_pass} of {n_q} '
             f"quoted values reproduced within tolerance; {n_ver} of {n_err} errata verified by "
             'an independent computation. <a href="#check">Check table</a> · '
             '<a href="../checks/summary.md">summary.md</a> · '
             '<a href="../checks/summary.json">summary.json</a></p>']
    if extra_links:
        parts.append("<p>" + " · ".join(f'<a href="{html.escape(h)}">{html.escape(t)}</a>'
                                        for h, t in extra_links) + "</p>")
    parts.append("<nav><ul>" + "".join(
        f'<li><a href="#s{k}">{html.escape(s["title"])}</a></li>'
        for k, s in enumerate(layout["sections"])) + '<li><a href="#check">The check</a></li>'
        + ('<li><a href="#stress">Stress tests</a></li>' if stress else "") + "</ul></nav>")
    for k, section in enumerate(layout["sections"]):
        parts.append(f'<h2 id="s{k}">{html.escape(section["title"])}</h2>')
        if section.get("intro"):
            parts.append(f"<p>{section['intro']}</p>")
        if section.get("notebook"):
            nb = section["notebook"]
            parts.append(f'<p>Executed notebook: <a href="{nb}.html">{nb}.html</a> '
                         f"(source <code>notebooks/{nb}.py</code>)</p>")
        parts.append('<div class="grid">')
        for scene, caption in section.get("figures", {}).items():
            data = figure_data.get(scene, scene)
            parts.append(
                f'<figure id="fig-{scene}"><a href="../figures/{scene}.png">'
                f'<img src="../figures/{scene}.png" alt="{scene}" loading="lazy"></a>'
                f"<figcaption><b>{scene}</b>: {html.escape(caption)}<br>"
                f'<a href="../figures/{scene}.pdf">PDF</a>'
                f'<a href="../data/{data}.json">data</a></figcaption></figure>')
        for path, spec in section.get("images", {}).items():
            links = "".join(f'<a href="../{html.escape(h)}">{html.escape(t)}</a>'
                            for t, h in spec.get("links", {}).items())
            parts.append(
                f'<figure><a href="../{path}"><img src="../{path}" alt="{path}" '
                f'loading="lazy"></a><figcaption>{html.escape(spec["caption"])}<br>{links}'
                "</figcaption></figure>")
        for gif, caption in section.get("animations", {}).items():
            parts.append(
                f'<figure><a href="../figures/{gif}"><img src="../figures/{gif}" alt="{gif}" '
                f'loading="lazy"></a><figcaption><b>{gif}</b>: {html.escape(caption)}'
                "</figcaption></figure>")
        parts.append("</div>")
    parts.append('<h2 id="check">The check: every quoted number, every erratum</h2>'
                 "<p>error: normalised error against the quoted value (for an erratum: printed "
                 "form against the independent computation, must exceed 1); agreement: primary "
                 "against independent method (must be at most 1). Errata rows are yellow; open "
                 "<i>evidence</i> for the printed and corrected forms.</p>")
    parts.append(_check_table(rows, errata))
    if stress:
        parts.append(_stress_section(stress))
    parts.append("</body></html>")
    return "\n".join(parts)


def _stress_section(stress: list[Mapping[str, str]]) -> str:
    counts = {k: sum(r["outcome"] == k for r in stress) for k in ("correct", "refused", "WRONG")}
    out = ['<h2 id="stress">Stress tests of numerical stability</h2>',
           f'<p class="summary{" bad" if counts["WRONG"] else ""}">{len(stress)} cases: '
           f'{counts["correct"]} correct, {counts["refused"]} refused clearly, '
           f'<b>{counts["WRONG"]} silent wrong answers</b>. Each solver pushed where numerics '
           "break, against an independent reference (50-digit mpmath, exact arithmetic). "
           '<a href="stress.md">stress.md</a></p>',
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
