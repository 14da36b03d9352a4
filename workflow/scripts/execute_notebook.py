"""Execute a jupytext notebook from the repository root and write it as HTML (atomically) that
reads offline: math as MathML, code folded, the workflow's figures linked rather than embedded
again (flutterfriction.notebook_export)."""

from pathlib import Path

import jupytext
from nbclient import NotebookClient

from flutterfriction.io import log_job_output, write_text
from flutterfriction.notebook_export import export_notebook, warm_exporter

log_job_output(snakemake.log[0])  # this job's output goes to its log file

nb = jupytext.read(snakemake.input.notebook)
# The kernel is started first and the exporter warmed up while it boots (the job waited
# ~0.6 s for it, idle, then paid ~0.6 s for its first export's imports and compilations);
# "immediate": once the cells have run, the kernel has nothing left to save (a graceful
# shutdown waited ~0.2 s more; all measured).
client = NotebookClient(nb, timeout=600, kernel_name="python3", shutdown_kernel="immediate",
                        resources={"metadata": {"path": str(Path.cwd())}})
client.km = client.create_kernel_manager()
client.start_new_kernel()
try:
    warm_exporter()
    client.execute()
finally:
    # execute() shuts its kernel down however it ends; a failure before it (the exporter's
    # warm-up) would leave the kernel running, in a session of its own (an outside review)
    if client.km is not None:
        client._cleanup_kernel()
figure_dirs = sorted({str(Path(f).parent) for f in snakemake.input.figures}) or ["results/figures"]
write_text(snakemake.output[0], export_notebook(nb, figure_dirs, "../figures"))
