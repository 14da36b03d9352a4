"""The one report: its layout covers every figure, and every link it writes resolves."""

from pathlib import Path

import pytest

from flutterfriction.errors import ParameterError
from flutterfriction.reference import CheckRow
from flutterfriction.registry import PARTS, figures
from flutterfriction.report import (
    CHAPTER_FIGURES,
    broken_links,
    build_index,
    coverage_markdown,
    coverage_problems,
    layout_figures,
    load_coverage,
    load_layout,
    parameter_list_rows,
    parameter_lists_markdown,
    registry_figure_scenes,
    row_scenes,
)

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


def _coverage():
    return [{"number": 1, "title": "the A figure",
             "caption": "Branches of $\\tilde{\\omega}$ & co, stick for $a < 0$",
             "status": "reproduced", "figures": ["figA"], "shows": "all of it"},
            {"number": 2, "title": "a photograph", "caption": "Two silos.",
             "status": "not reproduced", "figures": [], "missing": "a photograph"}]


def test_every_link_of_a_built_report_resolves(tmp_path):
    res, layout = _tree(tmp_path)
    errata = {"e1": {"printed": "a", "corrected": "b", "evidence": "sympy says so"}}
    page = res / "reports" / "index.html"
    page.write_text(build_index(
        layout, _rows(), errata, figure_data={"figB": "shared"}, coverage=_coverage(),
        row_scene={"q1": "figA", "e1": "shared"}, figure_params={"figA": {"n": 3}},
        footer="built from commit abc"))
    assert broken_links(page) == []
    text = page.read_text()
    assert "caption &lt;B&gt; &amp; more" in text  # captions are escaped
    assert "sympy says so" in text and "1 of 1 checked values" in text
    assert 'id="coverage"' in text and 'id="lists"' in text and "built from commit abc" in text


def _figure_block(text, name):
    start = text.index(f'<figure class="big" id="fig-{name}"')
    return text[start:text.index("</figure>", start)]


def test_each_figure_is_shown_large_with_its_caption_links_and_checked_values(tmp_path):
    res, layout = _tree(tmp_path)
    page = res / "reports" / "index.html"
    page.write_text(build_index(layout, _rows(), {}, figure_data={"figB": "shared"},
                                row_scene={"q1": "figA", "e1": "shared"},
                                figure_params={"figA": {"n": 3}}))
    text = page.read_text()
    a, b = _figure_block(text, "figA"), _figure_block(text, "figB")
    assert "caption A" in a and 'href="../figures/figA.png"' in a
    assert 'href="../figures/figA.pdf"' in a and 'href="../data/figA.json"' in a
    assert 'href="#q1"' in a and "e1" not in a and "Drawn with: n = 3" in a
    assert 'href="#e1"' in b and 'href="../data/shared.json"' in b
    assert "height: 190px" not in text.split("figure.big img")[1].split("}")[0]
    assert broken_links(page) == []


def test_each_figure_shows_the_chapter_caption_it_reproduces_with_its_math(tmp_path):
    res, layout = _tree(tmp_path)
    text = build_index(layout, _rows(), {}, figure_data={"figB": "shared"},
                       coverage=_coverage())
    a, b = _figure_block(text, "figA"), _figure_block(text, "figB")
    assert "The chapter's Fig. 1, as printed:</b> Branches of <math" in a  # TeX -> MathML
    assert "&amp; co" in a and "$" not in a.split("as printed")[1]
    # the math converted unescaped: its "<" is MathML's operator, not a stray "&lt;"
    assert "<mo>&#x0003C;</mo>" in a and "&lt;" not in a.split("as printed")[1]
    assert "as printed" not in b  # figB reproduces no chapter figure listed in the coverage


def test_the_coverage_file_quotes_the_chapter_captions_verbatim():
    """Every chapter figure's printed caption, word for word (when the chapter's text is at
    hand: ../shared/chapter in the development tree; a clone without it checks the count)."""
    import re

    entries = load_coverage(ROOT / "workflow" / "coverage.yaml")
    assert [bool(e["caption"].strip()) for e in entries] == [True] * CHAPTER_FIGURES
    chapter = ROOT.parent / "shared" / "chapter" / "flutter-from-friction.md"
    if not chapter.is_file():
        pytest.skip("the chapter's text is not beside this clone")
    printed = {int(m[1]): " ".join(m[2].split()) for m in re.finditer(
        r"^\*\*Figure (\d+)\.\*\* (.*)$", chapter.read_text(encoding="utf-8"), re.M)}
    assert {e["number"]: e["caption"] for e in entries} == printed


