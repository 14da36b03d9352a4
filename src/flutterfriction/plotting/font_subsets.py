"""The TrueType subsets a PDF figure embeds (``pdf.fonttype`` 42): what they leave out, and a
cheaper way to cut them that gives the same bytes.

matplotlib subsets every font a PDF embeds from the font file, for every PDF: fontTools parses
the whole font (DejaVu Sans: ~6000 glyphs) each time, 60-95 ms a font on the slow 2-core host,
~16 % of drawing the 39 paper figures in one process (measured: 12.8 of 80 CPU-s, 164
subsets). Two levers, both applied while saving (:func:`embedded_font_subsets`):

- the subsets leave out the OpenType layout tables (:data:`UNREAD_FONT_TABLES`), which no PDF
  reader uses (was ~30 % of a paper PDF's save);
- a process that embeds a font in a second PDF (a chapter part's figure batch) cuts it once to a
  *working copy* holding the glyphs of the scripts the figures write (:data:`WORKING_RANGES`:
  Latin, Greek, punctuation, arrows, mathematical operators; ~1000 glyphs) and cuts each
  further subset from that copy, ~4.5x cheaper (measured on the 164 subsets of the paper
  figures: 15.4 -> 3.4 CPU-s). fontTools keeps the glyph order and the glyph names through
  both cuts, so the subset is the same bytes as matplotlib's own and its glyph map the same
  (all 164 compared; ``tests/test_font_subsets.py`` checks whole PDFs). A glyph outside the
  copy is cut from the font file, as matplotlib does.

Both reach into matplotlib's and fontTools' internals (matplotlib offers no option for either):
each is a no-op when the names it relies on are not there, and the PDFs are then matplotlib's.
"""

from __future__ import annotations

import inspect
import io
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

#: OpenType layout tables (ligatures, positioning): a PDF viewer draws the glyphs at the places
#: matplotlib wrote and never reads them, and matplotlib reads only the subset's advance widths
#: (``backend_pdf.embedTTFType42``); fontTools' subsetting decompiled them for every embedded
#: font, ~30 % of a paper PDF's save (14.5 -> 10.4 CPU-s over the 39 figures, measured).
UNREAD_FONT_TABLES = ("GSUB", "GPOS", "GDEF")

#: Unicode blocks whose glyphs a working copy holds (first, last code point): Basic Latin,
#: Latin-1, Greek, General Punctuation, super- and subscripts, letterlike symbols, arrows,
#: mathematical operators. 155 of the paper figures' 164 subsets lie within them (measured);
#: the others (mathtext's size variants, TeX fonts without Unicode names) go the direct way.
WORKING_RANGES = ((0x20, 0x7E), (0xA0, 0xFF), (0x370, 0x3FF), (0x2000, 0x206F),
                  (0x2070, 0x209F), (0x2100, 0x214F), (0x2190, 0x21FF), (0x2200, 0x22FF))


@contextmanager
def without_layout_tables() -> Iterator[None]:
    """While saving: the subsets leave out :data:`UNREAD_FONT_TABLES` (fontTools' list of
    tables to drop extended, and put back after; a no-op if fontTools renames it)."""
    from fontTools.subset import Options  # a dependency of matplotlib's PDF backend

    default = getattr(Options, "_drop_tables_default", None)
    if not isinstance(default, list):
        yield
        return
    Options._drop_tables_default = [*default, *UNREAD_FONT_TABLES]
    try:
        yield
    finally:
        Options._drop_tables_default = default


class _FontBytes(io.BytesIO):
    """A working copy where matplotlib's subsetting expects a font path (its face index)."""

    face_index = 0


class _WorkingCopies:
    """Per process: the PDF save that first embedded each font, and its working copy, made
    when a later save embeds it again."""

    def __init__(self) -> None:
        self.saves = 0  # PDF saves so far (from_working_copies counts them)
        self.first_save: dict[tuple, int] = {}  # the save that first embedded each font
        self.copies: dict[tuple, tuple[bytes, dict[int, int]]] = {}
        self.cut_from_copy = 0  # subsets cut from a working copy (the tests read them)
        self.outside_copy = 0  # subsets with a glyph the copy lacks, cut from the font

    def subset(self, direct: Any, backend: Any, fontfile: Any, glyphs: Any) -> Any:
        """matplotlib's ``get_glyphs_subset(fontfile, glyphs)``, cut from the working copy
        where it holds every glyph asked for."""
        from fontTools.subset import Options

        glyphs = {int(g) for g in glyphs}
        # the tables to drop are part of the key: a copy cut under other options would give
        # other subsets
        key = (str(fontfile), fontfile.face_index, tuple(Options._drop_tables_default))
        # a font's first PDF costs what it did (one PDF may subset one font several times:
        # a copy built there cost more than it saved in a one-figure job, measured)
        if self.first_save.setdefault(key, self.saves) == self.saves:
            return direct(fontfile, glyphs)
        if key not in self.copies:
            self.copies[key] = self._working_copy(direct, backend, fontfile)
        data, to_copy = self.copies[key]
        if not glyphs <= to_copy.keys():
            self.outside_copy += 1
            return direct(fontfile, glyphs)
        self.cut_from_copy += 1

        @contextmanager
        def results() -> Iterator[Any]:
            with direct(_FontBytes(data), {to_copy[g] for g in glyphs}) as cut:
                from_copy = cut.glyph_index_map
                yield backend.SubsetResults(cut.font, {
                    g: from_copy[c] for g, c in to_copy.items() if c in from_copy})

        return results()

    @staticmethod
    def _working_copy(direct: Any, backend: Any, fontfile: Any) -> tuple[bytes, dict[int, int]]:
        """The font cut to the glyphs of :data:`WORKING_RANGES` (and ``.notdef``): its bytes,
        and the map from the font's glyph indices to the copy's."""
        from fontTools.ttLib import TTFont

        with TTFont(str(fontfile), fontNumber=fontfile.face_index, lazy=True) as font:
            cmap = font.getBestCmap() or {}
            glyphs = {0} | {font.getGlyphID(cmap[u]) for first, last in WORKING_RANGES
                            for u in range(first, last + 1) if u in cmap}
        with direct(fontfile, glyphs) as cut:
            return backend.font_as_file(cut.font).getvalue(), dict(cut.glyph_index_map)


_COPIES = _WorkingCopies()


@contextmanager
def from_working_copies() -> Iterator[None]:
    """While saving: matplotlib's subsets cut from per-process working copies of the fonts
    (see the module's text); a no-op where matplotlib's subsetting is not the one this was
    measured on (``_backend_pdf_ps.get_glyphs_subset(fontfile, glyphs)`` returning a context
    manager of ``SubsetResults(font, glyph_index_map)``)."""
    from matplotlib.backends import _backend_pdf_ps as backend

    direct = getattr(backend, "get_glyphs_subset", None)
    try:
        known = (list(inspect.signature(direct).parameters) == ["fontfile", "glyphs"]
                 and hasattr(backend, "SubsetResults") and hasattr(backend, "font_as_file"))
    except (TypeError, ValueError):
        known = False
    if not known:
        yield
        return

    def get_glyphs_subset(fontfile: Any, glyphs: Any) -> Any:
        return _COPIES.subset(direct, backend, fontfile, glyphs)

    _COPIES.saves += 1
    backend.get_glyphs_subset = get_glyphs_subset
    try:
        yield
    finally:
        backend.get_glyphs_subset = direct


@contextmanager
def embedded_font_subsets() -> Iterator[None]:
    """While saving PDFs: both levers of this module."""
    with without_layout_tables(), from_working_copies():
        yield
