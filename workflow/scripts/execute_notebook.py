"""Execute a jupytext notebook from the repository root and write it as HTML (atomically) that
reads offline: math as MathML, code folded, the workflow's figures linked rather than embedded
again (flutterfriction.notebook_export)."""

from pathlib import Path

import jupytext
from nbclient import NotebookClient

from flutterfriction.io import log_job_output, write_text
from flutterfriction.notebook_export import export_notebook

log_job_output(snakemake.log[0])  # this job's output goes to its log file

nb = jupytext.read(snakemake.input.notebook)
NotebookClient(nb, timeout=600, kernel_name="python3",
               resources={"metadata": {"path": str(Path.cwd())}}).execute()
figure_dirs = sorted({str(Path(f).parent) for f in snakemake.input.figures}) or ["results/figures"]
write_text(snakemake.output[0], export_notebook(nb, figure_dirs, "../figures"))