def test_a_figure_of_your_own_parameters_says_its_captions_are_the_chapters(tmp_path):
    """A second outside audit: with your own parameters the report's captions still quoted the
    chapter's loads and lists next to your figure, and rows checked on another scene's data
    (fig13 shows fig14's) read as checks of your figure. Now a note names your changed keys and
    such rows say whose data they check."""
    res, layout = _tree(tmp_path)
    rows = _rows()
    text = build_index(layout, rows, {}, figure_data={"figB": "shared"},
                       row_scene={"q1": "figA", "e1": "other"},
                       own_parameters={"shared": ["pendulum.k1: 0.189 -> 0.25"]})
    b, a = _figure_block(text, "figB"), _figure_block(text, "figA")
    assert "Drawn with your own parameters</b> (pendulum.k1: 0.189 -&gt; 0.25)" in b
    assert "your own parameters" not in a
    # a row naming Fig. 13 but computed from another scene's data, under your own fig13
    row = CheckRow(id="sec29_period", kind="quantity", source="§2.9 Fig. 13", quoted=1.0,
                   unit="s", reproduced=1.0, independent=1.0, method="m", independent_method="i",
                   error=0.0, agreement=0.0, status="pass")
    layout13 = {"title": "T", "sections": [{"title": "S", "figures": {"fig13": "c"}}]}
    text = build_index(layout13, [row], {}, row_scene={"sec29_period": "fig14"},
                       own_parameters={"fig13": ["pendulum.l2: 0.1 -> 0.12"]})
    assert "(checked on fig14's data, not this figure's)" in _figure_block(text, "fig13")


def test_figures_drawing_the_same_data_show_its_checks_once(tmp_path):
    res, layout = _tree(tmp_path)
    page = res / "reports" / "index.html"
    page.write_text(build_index(layout, _rows(), {}, figure_data={"figB": "figA"},
                                row_scene={"q1": "figA"}))
    text = page.read_text()
    assert 'href="#q1"' in _figure_block(text, "figA")
    b = _figure_block(text, "figB")
    assert 'href="#q1"' not in b and 'href="#fig-figA"' in b
    assert broken_links(page) == []


def test_every_check_row_of_the_reference_names_a_scene():
    import yaml

    ref = yaml.safe_load((ROOT / "workflow" / "reference.yaml").read_text())
    scenes = row_scenes(ref)
    assert len(scenes) == len(ref["quantities"]) + len(ref["errata"])


def test_the_coverage_table_lists_every_chapter_figure_and_only_drawn_figures():
    entries = load_coverage(ROOT / "workflow" / "coverage.yaml")
    assert [e["number"] for e in entries] == list(range(1, CHAPTER_FIGURES + 1))
    scenes = registry_figure_scenes()
    # a figure the table names must be one the registry draws; a chapter figure the registry
    # draws (figNN) must be in the table under its number
    assert coverage_problems(entries, scenes) == []
    assert entries[23]["status"] == "not reproduced"  # Fig. 24 is a photograph
    for n in (19, 20, 21):
        assert entries[n - 1]["status"] == "reproduced in part"


def test_coverage_problems_name_an_undrawn_figure_and_an_unlisted_one():
    entries = _coverage()
    assert coverage_problems(entries, {"figA": "figA"}) == []
    missing = coverage_problems(entries, {})
    assert len(missing) == 1 and "'figA'" in missing[0]
    unlisted = coverage_problems(entries, {"figA": "figA", "fig02": "fig02"})
    assert len(unlisted) == 1 and "Fig. 2 does not list" in unlisted[0]


def test_a_drawing_listed_under_two_chapter_figures_is_a_coverage_problem():
    """An outside audit: one figure under two chapter figures was accepted (the second
    silently replaced the first)."""
    entries = [dict(e, figures=["figA"]) for e in _coverage()[:1]] * 2
    entries = [entries[0], dict(entries[1], number=entries[0]["number"] + 1)]
    problems = coverage_problems(entries, {"figA": "figA"})
    assert len(problems) == 1 and "'figA' is listed under Fig. " in problems[0]


