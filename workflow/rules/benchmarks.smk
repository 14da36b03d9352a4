# The work-precision scene: every solver family's accuracy against cost (one figure, drawn as
# soon as the four studies are solved), and the wall time and peak memory of every job (from
# the `benchmark:` files, one table, written once every job has run).

from flutterfriction.benchmarks import STUDIES

# The four studies' data and timings, by the input names benchmarks.read_studies reads.
WORK_PRECISION_STUDIES = {
    **{name: f"results/data/{scene}.json" for name, scene in STUDIES.items()},
    **{
        f"{name}_timings": f"results/benchmarks/{scene}.timings.json"
        for name, scene in STUDIES.items()
    },
}


rule work_precision_figure:
    input:
        job_sources("flutterfriction.benchmarks", "flutterfriction.plotting.benchmarks"),
        **WORK_PRECISION_STUDIES,
    output:
        *[f"results/benchmarks/work_precision.{ext}" for ext in PDF],
        png="results/benchmarks/work_precision.png",
        check="results/checks/figures/work_precision.json",
    log:
        "results/logs/work_precision_figure.log",
    benchmark:
        "results/benchmarks/work_precision_figure.tsv"
    priority: 3  # with the other figures (see animate_pendulum_cycle)
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    script:
        "../scripts/work_precision_figure.py"


# Last but the report: it reads the benchmark file of every job, the notebooks' included (it
# imports no matplotlib, so the run's serial tail stays short).
rule work_precision:
    input:
        job_sources("flutterfriction.benchmarks"),
        **WORK_PRECISION_STUDIES,
        benchmarks=benchmark_files,
    output:
        json="results/benchmarks/work_precision.json",
        md="results/benchmarks/work_precision.md",
    log:
        "results/logs/work_precision.log",
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    script:
        "../scripts/work_precision.py"
