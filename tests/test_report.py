"""The one report: its layout covers every figure, and every link it writes resolves."""

from pathlib import Path

import pytest

from flutterfriction.errors import ParameterError
from flutterfriction.reference import CheckRow
from flutterfriction.registry import PARTS, figures
from flutterfriction.report import broken_links, build_index, layout_figures, load_layout

ROOT = Path(__file__).resolve().parents[1]


def _rows():
    return [
        CheckRow(id="q1", kind="quantity", source="eq. (1)", quoted=1.0, unit="N",
                 reproduced=1.0, independent=1.0, method="closed form", independent_method="eig",
                 error=0.0, agreement=0.0, status="pass"),
        CheckRow(id="e1", kind="erratum", source="eq. (2)", quoted="printed: a -> 2",
                 unit="", reproduced=3.0, independent=3.0, method="corrected: b",
                 independent_method="sympy", error=5.0, agreement=0.0,
                 status="verified erratum"),
    ]


def _tree(tmp_path, figures=("figA", "figB")):
    res = tmp_path / "results"
    for sub in ("figures", "data", "reports", "checks"):
        (res / sub).mkdir(parents=True)
    for f in figures:
        for ext in ("png", "pdf"):
            (res / "figures" / f"{f}.{ext}").write_bytes(b"x")
    (res / "data" / "figA.json").write_text("{}")
    (res / "data" / "shared.json").write_text("{}")
    (res / "reports" / "nb.html").write_text("<html></html>")
    for name in ("summary.md", "summary.json"):
        (res / "checks" / name).write_text("")
    layout = {"title": "T", "sections": [{"title": "S", "notebook": "nb", "figures": {
        "figA": "caption A", "figB": "caption <B> & more"}}]}
    return res, layout


def test_every_link_of_a_built_report_resolves(tmp_path):
    res, layout = _tree(tmp_path)
    errata = {"e1": {"printed": "a", "corrected": "b", "evidence": "sympy says so"}}
    page = res / "reports" / "index.html"
    page.write_text(build_index(layout, _rows(), errata, figure_data={"figB": "shared"}))
    assert broken_links(page) == []
    text = page.read_text()
    assert "caption &lt;B&gt; &amp; more" in text  # captions are escaped
    assert "sympy says so" in text and "1 of 1 quoted values" in text


def test_a_missing_file_or_anchor_is_reported(tmp_path):
    res, layout = _tree(tmp_path)
    page = res / "reports" / "index.html"
    page.write_text(build_index(layout, _rows(), {}) + '<a href="#nowhere">x</a>')
    (res / "figures" / "figA.pdf").unlink()
    # figB draws its own data here, which does not exist
    assert sorted(broken_links(page)) == ["#nowhere", "../data/figB.json", "../figures/figA.pdf"]


def test_the_layout_shows_every_figure_the_workflow_draws():
    layout = load_layout(ROOT / "workflow" / "report.yaml")
    shown = layout_figures(layout)
    assert len(shown) == len(set(shown))
    assert shown == list(figures())  # every registered figure, in the registry's order
    assert {s["notebook"] for s in layout["sections"] if "notebook" in s} == set(PARTS)


def test_an_unknown_layout_key_is_refused(tmp_path):
    p = tmp_path / "layout.yaml"
    p.write_text("sections:\n  - title: S\n    figure: {}\n")
    with pytest.raises(ParameterError, match="unknown keys"):
        load_layout(p)
