"""The work-precision gathering: runs from every study, and Snakemake's benchmark files."""

import json
import math

import pytest

from flutterfriction.benchmarks import (
    STUDIES,
    best_per_method,
    gather_runs,
    read_benchmarks,
    read_studies,
    work_precision_markdown,
)
from flutterfriction.errors import ParameterError


def _studies():
    pendulum = {"runs": [{"family": "pendulum flutter load", "method": "closed form",
                          "setting": None, "error": 1e-16, "wall_s": 1e-5}]}
    rod_fe = {"elements": [4, 8], "cases": {"beck": {"rel_error_p": [1e-5, 6e-7],
                                                     "time_s": [0.01, 0.02]}}}
    integrators = {"runs": [
        {"mesh": 4, "method": "LSODA", "setting": 1e-7, "wall_s": 0.4, "failed": False,
         "period_error": 2e-8, "amplitude_error": 5e-8},
        {"mesh": 4, "method": "generalized-alpha", "setting": 1e-3, "wall_s": 0.1,
         "failed": True, "period_error": None, "amplitude_error": None}]}
    cycle = {"meshes": [4, 8, 16], "cycles": {
        "4": {"wall_s": 19.0, "tip_amplitude_m": 0.2503, "period_s": 0.1362,
              "tip_rotation_amplitude_rad": 1.4204},
        "8": {"wall_s": 12.0, "tip_amplitude_m": 0.2502, "period_s": 0.1363,
              "tip_rotation_amplitude_rad": 1.4194},
        "16": {"wall_s": 10.0, "tip_amplitude_m": 0.2500, "period_s": 0.1363,
               "tip_rotation_amplitude_rad": 1.4192}}}
    return pendulum, rod_fe, integrators, cycle


def test_every_study_contributes_runs():
    runs = gather_runs(*_studies())
    families = {r["family"] for r in runs}
    assert families == {"pendulum flutter load", "rod flutter load: finite elements vs exact",
                        "rod limit cycle (one period)", "rod limit cycle: mesh (vs finest)"}
    lsoda = next(r for r in runs if r["method"] == "LSODA, 4 el.")
    assert lsoda["error"] == 5e-8  # the larger of period and amplitude errors
    failed = next(r for r in runs if r["method"].startswith("generalized-alpha"))
    assert failed["error"] is None
    mesh = [r for r in runs if r["family"].startswith("rod limit cycle: mesh")]
    # the mesh chain's cost accumulates; the error is against the finest mesh
    assert [r["wall_s"] for r in mesh] == [19.0, 31.0]
    assert abs(mesh[0]["error"] - 0.0012) < 1e-12
    best = best_per_method(runs)
    assert best["rod flutter load: finite elements vs exact"]["FE, beck"] == 6e-7
    assert "| failed |" in work_precision_markdown(runs, [])


def test_every_family_says_what_varies_along_its_lines():
    """The figure titles each panel with what its lines sweep (a line of the damped flutter
    load crosses viscosities, not costs): every family the scenes produce has its entry."""
    from flutterfriction.benchmarks import FAMILY_SETTINGS
    from flutterfriction.scenes import ziegler_nonlinear

    source = open(ziegler_nonlinear.__file__, encoding="utf-8").read()
    pendulum = {f for f in FAMILY_SETTINGS if f.startswith("pendulum")}
    assert all(f'"family": "{f}"' in source for f in pendulum)
    assert {r["family"] for r in gather_runs(*_studies())} <= set(FAMILY_SETTINGS)


def test_benchmark_files_are_read_latest_line_and_sorted(tmp_path):
    header = "s\th:m:s\tmax_rss\tmax_vms\tmax_uss\tmax_pss\tio_in\tio_out\tmean_load\tcpu_time\n"
    (tmp_path / "a.solve.tsv").write_text(header + "9.0\t0:00:09\t100\t1\t1\t1\t0\t0\t50\t4.5\n"
                                          + "2.0\t0:00:02\t120.5\t1\t1\t1\t0\t0\t50\t1.5\n")
    (tmp_path / "b.tsv").write_text(header + "3.0\t0:00:03\t-\t1\t1\t1\t0\t0\t50\t2.0\n")
    jobs = read_benchmarks(sorted(tmp_path.glob("*.tsv")))
    assert [j["job"] for j in jobs] == ["b", "a.solve"]
    assert jobs[1] == {"job": "a.solve", "wall_s": 2.0, "max_rss_mb": 120.5, "cpu_s": 1.5}
    assert jobs[0]["max_rss_mb"] is None  # '-' where the platform does not measure it
    md = work_precision_markdown([], jobs)
    assert "2 jobs, 5 s of job wall time" in md


