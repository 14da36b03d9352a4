"""The pendulum's limit cycle as a GIF (thin: JSON in, GIF out)."""

from flutterfriction.io import log_job_output, read_json
from flutterfriction.plotting.animation import pendulum_cycle_gif

log_job_output(snakemake.log[0])  # this job's output goes to its log file

# the quick preset: a handful of frames (a smoke test of the animation, ~1 s)
frames = {"frames": 8} if snakemake.params.quick else {}
pendulum_cycle_gif(read_json(snakemake.input.data), snakemake.output[0], **frames)
