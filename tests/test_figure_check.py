"""The figure check catches what makes a figure illegible or unexplained (issue 13): deliberately
broken figures fail it, each for its reason, and a clean figure passes."""

from __future__ import annotations

import json

import matplotlib
import numpy as np
import pytest
from conftest import ROOT

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

from flutterfriction.figure_check import check_figure  # noqa: E402
from flutterfriction.figure_offences import (  # noqa: E402
    Offence,
    figure_checks_markdown,
    figure_checks_summary,
    figure_problems,
    load_figure_checks,
    offences_json,
)
from flutterfriction.plotting import save_figure  # noqa: E402

X = np.linspace(0.0, 1.0, 21)


def clean():
    """Two explained curves, both axes labelled with units, a legend clear of everything."""
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    ax.plot(X, X, color="C0", label="linear")
    ax.plot(X, X**2, color="C3", ls="--", label="quadratic")
    ax.axhline(0.5, color="k", lw=0.8)  # a reference line: left to its annotation
    ax.annotate("half", (0.05, 0.52), fontsize=7)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("ratio [-]")
    ax.set_title("clean")
    ax.legend(loc="upper left")
    return fig, ax


def kinds(offences: list[Offence]) -> list[str]:
    return sorted(o.kind for o in offences)


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def test_a_clean_figure_passes():
    fig, _ = clean()
    assert check_figure(fig) == []


def test_two_overlapping_texts_are_caught_by_name():
    fig, ax = clean()
    ax.text(0.6, 0.2, "flutter load")
    ax.text(0.62, 0.21, "divergence load")
    offences = check_figure(fig)
    assert kinds(offences) == ["overlap"]
    assert {offences[0].text, offences[0].other} == {"flutter load", "'divergence load'"}
    assert "clean" in offences[0].axes  # the axes, by its title


def test_small_text_in_a_wide_figure_is_caught_and_the_same_text_in_a_narrow_one_passes():
    # 6.5 pt in a 14-inch figure: 6.5/72 * 1200/14 = 7.7 px when shown 1200 px wide (a review
    # read Fig. 22's legends so); in a 4-inch figure shown at 200 dpi, 18 px
    fig, ax = clean()
    ax.text(0.6, 0.1, "slip onset", fontsize=6.5)
    assert check_figure(fig) == []
    fig.set_size_inches(14.0, 3.0)
    offences = check_figure(fig)
    assert "small" in kinds(offences)
    small = [o for o in offences if o.kind == "small"]
    assert {o.text for o in small} >= {"slip onset"}
    assert all(" px in a 1" in o.other and "-inch figure shown 1200 px wide" in o.other
               for o in small)
    # 10 pt there is 11.9 px: legible
    for t in ax.texts:
        t.set_fontsize(10)
    assert "slip onset" not in {o.text for o in check_figure(fig) if o.kind == "small"}


def test_a_tick_label_under_a_long_title_of_the_next_panel_overlaps():
    fig, (a, b) = plt.subplots(1, 2, figsize=(4.0, 2.0))
    for ax in (a, b):
        ax.plot(X, X)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    a.set_title("a title far too long for its own panel, running into the next")
    b.set_title("second")
    assert "overlap" in kinds(check_figure(fig))


def test_a_label_clipped_by_its_axes_is_caught():
    fig, ax = clean()
    ax.text(0.9, 0.3, "a label running out of the axes", transform=ax.transAxes, clip_on=True)
    offences = check_figure(fig)
    assert kinds(offences) == ["clipped"]
    assert offences[0].text == "a label running out of the axes"


def test_text_beyond_the_saved_area_is_clipped():
    fig, ax = clean()
    t = fig.text(1.3, 0.5, "outside the tight box")
    t.set_in_layout(False)  # the tight bounding box does not grow to include it
    assert kinds(check_figure(fig)) == ["clipped"]
    fig2, _ = clean()
    fig2.tight_layout()
    fig2.text(0.9, 0.5, "beyond the canvas")  # saved without bbox_inches="tight"
    assert kinds(check_figure(fig2, tight=False)) == ["clipped"]
    assert check_figure(fig2, tight=True) == []  # the tight box grows to include it


