"""Executed notebooks as HTML a reader can use offline: ``results/reports/<notebook>.html``.

nbconvert's HTML loads MathJax, RequireJS and Mermaid from the network, so offline every
equation shows as raw TeX. Here

- every ``$...$`` and ``$$...$$`` of the markdown (cells and ``text/markdown`` outputs) is
  converted to MathML at export (``latex2mathml``), which browsers render natively: no script,
  no network;
- code inputs are folded (a ``<details>`` per cell, closed): the page reads as text, tables and
  figures, and the code is one click away;
- a PNG output identical to a workflow figure (``results/figures/<name>.png``) is not embedded
  again but linked (``../figures/<name>.png``), which keeps the pages small; the page then
  needs the ``results/`` folder beside it, as the report does.
"""

from __future__ import annotations

import base64
import html
import re
from collections.abc import Iterable
from pathlib import Path
from typing import Any

#: ``$$...$$`` (display) or ``$...$`` (inline, within a paragraph, not ``\$``), outside code.
_MATH = re.compile(r"(?<!\\)\$\$(.+?)(?<!\\)\$\$"
                   r"|(?<![\\$])\$(?!\s)((?:[^$\n]|\n(?![ \t]*\n))+?)(?<![\s\\])\$(?!\$)", re.S)
_CODE = re.compile(r"(```.*?```|`[^`\n]*`)", re.S)


def _mathml(tex: str, display: bool) -> str:
    from latex2mathml.converter import convert

    try:
        return convert(tex.strip(), display="block" if display else "inline")
    except Exception:  # noqa: BLE001  (an unknown command: show the TeX, never fail the page)
        return f"<code>{html.escape(tex)}</code>"


def math_to_mathml(text: str) -> str:
    """``text`` (markdown) with its TeX math replaced by MathML; code spans are left alone."""
    def convert(chunk: str) -> str:
        return _MATH.sub(lambda m: _mathml(m.group(1), True) if m.group(1) is not None
                         else _mathml(m.group(2), False), chunk)

    return "".join(part if i % 2 else convert(part)
                   for i, part in enumerate(_CODE.split(text)))


def figure_index(figure_dirs: Iterable[str | Path]) -> dict[str, str]:
    """Base64 of every PNG under ``figure_dirs`` -> its file name (to recognise the workflow's
    figures among a notebook's outputs)."""
    out = {}
    for d in figure_dirs:
        for png in sorted(Path(d).glob("*.png")):
            out[base64.b64encode(png.read_bytes()).decode()] = png.name
    return out


def offline_notebook(nb: Any, figures: dict[str, str] | None = None,
                     figure_href: str = "../figures") -> Any:
    """The executed notebook ``nb`` (nbformat node, changed in place and returned) prepared
    for offline HTML: math as MathML in markdown cells and markdown outputs; PNG outputs equal
    to a workflow figure (``figures``, from :func:`figure_index`) replaced by a link to it."""
    figures = figures or {}
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            cell.source = math_to_mathml(cell.source)
        for out in cell.get("outputs", []):
            data = out.get("data")
            if not data:
                continue
            if "text/markdown" in data:
                data["text/markdown"] = math_to_mathml(data["text/markdown"])
            png = data.get("image/png")
            if isinstance(png, str) and png.replace("\n", "") in figures:
                name = figures[png.replace("\n", "")]
                width = (out.get("metadata", {}).get("image/png") or {}).get("width")
                style = f' style="width: {int(width)}px; max-width: 100%"' if width else \
                    ' style="max-width: 100%"'
                data.clear()
                data["text/html"] = (f'<a href="{figure_href}/{name}"><img src="{figure_href}/'
                                     f'{name}" alt="{name}" title="{name}: click for the '
                                     f'full-size figure"{style}></a>')
                out["metadata"] = {}
    return nb


