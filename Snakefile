# flutterfriction: `snakemake -j2` rebuilds every result into results/ and ends with the
# tolerance check of every number the chapter quotes (results/checks/summary.md).
import sys

from snakemake.utils import min_version

from flutterfriction.config import validate_config

min_version("8.0")


configfile: "workflow/config.yaml"


# The whole configuration, every preset as it resolves, before the first job: one line per
# problem naming the key (the schema, the pendulum and rod geometry, finite numbers, ranges).
_problems = validate_config(config, "workflow/schemas/config.schema.yaml")
if _problems:
    sys.exit("invalid configuration:\n  " + "\n  ".join(_problems))


include: "workflow/rules/common.smk"
include: "workflow/rules/scenes.smk"
include: "workflow/rules/reports.smk"
include: "workflow/rules/benchmarks.smk"
include: "workflow/rules/check.smk"


# Cheap bookkeeping jobs run on the submitting node, not as cluster jobs.
localrules:
    all,
    report,
    check,


rule all:
    input:
        USER_OUTPUTS,
        rules.check.output,
    default_target: True