def test_text_covered_by_a_legend_is_caught():
    fig, ax = clean()
    ax.text(0.02, 0.9, "under the legend", transform=ax.transAxes)
    offences = check_figure(fig)
    assert ("covered", "under the legend", "a legend") in [(o.kind, o.text, o.other)
                                                           for o in offences]
    assert set(kinds(offences)) == {"covered", "overlap"}  # and it runs into the legend's text


def test_text_under_an_inset_is_covered_and_the_inset_is_named():
    fig, ax = clean()
    ax.text(0.7, 0.1, "under the inset", transform=ax.transAxes)
    ins = ax.inset_axes([0.65, 0.05, 0.3, 0.2])
    ins.set_xticks([])
    ins.set_yticks([])
    ins.set_title("zoom", fontsize=6)
    offences = check_figure(fig)
    assert [(o.kind, o.text, o.other) for o in offences] == [
        ("covered", "under the inset", "axes 0.1: zoom")]


def test_an_axis_label_without_unit_and_an_unlabelled_axis_are_caught():
    fig, ax = clean()
    ax.set_xlabel("time")
    ax.set_ylabel("")
    offences = check_figure(fig)
    assert kinds(offences) == ["unit", "unit"]
    assert {o.text for o in offences} == {"time", "y axis without a label"}
    fig2, ax2 = clean()
    ax2.set_xlabel("time, dimensionless")  # the word, instead of [-]
    assert check_figure(fig2) == []


def test_an_axis_with_a_unit_but_no_values_is_caught_unless_a_shared_axis_shows_them():
    from matplotlib.ticker import NullFormatter

    fig, (a, b) = plt.subplots(2, 1, sharex=True)
    for ax in (a, b):
        ax.semilogx([2.0, 8.0], [1.0, 2.0])
        ax.set_ylabel("y [m]")
    b.set_xlabel("wall time [s]")
    a.tick_params(labelbottom=False)  # the upper panel's values: the lower panel's
    assert check_figure(fig) == []
    b.xaxis.set_minor_formatter(NullFormatter())  # no power of ten in 2..8: no label left
    assert [(o.kind, o.text) for o in check_figure(fig)] == [("unit", "wall time [s]")]


def test_names_on_an_axis_need_no_unit_and_hidden_tick_labels_need_no_label():
    fig, (a, b) = plt.subplots(2, 1, sharex=True)
    a.bar(["Beck", "Pflüger"], [20.05, 16.21])
    a.set_ylabel("p [-]")
    b.bar(["Beck", "Pflüger"], [10.94, 7.91])
    b.set_ylabel("p [-]")
    a.tick_params(labelbottom=False)
    assert check_figure(fig) == []


def test_two_unexplained_coloured_lines_are_caught():
    fig, ax = plt.subplots()
    ax.plot(X, X, color="C0")
    ax.plot(X, X**2, color="C3")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("y [m]")
    offences = check_figure(fig)
    assert kinds(offences) == ["unexplained", "unexplained"]
    assert {o.text for o in offences} == {"#1f77b4 -", "#d62728 -"}


def test_lines_named_by_a_text_of_their_colour_or_one_alone_are_explained():
    fig, ax = plt.subplots()
    ax.plot(X, X, color="C0")
    ax.plot(X, X**2, color="C3")
    ax.text(0.5, 0.2, "quadratic", color="C3")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("y [m]")
    assert check_figure(fig) == []  # C3 named; C0 the one curve the axis labels describe


def test_a_colour_map_needs_a_colorbar_and_a_label_a_legend():
    fig, ax = plt.subplots()
    sc = ax.scatter(X, X, c=X, cmap="viridis")
    ax.plot(X, 1 - X, color="C1", label="falling")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("y [m]")
    assert sorted((o.kind, o.text) for o in check_figure(fig)) == [
        ("unexplained", "colour map viridis"), ("unexplained", "falling")]
    fig.colorbar(sc, ax=ax, label="time t [s]")
    ax.legend()
    assert check_figure(fig) == []


