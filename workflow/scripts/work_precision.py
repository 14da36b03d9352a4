"""Gather the work-precision studies and the jobs' benchmarks into one table (JSON + Markdown);
the figure is work_precision_figure.py's (drawn earlier, from the studies alone)."""

from flutterfriction.benchmarks import (
    gather_runs,
    read_benchmarks,
    read_studies,
    work_precision_markdown,
)
from flutterfriction.io import log_job_output, write_json, write_text

log_job_output(snakemake.log[0])  # this job's output goes to its log file

runs = gather_runs(*read_studies(snakemake.input))
jobs = read_benchmarks(snakemake.input.benchmarks)
write_json(snakemake.output.json, {"runs": runs, "jobs": jobs})
write_text(snakemake.output.md, work_precision_markdown(runs, jobs))
