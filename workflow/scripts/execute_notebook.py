"""Execute a jupytext notebook from the repository root and write it as HTML (atomically)."""

from pathlib import Path

import jupytext
import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter

from flutterfriction.io import log_job_output, write_text

log_job_output(snakemake.log[0])  # this job's output goes to its log file

nb = jupytext.read(snakemake.input.notebook)
NotebookClient(nb, timeout=600, kernel_name="python3",
               resources={"metadata": {"path": str(Path.cwd())}}).execute()
html, _ = HTMLExporter().from_notebook_node(nbformat.from_dict(nb))
write_text(snakemake.output[0], html)
