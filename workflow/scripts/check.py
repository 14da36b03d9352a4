"""Compare every scene with workflow/reference.yaml; write the summary and the report; fail on
any mismatch or on a report link that does not resolve."""

import sys
from pathlib import Path

from flutterfriction.io import read_json, write_text
from flutterfriction.reference import (
    failed,
    load_reference,
    load_scene_data,
    run_check,
    summary_markdown,
    write_summary,
)
from flutterfriction.report import broken_links, build_index, layout_figures, load_layout

reference = load_reference(snakemake.input.reference)
rows = run_check(reference, load_scene_data(snakemake.input.data), snakemake.params.fidelity)
write_summary(rows, snakemake.output.json, snakemake.output.md)
print(summary_markdown(rows))

layout = load_layout(snakemake.input.layout)
drawn = {Path(f).stem for f in snakemake.input.figures}
shown = set(layout_figures(layout))
problems = []
if drawn != shown:
    problems.append(f"workflow/report.yaml: figures not shown {sorted(drawn - shown)}, "
                    f"unknown figures {sorted(shown - drawn)}")
errata = {e["id"]: e for e in reference.get("errata", [])}
write_text(snakemake.output.html,
           build_index(layout, rows, errata, figure_data=snakemake.params.figure_data,
                       stress=read_json(snakemake.input.stress)))
bad_links = broken_links(snakemake.output.html)
if bad_links:
    problems.append(f"results/reports/index.html: links that do not resolve: {bad_links}")

bad = failed(rows)
if bad:
    problems.append(f"reference check failed for: {', '.join(r.id for r in bad)}")
if problems:
    # Snakemake deletes the outputs of a failed job: keep a copy to read.
    write_text(Path(snakemake.output.md).with_name("FAILED-summary.md"), summary_markdown(rows))
    sys.exit("\n".join(problems))