def test_an_invalid_coverage_file_is_refused(tmp_path):
    p = tmp_path / "coverage.yaml"
    p.write_text("figures:\n  - {number: 1, title: t, status: reproduced, figures: []}\n")
    with pytest.raises(ParameterError, match="invalid coverage file"):
        load_coverage(p)  # reproduced needs a figure and what it shows; and 24 figures


def test_the_readme_tables_render_as_markdown():
    md = coverage_markdown()
    lines = md.splitlines()
    assert lines[0].startswith("| Fig. |")
    assert sum(line.startswith("| ") for line in lines) == CHAPTER_FIGURES + 1
    assert "[fig02](results/figures/fig02.png)" in md and "Of the chapter's 24 figures" in md
    rows = parameter_list_rows()
    assert [r["ours"] for r in rows].count(True) == 1 and rows[-1]["name"] == "sec35"
    lists = parameter_lists_markdown()
    assert "**sec35**" in lists and "OUR CHOICE" in lists and "0.189 N m" in lists


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


def test_a_layout_section_naming_no_chapter_part_is_refused(tmp_path):
    p = tmp_path / "layout.yaml"
    p.write_text("title: T\nsections:\n  - title: S\n    notebook: rodz\n")
    with pytest.raises(ParameterError, match="sections.0.notebook"):
        load_layout(p)


def test_the_layout_schema_lists_the_registry_parts():
    import yaml

    schema = yaml.safe_load((ROOT / "workflow" / "schemas" / "report.schema.yaml").read_text())
    from flutterfriction.registry import PARTS

    parts = schema["properties"]["sections"]["items"]["properties"]["notebook"]["enum"]
    assert parts == list(PARTS)


def test_a_check_row_naming_a_chapter_figure_is_shown_under_it(tmp_path):
    res, _ = _tree(tmp_path, figures=("fig02", "fig03"))
    (res / "data" / "fig02.json").write_text("{}")
    (res / "data" / "fig03.json").write_text("{}")
    layout = {"title": "T", "sections": [{"title": "S", "figures": {
        "fig02": "Fig. 2", "fig03": "Fig. 3"}}]}
    rows = _rows()
    rows[0].source = "§2 Figs. 1-2 caption"  # q1 checks other data but names Fig. 2
    page = res / "reports" / "index.html"
    page.write_text(build_index(layout, rows, {}, row_scene={"q1": "elsewhere"}))
    text = page.read_text()
    assert 'href="#q1"' in _figure_block(text, "fig02")
    assert 'href="#q1"' not in _figure_block(text, "fig03")
    assert broken_links(page) == []


def test_the_readme_shows_the_current_coverage_and_parameter_lists():
    """The README claims no more than the coverage table shows: its copy is the generated one."""
    from flutterfriction.report import coverage_markdown, parameter_lists_markdown

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert coverage_markdown().rstrip() in readme
    assert parameter_lists_markdown().rstrip() in readme


def test_quick_preset_report_links_no_pdf(tmp_path):
    """The quick preset draws PNG only: its report links no PDF (the link check would fail)."""
    layout = {"title": "T", "sections": [{"title": "S", "figures": {"figA": "caption A"}}]}
    html_text = build_index(layout, _rows(), {}, formats=("png",))
    assert 'href="../figures/figA.png"' in html_text
    assert ".pdf" not in html_text


def test_the_stress_section_names_the_areas_this_run_left_out(tmp_path):
    _, layout = _tree(tmp_path)
    case = {"area": "a", "case": "c", "tried": "t", "expected": "e", "got": "g",
            "outcome": "correct"}
    text = build_index(layout, _rows(), {}, stress=[case],
                       stress_skipped=["rod: regimes along p", "rod: <slow>"])
    assert "1 cases: 1 correct" in text
    assert "Not run here: rod: regimes along p, rod: &lt;slow&gt;" in text
    assert "--config stress=full</code> runs every area" in text
    assert "Not run here" not in build_index(layout, _rows(), {}, stress=[case])
