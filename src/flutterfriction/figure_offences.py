"""The figure check's results as data (no matplotlib): what the plot jobs write for each figure
(``results/checks/figures/<figure>.json``, by :mod:`flutterfriction.figure_check`), and what the
check summary and the report make of them."""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

#: The kinds of offence (see :mod:`flutterfriction.figure_check` for the rules).
KINDS = ("overlap", "clipped", "covered", "small", "unit", "unexplained")

#: What a figure that passes satisfies, in one line (the summary and the report say it).
RULES = ("no two texts overlap, no text is clipped or covered by a legend or another axes, "
         "every text is at least 10 px tall with the figure 1200 px wide (a laptop's report "
         "column), every axis that shows values has a label with a unit [..], every colour "
         "and line style is explained (not checked: text over drawn lines or arrows, text "
         "running past its axes' frame inside the figure, legends over data; those are looked "
         "at by eye)")


@dataclass(frozen=True)
class Offence:
    """One problem of a figure: its kind (:data:`KINDS`), the text (or artist) at fault, what
    it collides with, and the axes it belongs to (its number and title or labels)."""

    kind: str
    text: str
    other: str = ""
    axes: str = ""

    def __str__(self) -> str:
        where = f" ({self.axes})" if self.axes else ""
        return f"{self.kind}: {self.text!r}" + (f" / {self.other}" if self.other else "") + where


def offences_json(figure: str, offences: Iterable[Offence]) -> dict[str, Any]:
    """The file written for one figure (no timings: reruns give identical files)."""
    return {"figure": figure, "offences": [asdict(o) for o in offences]}


def load_figure_checks(paths: Iterable[str | Path]) -> dict[str, list[Offence]]:
    """``{figure: its offences}`` from the files :func:`offences_json` wrote, by name."""
    out = {}
    for p in paths:
        with open(p, encoding="utf-8") as fh:
            d = json.load(fh)
        out[d["figure"]] = [Offence(**o) for o in d["offences"]]
    return dict(sorted(out.items()))


def figure_problems(checks: Mapping[str, list[Offence]]) -> list[str]:
    """One line per offence, naming the figure: what fails the run."""
    return [f"figure check: {figure}: {o}" for figure, offences in checks.items()
            for o in offences]


def figure_checks_summary(checks: Mapping[str, list[Offence]]) -> dict[str, Any]:
    """The figure check in ``results/checks/summary.json``."""
    return {"n_figures": len(checks), "n_failed": sum(bool(o) for o in checks.values()),
            "rules": RULES,
            "offences": {f: [asdict(o) for o in offences] for f, offences in checks.items()
                         if offences}}


def figure_checks_markdown(checks: Mapping[str, list[Offence]]) -> str:
    """The figure check's section of ``results/checks/summary.md``."""
    bad = {f: o for f, o in checks.items() if o}
    lines = ["## Figure check", "",
             (f"{len(checks)} of {len(checks)} figures pass" if not bad else
              f"**{len(bad)} of {len(checks)} figures FAIL**") + f": {RULES}.", ""]
    if bad:
        lines += ["| figure | kind | text | with | axes |", "|---|---|---|---|---|"]
        lines += [f"| {f} | {o.kind} | {_cell(o.text)} | {_cell(o.other)} | {_cell(o.axes)} |"
                  for f, offences in bad.items() for o in offences]
        lines.append("")
    return "\n".join(lines)


def _cell(s: str) -> str:
    return s.replace("|", "\\|").replace("\n", " ")
