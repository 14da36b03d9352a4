"""Run the stress tests; write what was tried and the outcome; fail on a silent wrong answer."""

import sys

from flutterfriction.io import log_job_output, write_json, write_text
from flutterfriction.stress import WRONG, run_all, skipped_areas, stress_markdown

log_job_output(snakemake.log[0])  # this job's output goes to its log file

skipped = skipped_areas(snakemake.params.fidelity, snakemake.params.level)
results = run_all(skip=skipped)
write_json(snakemake.output.json,
           {"skipped": list(skipped), "cases": [r.as_dict() for r in results]})
write_text(snakemake.output.md, stress_markdown(results, skipped))
wrong = [f"{r.area}: {r.case}" for r in results if r.outcome == WRONG]
if wrong:
    sys.exit(f"stress tests: silent wrong answers in {wrong}")