def test_save_figure_writes_the_check_and_the_problems_name_the_figure(tmp_path):
    fig, ax = clean()
    ax.set_xlabel("time")
    save_figure(fig, tmp_path / "demo.png", check=tmp_path / "checks" / "demo.json")
    assert (tmp_path / "demo.png").is_file()
    saved = json.loads((tmp_path / "checks" / "demo.json").read_text())
    assert saved == offences_json("demo", [Offence("unit", "time", "x axis label without a "
                                                   "unit [..]", "axes 0: clean")])
    checks = load_figure_checks([tmp_path / "checks" / "demo.json"])
    assert figure_problems(checks) == [
        "figure check: demo: unit: 'time' / x axis label without a unit [..] (axes 0: clean)"]
    assert figure_checks_summary(checks | {"fine": []})["n_failed"] == 1
    md = figure_checks_markdown(checks | {"fine": []})
    assert "**1 of 2 figures FAIL**" in md and "| demo | unit | time |" in md
    assert "2 of 2 figures pass" in figure_checks_markdown({"a": [], "b": []})


def test_the_summary_and_the_report_show_the_figure_check(tmp_path):
    from flutterfriction.reference import write_summary
    from flutterfriction.report import build_index

    checks = {"figA": [], "figB": [Offence("overlap", "P_flu", "'P_div'", "axes 0: load")]}
    write_summary([], tmp_path / "summary.json", tmp_path / "summary.md", figure_checks=checks)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["figures"]["n_figures"] == 2 and summary["figures"]["n_failed"] == 1
    assert "| figB | overlap | P_flu | 'P_div' | axes 0: load |" in (
        tmp_path / "summary.md").read_text()
    layout = {"title": "T", "sections": [{"title": "S", "figures": {}}]}
    page = tmp_path / "index.html"
    page.write_text(build_index(layout, [], {}, figure_checks=checks))
    text = page.read_text()
    assert "<b>Figure check</b>: 1 of 2 figures pass" in text
    assert "<td>figB</td><td>overlap</td><td>P_flu</td>" in text
    assert 'href="#figure-check"' in text and 'id="figure-check"' in text


@pytest.mark.parametrize("span", [(2.5e-3, 9e-3), (1.2e-4, 8.6e-3), (0.9, 2.1), (3e-2, 0.95)])
def test_timing_axes_never_overprint_their_labels(span):
    """tidy_log_axis on a work-precision-sized panel: measured wall times anywhere within two
    decades (1.2e-4 to 8.6e-3 s overprinted with 1-2-5 labels on CI's machine) give labels the
    figure check passes, and at least two of them."""
    from flutterfriction.plotting import tidy_log_axis

    fig, ax = plt.subplots(figsize=(4.3, 4.0))
    x = np.geomspace(*span, 5)
    ax.loglog(x, x, "o-")
    tidy_log_axis(ax.xaxis, x)
    tidy_log_axis(ax.yaxis, x)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("time [s]")
    fig.canvas.draw()
    shown = [t for t in ax.xaxis.get_ticklabels() if t.get_visible() and t.get_text()
             and ax.get_xlim()[0] <= t.get_position()[0] <= ax.get_xlim()[1]]
    assert len(shown) >= 2
    assert check_figure(fig, tight=True) == []
    plt.close(fig)


@pytest.mark.parametrize("scene", ["fig18", "fig19_theory"])
def test_figures_of_your_own_pendulum_stay_legible(scene):
    """An outside audit: with your own pendulum (l1 = 0.12 m, k1 = 0.25 N m) the "your own
    pendulum (l1 = ...)" text in a title and two legend entries broke Fig. 18 (65 overlaps)
    and Fig. 19's titles overlapped: the run failed. The short name is used there and the
    values are given once, wrapped, under the figure."""
    import matplotlib.pyplot as plt

    from flutterfriction.config import load_config, scene_params
    from flutterfriction.registry import SCENES, figures
    from flutterfriction.scenes import build_scene

    params = scene_params(load_config(ROOT / "workflow" / "config.yaml"), scene)
    own = {**params, "pendulum": {**params["pendulum"], "l1": 0.12, "k1": 0.25}}
    data = build_scene(scene, own, SCENES[scene].compute)
    fig = figures()[scene][1].plot(data)
    texts = [t.get_text() for t in fig.texts]
    assert check_figure(fig) == []
    plt.close(fig)
    assert any(t.startswith("your own pendulum: l1 = 0.12 m") for t in texts)


