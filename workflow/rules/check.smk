# The last target: every quoted number against workflow/reference.yaml, and the one report
# (results/reports/index.html) that shows the figures, the notebooks and this check.


rule stress:
    input:
        job_sources("flutterfriction.stress"),
    output:
        json="results/checks/stress.json",
        md="results/reports/stress.md",
    log:
        "results/logs/stress.log",
    benchmark:
        "results/benchmarks/stress.tsv"
    priority: 10  # ~5 s (~29 with stress: full): start it with the slow solvers
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=20,
        mem_mb=1000,
    params:
        # which areas run: stress.skipped_areas (config `stress`: standard | full)
        fidelity=config["fidelity"],
        level=config.get("stress"),
    script:
        "../scripts/stress.py"


# The figure check of every figure drawn (written by its plot job; the report reads them all).
FIGURE_CHECKS = expand(
    "results/checks/figures/{figure}.json", figure=[*ALL_FIGURES, "work_precision"]
)


# Every output a reader sees: each is a target of `rule all`, so a deleted one is rebuilt
# (Snakemake does not rebuild a missing intermediate file whose consumers are up to date),
# and the report, which links to all of them, is refreshed.
USER_OUTPUTS = (
    expand("results/data/{scene}.json", scene=ALL_SCENES)
    + expand("results/figures/{scene}.{ext}", scene=ALL_FIGURES, ext=FIGURE_FORMATS)
    + ["results/figures/pendulum_cycle.gif", "results/figures/beck_cycle.gif"]
    + expand("results/reports/{nb}.html", nb=NOTEBOOK_REPORTS)
    + list(rules.work_precision.output)
    + list(rules.work_precision_figure.output)
    + list(rules.stress.output)
    + FIGURE_CHECKS
)


rule report:
    input:
        code=job_sources("flutterfriction.reference", "flutterfriction.report"),
        reference="workflow/reference.yaml",
        # the parameters each quoted value belongs to (another scene's: not applicable)
        reference_parameters="workflow/reference_parameters.json",
        layout="workflow/report.yaml",
        layout_schema="workflow/schemas/report.schema.yaml",
        coverage="workflow/coverage.yaml",
        stress="results/checks/stress.json",
        work_precision=rules.work_precision.output,
        work_precision_figure=rules.work_precision_figure.output,
        data=expand("results/data/{scene}.json", scene=ALL_SCENES),
        figures=expand("results/figures/{scene}.{ext}", scene=ALL_FIGURES, ext=FIGURE_FORMATS),
        animations=["results/figures/pendulum_cycle.gif", "results/figures/beck_cycle.gif"],
        reports=expand("results/reports/{nb}.html", nb=NOTEBOOK_REPORTS),
        figure_checks=FIGURE_CHECKS,
    output:
        json="results/checks/summary.json",
        md="results/checks/summary.md",
        html="results/reports/index.html",
        problems="results/checks/problems.json",
    log:
        "results/logs/report.log",
    benchmark:
        "results/benchmarks/report.tsv"
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        figure_data=FIGURE_DATA,
        fidelity=config.get("fidelity", "paper"),
        formats=FIGURE_FORMATS,
        # the check's verdict, removed when the report is rebuilt (rule check writes it)
        passed="results/checks/passed.txt",
    script:
        "../scripts/build_report.py"


rule check:
    input:
        problems=rules.report.output.problems,
        summary=rules.report.output.json,
        summary_md=rules.report.output.md,
    output:
        "results/checks/passed.txt",
    log:
        "results/logs/check.log",
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    script:
        "../scripts/check.py"
