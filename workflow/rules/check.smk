# The last target: every quoted number against workflow/reference.yaml, and the one report
# (results/reports/index.html) that shows the figures, the notebooks and this check.


rule stress:
    input:
        SOLVER_SOURCES,
        "src/flutterfriction/stress.py",
    output:
        json="results/checks/stress.json",
        md="results/reports/stress.md",
    benchmark:
        "results/benchmarks/stress.tsv"
    script:
        "../scripts/stress.py"


rule check:
    input:
        code=[str(PKG / "reference.py"), str(PKG / "report.py")],
        reference="workflow/reference.yaml",
        layout="workflow/report.yaml",
        stress="results/checks/stress.json",
        work_precision=rules.work_precision.output,
        data=expand("results/data/{scene}.json", scene=ALL_SCENES),
        figures=expand("results/figures/{scene}.{ext}", scene=ALL_FIGURES, ext=["pdf", "png"]),
        animations=["results/figures/pendulum_cycle.gif", "results/figures/beck_cycle.gif"],
        reports=["results/reports/ziegler.html", "results/reports/ziegler_paradox.html",
                 "results/reports/rods.html", "results/reports/solids.html",
                 "results/reports/limit_cycles.html"],
    output:
        json="results/checks/summary.json",
        md="results/checks/summary.md",
        html="results/reports/index.html",
    params:
        figure_data=FIGURE_DATA,
        fidelity=config.get("fidelity", "paper"),
    script:
        "../scripts/check.py"
