# The work-precision scene: every solver family's accuracy against cost (one figure, drawn as
# soon as the four studies are solved), and the wall time and peak memory of every job (from
# the `benchmark:` files, one table, written once every job has run).

WORK_PRECISION_STUDIES = dict(
    pendulum="results/data/pendulum_work_precision.json",
    pendulum_timings="results/benchmarks/pendulum_work_precision.timings.json",
    rod_fe="results/data/rod_fe_convergence.json",
    rod_fe_timings="results/benchmarks/rod_fe_convergence.timings.json",
    rod_integrators="results/data/beck_work_precision.json",
    rod_integrators_timings="results/benchmarks/beck_work_precision.timings.json",
    rod_cycle="results/data/beck_limit_cycle.json",
    rod_cycle_timings="results/benchmarks/beck_limit_cycle.timings.json",
)


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
