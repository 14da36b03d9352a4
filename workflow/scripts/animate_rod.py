"""The nonlinear Beck rod's limit cycle as a GIF (thin: JSON in, GIF out)."""

from flutterfriction.io import read_json
from flutterfriction.plotting.animation import rod_cycle_gif

rod_cycle_gif(read_json(snakemake.input.data), snakemake.output[0])