def _same_drawing(a: np.ndarray, b: np.ndarray) -> bool:
    """Two PNGs of one layout and box: the same size, the ink's extent within a pixel, and
    the same mean within 2e-4 (savefig shifts the drawing by the box corner's fraction of a
    pixel, the PNG cut from the canvas by a whole pixel: the means differ by 2.2e-5 and
    2.7e-5 in the two figures tested here, measured)."""
    ink = [np.argwhere(im[..., :3].min(-1) < 0.5) for im in (a, b)]
    return (a.shape == b.shape and np.abs(ink[0].min(0) - ink[1].min(0)).max() <= 1
            and np.abs(ink[0].max(0) - ink[1].max(0)).max() <= 1
            and abs(float(np.mean(a[..., :3])) - float(np.mean(b[..., :3]))) < 2e-4)


@pytest.mark.parametrize("draft, dpi", [(True, 100), (False, 200)])
def test_the_check_measures_the_figure_as_its_png_is_saved(tmp_path, monkeypatch, draft, dpi):
    """The check runs at the PNG's resolution (text extents differ by resolution: at the
    figure's 150 dpi it passed three quick-preset PNGs, saved at 100 dpi, whose labels
    overlapped), and its draw lays the figure out, measures its tight box and renders the
    PNG's pixels once: a figure saved as PDF + PNG and checked is drawn twice (was 5, then 3:
    the PDF's own layout pass is skipped), as a checked PNG once (was 3). The PNG is the one
    ``bbox_inches="tight"`` gives (same size, the drawing within a pixel), with or without the
    check, and the figure keeps its own resolution."""
    from matplotlib.figure import Figure

    import flutterfriction.plotting as plotting

    seen, draws = [], []
    check = plotting.check_figure
    monkeypatch.setattr(plotting, "check_figure",
                        lambda f, **kw: seen.append(f.dpi) or check(f, **kw))
    draw = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda self, r: draws.append(1) or draw(self, r))

    def constrained() -> Figure:
        fig, axes = plt.subplots(1, 2, figsize=(5.0, 2.5), layout="constrained")
        for ax in axes:
            ax.plot(X, X**3, label="cubic")
            ax.set_xlabel(r"load $\eta = H l_1/k_2$ [-]")
            ax.set_ylabel("ratio [-]")
            ax.legend()
        fig.suptitle("a title wider than the axes below it, in two lines\nof text [-]")
        return fig

    fig = constrained()
    save_figure(fig, tmp_path / "a.pdf", tmp_path / "a.png", draft=draft,
                check=tmp_path / "a.json")
    assert seen == [dpi] and fig.dpi == 150
    assert len(draws) == 2
    draws.clear()
    save_figure(constrained(), tmp_path / "d.png", draft=draft, check=tmp_path / "d.json")
    assert len(draws) == 1
    save_figure(constrained(), tmp_path / "b.png", draft=draft)
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()
    fig = constrained()
    fig.savefig(tmp_path / "c.png", dpi=dpi, bbox_inches="tight", metadata={"Software": None})
    saved = [plt.imread(tmp_path / f"{name}.png") for name in "bc"]
    assert saved[0].shape == saved[1].shape
    assert _same_drawing(*saved)  # same layout, same box
    assert json.loads((tmp_path / "a.json").read_text())["offences"] == []


