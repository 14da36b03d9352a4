"""Compute one scene's data (thin: parameters in, package call, JSON out); a sweep scene is
gathered from its parts. Wall-clock timings go to their own file, so the data file is the same
byte for byte on every rerun. The job imports only its scene's module (params.compute, from
the registry), not the registry of every scene."""

from flutterfriction.io import log_job_output, read_json, split_timings, write_json
from flutterfriction.scenes import build_scene, combine_scene_parts
from flutterfriction.sources import resolve

log_job_output(snakemake.log[0])  # this job's output goes to its log file

scene, params = snakemake.wildcards.scene, snakemake.params.cfg
if snakemake.input.parts:
    parts = [read_json(p) for p in snakemake.input.parts]
    data = combine_scene_parts(scene, params, parts, resolve(snakemake.params.sweep))
else:
    data = build_scene(scene, params, resolve(snakemake.params.compute))
data, timings = split_timings(data)
write_json(snakemake.output.data, data)
write_json(snakemake.output.timings, timings or {})
