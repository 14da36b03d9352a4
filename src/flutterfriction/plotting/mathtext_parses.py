"""One parse of each mathtext string per process, shared by every renderer that draws it.

matplotlib parses a math string (``$10^{-3}$``, ``$\\tilde p$``) with pyparsing, ~10 ms a
string on the slow 2-core host, and caches the result per *parser*, that is per renderer, 50
strings deep. Saving a figure makes several renderers (the check's Agg canvas, the PDF's
measuring renderer and its drawing one), and a figure batch one set per figure, so the same
strings were parsed again and again: 1131 parses of ~520 distinct keys while drawing the 39
paper figures in one process (11.9 of ~74 CPU-s, measured).

While a figure is saved (:func:`shared_mathtext_parses`), every parser looks the parse up in
one process-wide cache keyed by what the parse depends on: matplotlib's own key (string, dpi,
font properties, antialiasing, glyph loading flags), the parser's output type (vector or
raster) and the ``mathtext.*``, ``font.*`` and ``text.*`` settings at the save (the fontset
reads some of them when it is made, outside matplotlib's key). The parse is a pure function of
that key, so the figures are the same bytes (all 39 paper figures' PDF and PNG compared;
``tests/test_mathtext_parses.py`` compares whole files).

It reaches into matplotlib's internals (``MathTextParser._parse_cached``; matplotlib offers no
option): where those names are not there, it is a no-op and matplotlib parses as it does.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

#: Most parses held (least recently used dropped first): a figure batch's distinct strings are
#: ~300 (measured: 522 for all 39 paper figures in one process), each a few kB.
MAX_PARSES = 2048

#: The settings a parse can depend on beyond matplotlib's key (by prefix).
_SETTINGS = ("mathtext.", "font.", "text.")

_PARSES: OrderedDict[tuple, Any] = OrderedDict()
#: Parses made and parses reused, this process (the tests read them).
counts = {"parsed": 0, "reused": 0}


def _settings_key() -> tuple:
    from matplotlib import rcParams

    return tuple((k, repr(v)) for k, v in sorted(rcParams.items()) if k.startswith(_SETTINGS))


@contextmanager
def shared_mathtext_parses() -> Iterator[None]:
    """While saving: every renderer's math parses from the process-wide cache (see the
    module); matplotlib's own per-parser cache is put back after."""
    from matplotlib.mathtext import MathTextParser

    cached = MathTextParser.__dict__.get("_parse_cached")
    parse = getattr(cached, "__wrapped__", None)
    if parse is None:
        yield
        return
    settings = _settings_key()

    def shared(self: Any, *key: Any) -> Any:
        output = getattr(self, "_output_type", None)
        if output is None:  # no output type to key by: matplotlib's own cache
            return cached(self, *key)
        full = (output, settings, *key)
        try:
            result = _PARSES[full]
        except KeyError:
            result = _PARSES[full] = parse(self, *key)
            counts["parsed"] += 1
            if len(_PARSES) > MAX_PARSES:
                _PARSES.popitem(last=False)
        else:
            _PARSES.move_to_end(full)
            counts["reused"] += 1
        return result

    MathTextParser._parse_cached = shared
    try:
        yield
    finally:
        MathTextParser._parse_cached = cached
