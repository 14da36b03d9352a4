"""Compute one block of a sweep scene (thin: parameters in, package call, JSON out)."""

from flutterfriction.io import log_job_output, write_json
from flutterfriction.scenes import build_scene_part
from flutterfriction.sources import resolve

log_job_output(snakemake.log[0])  # this job's output goes to its log file

w = snakemake.wildcards
sweep = resolve(snakemake.params.sweep)
write_json(snakemake.output[0], build_scene_part(w.scene, snakemake.params.cfg, int(w.part),
                                                 int(w.n), sweep))
