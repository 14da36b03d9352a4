"""Compute one block of a sweep scene (thin: parameters in, package call, JSON out)."""

from flutterfriction.io import write_json
from flutterfriction.scenes import build_scene_part

w = snakemake.wildcards
write_json(snakemake.output[0], build_scene_part(w.scene, snakemake.params.cfg, int(w.part),
                                                 int(w.n)))
