# flutterfriction: `snakemake -j2` rebuilds every result into results/ and ends with the
# tolerance check of every number the chapter quotes (results/checks/summary.md).
from snakemake.utils import min_version, validate

min_version("8.0")

configfile: "workflow/config.yaml"


validate(config, "workflow/schemas/config.schema.yaml")


include: "workflow/rules/common.smk"
include: "workflow/rules/scenes.smk"
include: "workflow/rules/reports.smk"
include: "workflow/rules/benchmarks.smk"
include: "workflow/rules/check.smk"


rule all:
    input:
        rules.check.output,
    default_target: True
