"""Compare every scene with workflow/reference.yaml; write the summary; fail on any mismatch."""

import sys
from pathlib import Path

from flutterfriction.io import write_text
from flutterfriction.reference import (
    failed,
    load_reference,
    load_scene_data,
    run_check,
    summary_markdown,
    write_summary,
)

rows = run_check(load_reference(snakemake.input.reference), load_scene_data(snakemake.input.data))
write_summary(rows, snakemake.output.json, snakemake.output.md)
print(summary_markdown(rows))
bad = failed(rows)
if bad:
    # Snakemake deletes the outputs of a failed job: keep a copy to read.
    write_text(Path(snakemake.output.md).with_name("FAILED-summary.md"), summary_markdown(rows))
    sys.exit(f"reference check failed for: {', '.join(r.id for r in bad)}")
