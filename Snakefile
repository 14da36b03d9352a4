# flutterfriction: `snakemake -j2` rebuilds every result into results/ and ends with the
# tolerance check of every number the chapter quotes (results/checks/summary.md).
import os
import sys
from pathlib import Path

# One BLAS thread per job: the matrices are small and Snakemake already runs jobs in parallel;
# two threads per job on two cores made small eigenvalue solves up to 100x slower (measured
# 1.57 s vs 6 ms for one damped rod spectrum). Results do not depend on it (CI's
# reproducibility check). Jobs inherit the environment; a user's own setting is kept. (The
# variables of flutterfriction.threads.THREAD_VARIABLES, written out: importing the package
# would load numpy, and BLAS reads them when it loads.)
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from snakemake.utils import min_version

from flutterfriction.config import expand_parameter_lists
from flutterfriction.workflow_plan import workflow_plan

min_version("8.0")


configfile: "workflow/config.yaml"


# `snakemake --report report.html`: Snakemake's provenance report (code, runtimes, job graph) with
# every figure and its caption; the reader's report is results/reports/index.html.
report: "workflow/report/workflow.rst"


# The whole configuration, every preset as it resolves, before the first job: one line per
# problem naming the key (the schema, the pendulum and rod geometry, the models' numerical
# ranges, finite numbers, ranges); a key written twice in workflow/config.yaml or in any
# --configfile (Snakemake keeps the last silently); and the reference and coverage files,
# which the last jobs read. PLAN: the registry's scenes and the package's imports as the rules
# need them. Both come from a cache keyed by every file and setting they depend on
# (flutterfriction.workflow_plan: 2.5-3 s of each snakemake call here otherwise).
PKG = Path(workflow.basedir) / "src" / "flutterfriction"
PLAN, _problems = workflow_plan(config, workflow.configfiles, root=PKG)
if _problems:
    sys.exit("invalid configuration:\n  " + "\n  ".join(_problems))
expand_parameter_lists(config)  # `rod: list119` -> its values (flutterfriction.parameters)


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
    default_target: True
    input:
        USER_OUTPUTS,
        # the report and the check tables themselves: a report job that failed or was
        # interrupted is rebuilt by the next run (as targets only through the check, they
        # were forgotten while an old passed.txt stood; an outside audit)
        rules.report.output,
        rules.check.output,


# Snakemake's job-rate timers: fewer scheduling rounds (common.smk).
onstart:
    rate_limit_rounds_every(workflow)
    compile_package_bytecode(PKG)


# The finished run does not wait for Snakemake's job-rate timers (common.smk).
onsuccess:
    stop_rate_limit_timers()


onerror:
    stop_rate_limit_timers()
