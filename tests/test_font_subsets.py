"""The embedded font subsets cut from working copies are matplotlib's own, byte for byte."""

from __future__ import annotations

from contextlib import contextmanager

import matplotlib.pyplot as plt
import pytest

import flutterfriction.plotting.font_subsets as fs
from flutterfriction.plotting import save_figure


def _figure(title: str):
    """Text in regular, bold, oblique and mathtext (Greek, operators, size variants)."""
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel(r"load $P\,l^2/B$ [–], $\omega^2 \leq \sqrt{\gamma}$")
    ax.set_ylabel(r"$\left(\frac{\alpha_1}{\beta}\right)$ [rad]")
    ax.set_title(title, fontweight="bold")
    ax.text(0.1, 0.8, "Stabilität ≈ 4.8 N → ∞", style="italic")
    return fig


def _pdfs(tmp_path, tag: str) -> list[bytes]:
    out = []
    for k, title in enumerate(["Fig. A: flutter", "Fig. B: divergence ΔΩ ♔"]):
        path = tmp_path / f"{tag}{k}.pdf"
        save_figure(_figure(title), path)
        out.append(path.read_bytes())
    return out


def test_pdfs_are_the_same_bytes_with_the_working_copies(tmp_path, monkeypatch):
    @contextmanager
    def direct():
        yield

    fresh = fs._WorkingCopies()
    monkeypatch.setattr(fs, "_COPIES", fresh)
    with_copies = _pdfs(tmp_path, "copies")
    # the second PDF embeds the same fonts again: cut from the copies (else this test would
    # compare matplotlib with itself), but for DejaVu Sans, which draws the king (U+2654,
    # outside WORKING_RANGES) there: cut from the font file
    assert fresh.cut_from_copy >= 2 and fresh.outside_copy >= 1
    monkeypatch.setattr(fs, "from_working_copies", direct)
    assert _pdfs(tmp_path, "direct") == with_copies


def test_another_subsetting_interface_is_left_alone(monkeypatch):
    from matplotlib.backends import _backend_pdf_ps as backend

    def get_glyphs_subset(fontfile, characters):  # the interface of older matplotlib
        raise AssertionError("not called here")

    monkeypatch.setattr(backend, "get_glyphs_subset", get_glyphs_subset)
    with fs.from_working_copies():
        assert backend.get_glyphs_subset is get_glyphs_subset


@pytest.mark.parametrize("name", ["_drop_tables_default"])
def test_the_layout_tables_are_dropped_only_while_saving(name):
    from fontTools.subset import Options

    before = list(getattr(Options, name))
    with fs.without_layout_tables():
        assert set(fs.UNREAD_FONT_TABLES) <= set(getattr(Options, name))
    assert getattr(Options, name) == before
