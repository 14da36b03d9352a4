"""Draw the work-precision figure (every solver family's error against its wall time) from the
four studies, as soon as they are solved."""

from flutterfriction.benchmarks import gather_runs, read_studies
from flutterfriction.io import log_job_output
from flutterfriction.plotting import save_figure
from flutterfriction.plotting.benchmarks import plot_work_precision

log_job_output(snakemake.log[0])  # this job's output goes to its log file

runs = gather_runs(*read_studies(snakemake.input))
pdfs = [p for p in snakemake.output if p.endswith(".pdf")]  # none in the quick preset
save_figure(plot_work_precision(runs), *pdfs, snakemake.output.png,
            check=snakemake.output.check)