def test_a_png_reaching_beyond_its_canvas_is_saved_whole(tmp_path, monkeypatch):
    """A figure drawing beyond its canvas (a text placed outside, no layout engine) cannot be
    cut from the rendered canvas: savefig draws the larger tight box (one more draw), and the
    PNG holds the outside text as ``bbox_inches="tight"`` gives it."""
    from matplotlib.figure import Figure

    draws = []
    draw = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda self, r: draws.append(1) or draw(self, r))

    def outside() -> Figure:
        fig, ax = plt.subplots(figsize=(3.0, 2.0))
        ax.plot(X, X, label="line")
        ax.set_xlabel("x [-]")
        ax.set_ylabel("y [-]")
        ax.legend()
        fig.text(1.05, 0.5, "beyond the canvas")
        return fig

    save_figure(outside(), tmp_path / "a.png", check=tmp_path / "a.json")
    assert len(draws) == 2
    outside().savefig(tmp_path / "b.png", dpi=200, bbox_inches="tight",
                      metadata={"Software": None})
    saved = [plt.imread(tmp_path / f"{name}.png") for name in "ab"]
    assert saved[0].shape == saved[1].shape and saved[0].shape[1] > 3.5 * 200
    assert np.abs(saved[0] - saved[1]).max() < 0.05


@pytest.mark.parametrize("rc", [{"figure.constrained_layout.use": True},
                                {"figure.autolayout": True}])
def test_save_figure_under_a_users_layout_rc(tmp_path, rc):
    """An outside review: with a user's rc asking for a layout engine, savefig put "no
    engine" back by reading the rc, installed the rc's engine mid-save and failed on a colorbar
    (RuntimeError) or re-laid the figure out. Now as plain savefig(bbox_inches="tight"), and
    the figure keeps its own engine."""
    with plt.rc_context(rc):
        for layout in ("tight", "constrained"):
            def make(layout: str = layout):
                fig, axs = plt.subplots(1, 2, layout=layout)
                fig.colorbar(axs[0].imshow(np.zeros((3, 3))), ax=axs[0], label="value [-]")
                axs[1].set_ylabel("long label [m]")
                fig.suptitle("title")
                return fig

            fig = make()
            engine = type(fig.get_layout_engine())
            save_figure(fig, tmp_path / "a.pdf", tmp_path / "a.png")
            assert type(fig.get_layout_engine()) is engine
            make().savefig(tmp_path / "b.png", bbox_inches="tight", metadata={"Software": None})
            a, b = (plt.imread(tmp_path / f"{n}.png") for n in "ab")
            assert a.shape == b.shape and _same_drawing(a, b)


def test_pdf_fonts_are_embedded_without_layout_tables_and_the_default_is_put_back(
        tmp_path, monkeypatch):
    """The PDF's TrueType subsets leave out GSUB/GPOS/GDEF (no PDF reader uses them; their
    subsetting was ~30 % of a PDF's save), keep the glyphs and widths, and fontTools' own
    default is restored after the save (also when the save fails)."""
    import io
    import re
    import zlib

    from fontTools.subset import Options
    from fontTools.ttLib import TTFont

    default = list(Options._drop_tables_default)
    fig, ax = plt.subplots()
    ax.set_xlabel("load P [N]")
    ax.set_title(r"fi ffl $\alpha$ AV")  # ligature and kerning candidates
    save_figure(fig, tmp_path / "a.pdf")
    assert Options._drop_tables_default == default
    raw = (tmp_path / "a.pdf").read_bytes()
    fonts = []
    for m in re.finditer(rb"/Length1 \d+.*?stream\r?\n", raw, re.S):
        start = m.end()
        data = raw[start:raw.index(b"endstream", start)]
        fonts.append(TTFont(io.BytesIO(zlib.decompress(data))))
    assert fonts, "no embedded TrueType font found"
    for font in fonts:
        assert not {"GSUB", "GPOS", "GDEF"} & set(font.keys())
        assert {"glyf", "hmtx"} <= set(font.keys()) and len(font.getGlyphOrder()) > 1
    from matplotlib.backends import backend_pdf

    def fail(*args, **kwargs):
        raise RuntimeError("font embedding failed")

    monkeypatch.setattr(backend_pdf.PdfFile, "writeFonts", fail)
    with pytest.raises(RuntimeError, match="font embedding failed"):
        save_figure(plt.figure(), tmp_path / "b.pdf")
    assert Options._drop_tables_default == default and not (tmp_path / "b.pdf").exists()
