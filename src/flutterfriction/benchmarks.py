"""The work-precision scene: accuracy against cost of every solver family, and the wall time
and memory of every workflow job.

The studies themselves are scenes (``pendulum_work_precision``, ``rod_fe_convergence``,
``beck_work_precision``, ``beck_limit_cycle``); this module only gathers their runs into one
table of ``(family, method, setting, error, wall_s)`` rows, and reads Snakemake's
``benchmark:`` files.
"""

from __future__ import annotations

import csv
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from flutterfriction.io import markdown_table, merge_timings, read_json

#: The four studies of :func:`gather_runs`, in its order: the workflow's input name of each
#: and the scene whose data (and ``<name>_timings``) it reads.
STUDIES = {"pendulum": "pendulum_work_precision", "rod_fe": "rod_fe_convergence",
           "rod_integrators": "beck_work_precision", "rod_cycle": "beck_limit_cycle"}


#: What each family's ``setting`` is, i.e. what varies along each line of the figure (a line
#: of the damped flutter load is not a work-precision curve: it crosses problems of smaller
#: and smaller viscosity, where the eigenvalue method loses digits and Routh does not).
FAMILY_SETTINGS = {
    "pendulum flutter load": "one run per method",
    "pendulum damped flutter load": "the hinge viscosity c (1e-2 to 1e-10 N m s; not a cost)",
    "pendulum limit cycle (one period)": "the integrator's rtol",
    "rod flutter load: finite elements vs exact": "the number of elements",
    "rod limit cycle (one period)": "rtol (adaptive) or the step (generalized-α)",
    "rod limit cycle: mesh (vs finest)": "the number of elements (chained)",
}


#: Families whose points are not joined: along them nothing is a cost (the lines zigzagged in
#: wall time; a fresh-eyes review).
UNJOINED = {"pendulum flutter load", "pendulum damped flutter load"}
#: Families whose points are each named by their setting: few, and one line only (the FE
#: family's three lines of four points in the quick preset overlapped).
NAMED_POINTS = {"rod limit cycle: mesh (vs finest)": "{:g} el."}
#: What a family's relative error measures, where it is not one number (the y label).
FAMILY_ERRORS = {
    "rod limit cycle (one period)": "larger relative error [-]\n(period, tip amplitude)",
    "rod limit cycle: mesh (vs finest)": "largest relative error [-]\n(tip amplitude, period, "
                                         "rotation)",
}


def _row(family: str, method: str, setting: Any, error: float | None, wall_s: float | None
         ) -> dict[str, Any]:
    return {"family": family, "method": method, "setting": setting,
            "error": None if error is None else float(error),
            "wall_s": None if wall_s is None else float(wall_s)}


def gather_runs(pendulum: Mapping[str, Any], rod_fe: Mapping[str, Any],
                rod_cycle_integrators: Mapping[str, Any], rod_cycle: Mapping[str, Any]
                ) -> list[dict[str, Any]]:
    """One list of runs from the four studies' data (with their timings merged back).

    Errors are relative: against 50-digit mpmath or exact closed forms (pendulum loads), the
    exact characteristic equation (rod FE), a tight reference integration (one period on a
    cycle), and the finest mesh (rod cycle, mesh continuation)."""
    rows = [_row(r["family"], r["method"], r["setting"], r["error"], r["wall_s"])
            for r in pendulum["runs"]]
    for name, case in rod_fe["cases"].items():
        for n, e, t in zip(rod_fe["elements"], case["rel_error_p"], case["time_s"], strict=True):
            rows.append(_row("rod flutter load: finite elements vs exact", f"FE, {name}", n,
                             e, t))
    for r in rod_cycle_integrators["runs"]:
        err = None if r["failed"] else max(r["period_error"], r["amplitude_error"])
        rows.append(_row("rod limit cycle (one period)", f"{r['method']}, {r['mesh']} el.",
                         r["setting"], err, r["wall_s"]))
    cycles, meshes = rod_cycle["cycles"], rod_cycle["meshes"]
    finest = cycles[str(meshes[-1])]
    wall = 0.0
    for n in meshes[:-1]:
        c = cycles[str(n)]
        wall += c["wall_s"]  # the chain: each mesh starts from the previous one
        err = max(abs(c[k] - finest[k]) / abs(finest[k])
                  for k in ("tip_amplitude_m", "period_s", "tip_rotation_amplitude_rad"))
        rows.append(_row("rod limit cycle: mesh (vs finest)", "mesh continuation", n, err, wall))
    return rows


def read_studies(files: Mapping[str, str | Path]) -> list[dict[str, Any]]:
    """The four studies of :func:`gather_runs` (:data:`STUDIES`) read from ``files``, a
    mapping of each name and ``<name>_timings`` to its JSON file, with the timings merged."""
    return [merge_timings(read_json(files[name]), read_json(files[f"{name}_timings"]) or None)
            for name in STUDIES]


def read_benchmarks(paths: list[str | Path]) -> list[dict[str, Any]]:
    """Wall time [s], peak resident memory [MB] and CPU time [s] of each job, from Snakemake's
    ``benchmark:`` files (the last line of each, the latest run)."""
    jobs = []
    for path in map(Path, paths):
        with open(path, encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh, delimiter="\t"))
        if not rows:
            continue
        last = rows[-1]

        def num(key, last=last):
            try:
                return float(last[key])
            except (KeyError, ValueError):
                return None

        jobs.append({"job": path.name.removesuffix(".tsv"), "wall_s": num("s"),
                     "max_rss_mb": num("max_rss"), "cpu_s": num("cpu_time")})
    return sorted(jobs, key=lambda j: -(j["wall_s"] or 0.0))


