"""Saving without the repeated work (math parsed once per process, no PDF layout pass) gives
the same files, byte for byte."""

from __future__ import annotations

from contextlib import contextmanager

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.mathtext import MathTextParser

import flutterfriction.plotting as plotting
import flutterfriction.plotting.mathtext_parses as mp
from flutterfriction.plotting import _save_pdf, save_figure


def _figure(title: str):
    """Math text in labels, ticks (log axis), a legend placed at draw time, an annotation, an
    inset and a colour bar: what a layout pass could move."""
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(6, 2.5), layout="constrained")
    x = np.geomspace(1e-3, 1e2, 30)
    ax.loglog(x, x**1.5, label=r"$\omega^2 \propto p^{3/2}$")
    ax.loglog(x, x, "--", label=r"$\tilde p$")
    ax.legend(loc="best")
    ax.set_xlabel(r"load $P\,l^2/B$ [-]")
    ax.set_ylabel(r"$\left(\frac{\alpha_1}{\beta}\right)$ [rad]")
    ax.annotate(r"$p_{\mathrm{flu}} = 20.05$", (1.0, 1.0), (0.05, 10.0),
                arrowprops={"arrowstyle": "->"})
    inset = ax.inset_axes([0.6, 0.1, 0.35, 0.3])
    inset.plot([0, 1], [1, 0])
    m = bx.pcolormesh(np.arange(12.0).reshape(3, 4))
    fig.colorbar(m, ax=bx, label=r"$\sigma$ [1/s]")
    bx.set_title(title)
    return fig


def _saved(tmp_path, tag: str, draft: bool = False) -> list[bytes]:
    out = []
    for k, title in enumerate([r"Fig. A: $\eta \to 0$", r"Fig. B: $\gamma = 10^{-3}$"]):
        paths = [tmp_path / f"{tag}{k}.{ext}" for ext in ("pdf", "png")]
        save_figure(_figure(title), *paths, draft=draft, check=tmp_path / f"{tag}{k}.json")
        out += [p.read_bytes() for p in paths]
    return out


# the paper figures (PDF and PNG, ~6 s here) with the slow tests; the quick ones stay fast
@pytest.mark.parametrize("draft", [pytest.param(False, marks=pytest.mark.slow), True])
def test_figures_are_the_same_bytes_with_shared_parses(tmp_path, monkeypatch, draft):
    @contextmanager
    def per_renderer():
        yield

    monkeypatch.setattr(mp, "_PARSES", type(mp._PARSES)())
    before = dict(mp.counts)
    shared = _saved(tmp_path, "shared", draft)
    # the second figure's tick labels and the PDF's two renderers found their parses (else
    # this test would compare matplotlib with itself)
    assert mp.counts["reused"] - before["reused"] >= 10
    monkeypatch.setattr(plotting, "shared_mathtext_parses", per_renderer)
    assert _saved(tmp_path, "own", draft) == shared


def test_a_setting_outside_matplotlibs_key_is_in_the_key(monkeypatch):
    # mathtext.default is read by the parser, not by matplotlib's cache key: a parse under
    # another value is parsed again, and is the one matplotlib makes
    monkeypatch.setattr(mp, "_PARSES", type(mp._PARSES)())

    def glyphs(parse) -> list:  # (font file, size, glyph, x, y) of each glyph
        return [(g[0].fname, *g[1:]) for g in parse.glyphs]

    def shared(default: str) -> list:
        with plt.rc_context({"mathtext.default": default}), mp.shared_mathtext_parses():
            return glyphs(MathTextParser("path").parse("$x + y$", 72))

    italic, roman = shared("it"), shared("rm")
    with plt.rc_context({"mathtext.default": "rm"}):
        direct = glyphs(MathTextParser("path").parse("$x + y$", 72))
    assert roman == direct and roman != italic


def test_the_parser_is_put_back_and_another_interface_left_alone(monkeypatch):
    own = MathTextParser.__dict__["_parse_cached"]
    with mp.shared_mathtext_parses():
        assert MathTextParser.__dict__["_parse_cached"] is not own
    assert MathTextParser.__dict__["_parse_cached"] is own

    def _parse_cached(self, s, dpi, prop, antialiased, load_glyph_flags):  # no cache inside
        raise AssertionError("not called here")

    monkeypatch.setattr(MathTextParser, "_parse_cached", _parse_cached)
    with mp.shared_mathtext_parses():
        assert MathTextParser.__dict__["_parse_cached"] is _parse_cached


def test_the_pdf_without_its_layout_pass_is_savefigs_own(tmp_path):
    fig = _figure("Fig. C")
    fig.draw_without_rendering()  # laid out, as save_figure has it
    fig.set_layout_engine(None)
    _save_pdf(fig, tmp_path / "ours.pdf", {"CreationDate": None})
    fig.savefig(tmp_path / "savefig.pdf", format="pdf", metadata={"CreationDate": None},
                bbox_inches="tight")
    assert (tmp_path / "ours.pdf").read_bytes() == (tmp_path / "savefig.pdf").read_bytes()
    assert "draw" not in vars(fig)
    plt.close(fig)


def test_a_savefig_without_a_layout_pass_draws_again(tmp_path):
    fig = _figure("Fig. D")
    calls = []

    def savefig(path, **kwargs):  # a matplotlib whose savefig draws once: the drawing
        calls.append("draw" in vars(fig))
        fig.draw(None)

    fig.savefig = savefig
    drawn = []
    type(fig).draw, own = (lambda self, r: drawn.append(r)), type(fig).draw
    try:
        _save_pdf(fig, tmp_path / "x.pdf", {})
    finally:
        type(fig).draw = own
    # the first save's only draw was skipped: saved again, as savefig saves
    assert calls == [True, False] and len(drawn) == 1
    plt.close(fig)
