"""Gather the work-precision studies and the jobs' benchmarks into one figure and one table."""

from flutterfriction.benchmarks import gather_runs, read_benchmarks, work_precision_markdown
from flutterfriction.io import log_job_output, merge_timings, read_json, write_json, write_text
from flutterfriction.plotting import save_figure
from flutterfriction.plotting.benchmarks import plot_work_precision

log_job_output(snakemake.log[0])  # this job's output goes to its log file


def scene(name):
    data = getattr(snakemake.input, name)
    timings = getattr(snakemake.input, f"{name}_timings")
    return merge_timings(read_json(data), read_json(timings) or None)


runs = gather_runs(scene("pendulum"), scene("rod_fe"), scene("rod_integrators"),
                   scene("rod_cycle"))
jobs = read_benchmarks(snakemake.input.benchmarks)
write_json(snakemake.output.json, {"runs": runs, "jobs": jobs})
write_text(snakemake.output.md, work_precision_markdown(runs, jobs))
pdfs = [p for p in snakemake.output if p.endswith(".pdf")]  # none in the quick preset
save_figure(plot_work_precision(runs), *pdfs, snakemake.output.png,
            check=snakemake.output.check)
