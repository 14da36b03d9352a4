"""Draw one scene's figure from its data (thin: JSON in, PDF + PNG out)."""

from flutterfriction.io import read_json
from flutterfriction.plotting import save_figure
from flutterfriction.plotting.registry import PLOTS

fig = PLOTS[snakemake.wildcards.scene](read_json(snakemake.input.data))
save_figure(fig, snakemake.output.pdf, snakemake.output.png)
