"""Compare every scene with workflow/reference.yaml; write the summary and the report, both
showing any failure (the `check` rule then fails the run: Snakemake would delete the outputs
of a failing job, and a reader needs the report most when something failed)."""

import sys
from pathlib import Path

from flutterfriction.figure_offences import figure_problems, load_figure_checks
from flutterfriction.io import log_job_output, read_json, write_json, write_text
from flutterfriction.reference import (
    failed,
    load_parameters,
    load_reference,
    load_scene_data,
    run_check,
    scene_parameter_changes,
    write_summary,
)
from flutterfriction.report import (
    broken_links,
    build_index,
    coverage_problems,
    layout_figures,
    load_coverage,
    load_layout,
    provenance,
    row_scenes,
)

log_job_output(snakemake.log[0])  # this job's output goes to its log file
# A report being rebuilt invalidates the last verdict: were this job to fail, the old
# passed.txt must not go on saying that everything passes (an outside audit saw it do so).
Path(snakemake.params.passed).unlink(missing_ok=True)

reference = load_reference(snakemake.input.reference)
data = load_scene_data(snakemake.input.data)
recorded = load_parameters(snakemake.input.reference_parameters)
rows = run_check(reference, data, snakemake.params.fidelity, recorded)
figure_checks = load_figure_checks(snakemake.input.figure_checks)
# first: the report links it
write_summary(rows, snakemake.output.json, snakemake.output.md, figure_checks=figure_checks)
layout = load_layout(snakemake.input.layout)
drawn = {Path(f).stem for f in snakemake.input.figures}
shown = set(layout_figures(layout))
problems = []
if drawn != shown:
    problems.append(f"workflow/report.yaml: figures not shown {sorted(drawn - shown)}, "
                    f"unknown figures {sorted(shown - drawn)}")
coverage_file = snakemake.input.get("coverage", "workflow/coverage.yaml")
coverage = load_coverage(coverage_file)
problems += coverage_problems(coverage, {f: snakemake.params.figure_data.get(f, f)
                                         for f in layout_figures(layout)})
bad = failed(rows)
if bad:
    problems.append(f"reference check failed for: {', '.join(r.id for r in bad)}")
problems += figure_problems(figure_checks)
errata = {e["id"]: e for e in reference.get("errata", [])}
stress = read_json(snakemake.input.stress)  # {"skipped": [areas], "cases": [results]}
if not (isinstance(stress, dict) and {"skipped", "cases"} <= set(stress)):
    sys.exit(f"{snakemake.input.stress}: not the stress job's record ({{skipped, cases}}): "
             "run the workflow again (its stress job rewrites it)")
params = {name: d.get("params", {}) for name, d in data.items()}
own = {name: scene_parameter_changes(recorded, snakemake.params.fidelity, name, p)
       for name, p in params.items()}


def index(problems):
    return build_index(layout, rows, errata, figure_data=snakemake.params.figure_data,
                       stress=stress["cases"], stress_skipped=stress["skipped"],
                       problems=problems, coverage=coverage,
                       row_scene=row_scenes(reference), figure_params=params,
                       own_parameters=own,
                       footer=provenance(), figure_checks=figure_checks,
                       formats=snakemake.params.formats)


write_text(snakemake.output.html, index(problems))
bad_links = broken_links(snakemake.output.html)
if bad_links:
    problems.append(f"results/reports/index.html: links that do not resolve: {bad_links}")
    write_text(snakemake.output.html, index(problems))
write_json(snakemake.output.problems, {"problems": problems})