_TEMPLATE = """{%- extends 'lab/index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{%- block html_head_js_mathjax -%}{%- endblock html_head_js_mathjax -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
{% block extra_css %}
<style>
details.code-fold > summary { cursor: pointer; color: #666; font-size: 12px; margin: 2px 0 2px
  64px; font-family: monospace; }
details.code-fold[open] > summary { color: #333; }
main { max-width: 1100px; margin: 0 auto; }
math { font-size: 1.08em; } math[display="block"] { margin: .6em 0; overflow-x: auto; }
.jp-RenderedMarkdown { overflow-x: auto; }
.jp-RenderedHTMLCommon table { font-size: 13px; }
</style>
{% endblock extra_css %}
{% block input_group -%}
<details class="code-fold"><summary>code</summary>
{{ super() }}
</details>
{%- endblock input_group %}
"""


def notebook_html(nb: Any) -> str:
    """HTML of the executed notebook ``nb`` with no script loaded from the network: code folded,
    output prompts hidden (apply :func:`offline_notebook` first for the math)."""
    import jinja2
    from nbconvert import HTMLExporter

    exporter = HTMLExporter(template_name="lab", template_file="offline.html.j2",
                            extra_loaders=[jinja2.DictLoader({"offline.html.j2": _TEMPLATE})],
                            exclude_output_prompt=True, exclude_input_prompt=True)
    body, _ = exporter.from_notebook_node(nb)
    return body


def export_notebook(nb: Any, figure_dirs: Iterable[str | Path] = ("results/figures",),
                    figure_href: str = "../figures") -> str:
    """An executed notebook's offline HTML: :func:`offline_notebook`, then
    :func:`notebook_html`."""
    import nbformat

    nb = nbformat.from_dict(nb)
    return notebook_html(offline_notebook(nb, figure_index(figure_dirs), figure_href))


def warm_exporter() -> None:
    """Export a two-cell notebook (markdown with math, code with output) and discard it: the
    first export of a process imports nbconvert and compiles its templates and the
    highlighter's patterns (0.92 s against 0.31 s for the next, measured), so that a job can
    do it while something else runs (the notebook job: while its kernel starts)."""
    import nbformat.v4 as v4

    nb = v4.new_notebook(cells=[
        v4.new_markdown_cell("warm-up: $x^2$"),
        v4.new_code_cell("print(1)", outputs=[v4.new_output("stream", text="1\n")])])
    export_notebook(nb, ())


def fmt(x: Any, digits: int = 6) -> str:
    """A number in ``digits`` significant digits (text and other values as they are)."""
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        return str(x)
    return f"{x:.{digits}g}"


def quantities_table(quantities: dict[str, dict[str, Any]], digits: int = 7,
                     absolute: Iterable[str] = ()) -> str:
    """A scene's ``quantities`` (value, unit, method, independent value and method) as a
    markdown table for a notebook: ``digits`` significant digits, the unit, and the relative
    difference of the two methods; for the quantities named in ``absolute`` (residuals, whose
    quoted value is 0, so that a relative difference of two round-offs means nothing) the
    absolute difference, marked "(abs.)"; also wherever one of the two is exactly 0."""
    absolute = set(absolute)
    lines = ["| quantity | value | unit | method | independent | independent method | "
             "rel. difference |", "|---|---|---|---|---|---|---|"]
    for k, q in quantities.items():
        v, w = q.get("value"), q.get("independent")
        diff = ""
        if all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in (v, w)):
            scale = max(abs(v), abs(w))
            # against an exact 0 (a residual) a relative difference is always 1: absolute then
            relative = k not in absolute and v != 0 and w != 0
            diff = "0" if v == w else (f"{abs(v - w) / scale:.1e}" if relative else
                                       f"{abs(v - w):.1e} (abs.)")
        cells = [k, fmt(v, digits), q.get("unit", ""), q.get("method", ""), fmt(w, digits),
                 q.get("independent_method", ""), diff]
        lines.append("| " + " | ".join(str(c).replace("|", "\\|") for c in cells) + " |")
    return "\n".join(lines)
