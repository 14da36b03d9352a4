"""Compute one block of a sweep scene (thin: parameters in, package call, JSON out)."""

from flutterfriction.io import log_job_output, write_json
from flutterfriction.scenes import build_scene_part
from flutterfriction.sources import resolve

log_job_output(snakemake.log[0])  # this job's output goes to its log file

w = snakemake.wildcards
k, n = (int(x) for x in w.scatteritem.split("-of-"))  # Snakemake's scatter item: 1-based
sweep = resolve(snakemake.params.sweep)
write_json(snakemake.output[0], build_scene_part(w.scene, snakemake.params.cfg, k - 1, n, sweep))
