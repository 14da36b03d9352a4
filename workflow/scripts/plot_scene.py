"""Draw one scene's figure from its data (thin: JSON in, PDF + PNG out)."""

from flutterfriction.io import log_job_output, merge_timings, read_json
from flutterfriction.plotting import save_figure
from flutterfriction.plotting.registry import PLOTS

log_job_output(snakemake.log[0])  # this job's output goes to its log file

data = merge_timings(read_json(snakemake.input.data), read_json(snakemake.input.timings) or None)
fig = PLOTS[snakemake.wildcards.scene](data)
save_figure(fig, snakemake.output.pdf, snakemake.output.png, draft=snakemake.params.draft)
