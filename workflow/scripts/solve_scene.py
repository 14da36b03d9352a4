"""Compute one scene's data (thin: parameters in, package call, JSON out)."""

from flutterfriction.io import write_json
from flutterfriction.scenes import build_scene

write_json(snakemake.output[0], build_scene(snakemake.wildcards.scene, snakemake.params.cfg))
