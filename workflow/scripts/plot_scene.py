"""Draw one figure from its scene's data (thin: JSON in, PDF + PNG out; PNG only in the quick
preset); the job imports only the figure's plotting module (params.plot, from the registry)."""

from flutterfriction.io import log_job_output, merge_timings, read_json
from flutterfriction.plotting import save_figure
from flutterfriction.sources import resolve

log_job_output(snakemake.log[0])  # this job's output goes to its log file

data = merge_timings(read_json(snakemake.input.data), read_json(snakemake.input.timings) or None)
fig = resolve(snakemake.params.plot)(data)
pdfs = [p for p in snakemake.output if p.endswith(".pdf")]  # none in the quick preset
save_figure(fig, *pdfs, snakemake.output.png, draft=snakemake.params.draft,
            check=snakemake.output.check)
