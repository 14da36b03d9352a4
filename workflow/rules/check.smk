# The last target: every quoted number against workflow/reference.yaml.


rule check:
    input:
        reference="workflow/reference.yaml",
        data=expand("results/data/{scene}.json", scene=ALL_SCENES),
        figures=expand("results/figures/{scene}.{ext}", scene=ALL_FIGURES, ext=["pdf", "png"]),
        animations=["results/figures/pendulum_cycle.gif", "results/figures/beck_cycle.gif"],
        reports=["results/reports/ziegler.html", "results/reports/ziegler_paradox.html",
                 "results/reports/rods.html", "results/reports/solids.html",
                 "results/reports/limit_cycles.html"],
    output:
        json="results/checks/summary.json",
        md="results/checks/summary.md",
    script:
        "../scripts/check.py"
