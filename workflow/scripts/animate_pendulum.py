"""The pendulum's limit cycle as a GIF (thin: JSON in, GIF out)."""

from flutterfriction.io import read_json
from flutterfriction.plotting.animation import pendulum_cycle_gif

pendulum_cycle_gif(read_json(snakemake.input.data), snakemake.output[0])
