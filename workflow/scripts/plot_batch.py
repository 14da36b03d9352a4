"""Draw the figures of one chapter part's cheap scenes in one process (thin: JSON in, PDF + PNG
out; the same files as the one-figure job)."""

from pathlib import Path

from flutterfriction.io import log_job_output, merge_timings, read_json
from flutterfriction.plotting import save_figure
from flutterfriction.sources import resolve

log_job_output(snakemake.log[0])  # this job's output goes to its log file

data_files = {Path(p).stem: p for p in snakemake.input.data}
timing_files = {Path(p).name.removesuffix(".timings.json"): p for p in snakemake.input.timings}
for figure, (scene, plot) in snakemake.params.figures.items():
    data = merge_timings(read_json(data_files[scene]), read_json(timing_files[scene]) or None)
    paths = [f"results/figures/{figure}.{ext}" for ext in ("pdf", "png")
             if f"results/figures/{figure}.{ext}" in snakemake.output]
    save_figure(resolve(plot)(data), *paths, draft=snakemake.params.draft,
                check=f"results/checks/figures/{figure}.json")
    print(f"{figure}: drawn", flush=True)
