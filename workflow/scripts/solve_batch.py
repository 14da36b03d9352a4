"""Compute the cheap scenes of one chapter part in one process (thin: parameters in, package
calls, JSON out; the same per-scene files as the one-scene job)."""

from flutterfriction.io import log_job_output, split_timings, write_json
from flutterfriction.scenes import build_scene
from flutterfriction.sources import resolve

log_job_output(snakemake.log[0])  # this job's output goes to its log file

for k, scene in enumerate(snakemake.params.scenes):
    data = build_scene(scene, snakemake.params.cfg[scene], resolve(snakemake.params.compute[scene]))
    data, timings = split_timings(data)
    write_json(snakemake.output.data[k], data)
    write_json(snakemake.output.timings[k], timings or {})
    print(f"{scene}: done", flush=True)