def _fmt(x: Any, spec: str) -> str:
    return "" if x is None else format(x, spec)


def work_precision_markdown(runs: list[dict[str, Any]], jobs: list[dict[str, Any]]) -> str:
    """The two tables: every run (family, method, setting, error, wall time), and every job's
    wall time and peak memory."""
    lines = ["# Work-precision and timings", "",
             "Accuracy against cost of every solver family (errors relative; times are medians "
             "or single runs on a shared 2-core machine, so compare ratios rather than absolute "
             "values), then the wall time and peak memory of every workflow job.", "",
             "## Solvers", ""]
    lines += markdown_table(
        ["family", "method", "setting", "relative error", "wall time [s]"],
        [[r["family"], r["method"], "" if r["setting"] is None else f"{r['setting']:g}",
          _fmt(r["error"], ".2e") or "failed", _fmt(r["wall_s"], ".4g")] for r in runs])
    total = sum(j["wall_s"] or 0.0 for j in jobs)
    lines += ["", "## Workflow jobs (Snakemake `benchmark:`)", "",
              f"{len(jobs)} jobs, {total:.0f} s of job wall time in all (run on 2 cores).", ""]
    lines += markdown_table(
        ["job", "wall time [s]", "peak RSS [MB]", "CPU time [s]"],
        [[j["job"], _fmt(j["wall_s"], ".2f"), _fmt(j["max_rss_mb"], ".0f"),
          _fmt(j["cpu_s"], ".2f")] for j in jobs])
    return "\n".join(lines) + "\n"


def best_per_method(runs: list[dict[str, Any]]) -> dict[str, dict[str, float]]:
    """``{family: {method: smallest error reached}}``: the summary of the runs."""
    out: dict[str, dict[str, float]] = {}
    for r in runs:
        if r["error"] is None:
            continue
        fam = out.setdefault(r["family"], {})
        fam[r["method"]] = float(np.minimum(fam.get(r["method"], np.inf), r["error"]))
    return out


# --------------------------------------------------------------------------- README timing
TIMING_START = "<!-- timing table: generated by .ci/timing_table.py; do not edit by hand -->"
TIMING_END = "<!-- end of timing table -->"


def timing_markdown(after: list[dict[str, Any]], before: list[dict[str, Any]] | None = None,
                    totals: Mapping[str, Mapping[str, float | None]] | None = None,
                    n_slowest: int = 10,
                    baseline: str = "previous main") -> str:
    """The README's timing section from Snakemake's ``benchmark:`` files.

    Parameters
    ----------
    after, before
        :func:`read_benchmarks` of this checkout's run and of the previous main's run (same
        machine, same hour). A job is matched by name; jobs that exist on one side only (the
        batches of cheap scenes replaced a job per scene) show "-" on the other.
    totals
        ``{what: {"before": s, "after": s}}``: whole-command wall times measured around the
        runs (paper from clean, quick from clean, no-op, tests), medians; optionally
        ``"paired"``, the median of the run-by-run ratios after/before (the host's speed
        drifts between runs: the ratio the pairs measure, shown beside the medians' ratio).
    baseline
        What ``before`` is, as the table's headers name it (the previous main, or the commit
        a target is measured against, e.g. "7ecfb71").
    """
    lines: list[str] = []
    if totals:
        lines += markdown_table(
            ["command (wall time; the median where several runs)", f"{baseline} [s]",
             "this main [s]", "ratio"],
            [[what, _seconds(t.get("before")), _seconds(t.get("after")),
              _speedup(t.get("before"), t.get("after"))
              + (f" ({_speedup(1.0, t['paired'])} by the paired ratios)"
                 if t.get("paired") else "")]
             for what, t in totals.items()])
        lines.append("")
    by_name = {j["job"]: j for j in before or []}

    def total(jobs, key):
        return sum(j[key] or 0.0 for j in jobs)

    lines.append(f"Jobs with a `benchmark:` file: {len(after)} ({baseline}: "
                 f"{len(before or [])}); CPU time of those jobs "
                 f"{total(after, 'cpu_s'):.0f} s ({baseline}: "
                 f"{total(before or [], 'cpu_s'):.0f} s). The slowest {n_slowest}:")
    lines.append("")
    rows = []
    for j in sorted(after, key=lambda j: -(j["wall_s"] or 0.0))[:n_slowest]:
        b = by_name.get(j["job"], {})
        rows.append([j["job"], _fmt(j["wall_s"], ".1f"), _fmt(j["cpu_s"], ".1f"),
                     _fmt(j["max_rss_mb"], ".0f"), _fmt(b.get("wall_s"), ".1f") or "-",
                     _fmt(b.get("cpu_s"), ".1f") or "-"])
    lines += markdown_table(["job", "wall [s]", "CPU [s]", "peak RSS [MB]",
                             f"{baseline} wall [s]", f"{baseline} CPU [s]"], rows)
    return "\n".join(lines) + "\n"


def _seconds(x: float | None) -> str:
    """A whole command's seconds: tenths below 10 s (a no-op rerun), whole seconds above."""
    return "" if x is None else format(x, ".1f" if x < 10 else ".0f")


def _speedup(before: float | None, after: float | None) -> str:
    if not before or not after:
        return ""
    r = before / after
    return f"{r:.2f}x faster" if r >= 1 else f"{1 / r:.2f}x slower"


def replace_timing_block(readme: str, table: str) -> str:
    """``readme`` with the text between the timing markers replaced by ``table``."""
    if TIMING_START not in readme or TIMING_END not in readme:
        raise ValueError("README has no timing markers")
    head, rest = readme.split(TIMING_START, 1)
    _, tail = rest.split(TIMING_END, 1)
    return f"{head}{TIMING_START}\n{table}{TIMING_END}{tail}"