def test_the_readme_timing_table_is_generated_from_benchmark_files(tmp_path):
    from flutterfriction.benchmarks import (
        TIMING_END,
        TIMING_START,
        read_benchmarks,
        replace_timing_block,
        timing_markdown,
    )

    header = "s\th:m:s\tmax_rss\tmax_vms\tmax_uss\tmax_pss\tio_in\tio_out\tmean_load\tcpu_time\n"
    for folder, rows in (("after", {"solve_ziegler": (3.0, 2.5), "beck_hopf.solve": (40.0, 39.0)}),
                         ("before", {"eq25.solve": (1.5, 1.2), "beck_hopf.solve": (90.0, 88.0)})):
        (tmp_path / folder).mkdir()
        for name, (wall, cpu) in rows.items():
            (tmp_path / folder / f"{name}.tsv").write_text(
                header + f"{wall}\t0:00:01\t100\t0\t0\t0\t0\t0\t0\t{cpu}\n")
    after = read_benchmarks(sorted((tmp_path / "after").glob("*.tsv")))
    before = read_benchmarks(sorted((tmp_path / "before").glob("*.tsv")))
    table = timing_markdown(after, before, {"paper from clean": {"before": 280.0, "after": 100.0}})
    assert "| paper from clean | 280 | 100 | 2.80x faster |" in table
    assert "| beck_hopf.solve | 40.0 | 39.0 | 100 | 90.0 | 88.0 |" in table
    assert "| solve_ziegler | 3.0 | 2.5 | 100 | - | - |" in table  # a batch: new job
    assert "CPU time of those jobs 42 s (previous main: 89 s)" in table
    slower = timing_markdown(after, before, {"x": {"before": 100.0, "after": 125.0}})
    assert "| x | 100 | 125 | 1.25x slower |" in slower
    # a no-op rerun in tenths; the paired ratios' median beside the medians' ratio
    noop = timing_markdown(after, before, {"no-op": {"before": 3.652, "after": 3.6,
                                                     "paired": 0.9846}})
    assert "| no-op | 3.7 | 3.6 | 1.01x faster (1.02x faster by the paired ratios) |" in noop
    readme = f"intro\n{TIMING_START}\nold\n{TIMING_END}\nrest\n"
    expected = f"intro\n{TIMING_START}\n{table}{TIMING_END}\nrest\n"
    assert replace_timing_block(readme, table) == expected


def test_median_wall_time_repeats_short_runs_only(monkeypatch):
    """Short runs are repeated `repeats` times (their median tames timer noise); once the runs
    took TIMED_ENOUGH_S together, no more (a long run is timed once); the value is fun's."""
    import flutterfriction.scenes.common as common

    calls = []

    def fun():
        calls.append(1)
        return 42.0

    monkeypatch.setattr(common, "TIMED_ENOUGH_S", math.inf)  # every run is "short"
    value, t = common.median_wall_time(fun, 3)
    assert (value, len(calls)) == (42.0, 3) and t >= 0
    calls.clear()
    monkeypatch.setattr(common, "TIMED_ENOUGH_S", 0.0)  # every run is "long"
    value, t = common.median_wall_time(fun, 3)
    assert (value, len(calls)) == (42.0, 1) and t >= 0
    with pytest.raises(ParameterError, match="repeats"):
        common.median_wall_time(fun, 0)


def test_read_studies_merges_each_study_with_its_timings(tmp_path):
    """The two work-precision jobs read the four studies by one function: each data file with
    its timings merged back, in gather_runs' order."""
    files = {}
    for k, name in enumerate(STUDIES):
        files[name] = tmp_path / f"{name}.json"
        files[name].write_text(json.dumps({"runs": [{"error": k}]}))
        files[f"{name}_timings"] = tmp_path / f"{name}.timings.json"
        files[f"{name}_timings"].write_text(json.dumps({"runs": [{"wall_s": 0.5 + k}]}))
    assert read_studies(files) == [{"runs": [{"error": k, "wall_s": 0.5 + k}]}
                                   for k in range(4)]


def test_timing_table_names_its_baseline():
    """The table says what it was measured against (the issue's 7ecfb71, not always the
    previous main)."""
    from flutterfriction.benchmarks import timing_markdown

    job = {"job": "solve_rods", "wall_s": 2.0, "cpu_s": 1.5, "max_rss_mb": 100.0}
    table = timing_markdown([job], [{**job, "wall_s": 4.0}],
                            {"paper": {"before": 300.0, "after": 150.0}}, baseline="7ecfb71")
    assert "| 7ecfb71 [s] |" in table and "7ecfb71 wall [s]" in table
    assert "previous main" not in table and "2.00x faster" in table
