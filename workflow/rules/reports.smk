# Notebooks (jupytext percent format) executed into HTML reports.


rule report_ziegler:
    input:
        notebook="notebooks/ziegler.py",
        data=expand("results/data/{scene}.json", scene=ZIEGLER_SCENES),
        figures=expand("results/figures/{scene}.png", scene=ZIEGLER_FIGURES),
    output:
        "results/reports/ziegler.html",
    benchmark:
        "results/benchmarks/report_ziegler.tsv"
    resources:
        runtime=20,
        mem_mb=2000,
    conda:
        "../envs/flutterfriction.yaml"
    log:
        "results/logs/report_ziegler.log",
    script:
        "../scripts/execute_notebook.py"


rule report_ziegler_paradox:
    input:
        notebook="notebooks/ziegler_paradox.py",
        data=expand("results/data/{scene}.json", scene=PARADOX_SCENES),
        figures=expand("results/figures/{scene}.png", scene=PARADOX_FIGURES),
    output:
        "results/reports/ziegler_paradox.html",
    benchmark:
        "results/benchmarks/report_ziegler_paradox.tsv"
    resources:
        runtime=20,
        mem_mb=2000,
    conda:
        "../envs/flutterfriction.yaml"
    log:
        "results/logs/report_ziegler_paradox.log",
    script:
        "../scripts/execute_notebook.py"


rule report_rods:
    input:
        notebook="notebooks/rods.py",
        data=expand("results/data/{scene}.json", scene=ROD_SCENES),
        figures=expand("results/figures/{scene}.png", scene=ROD_FIGURES),
    output:
        "results/reports/rods.html",
    benchmark:
        "results/benchmarks/report_rods.tsv"
    resources:
        runtime=20,
        mem_mb=2000,
    conda:
        "../envs/flutterfriction.yaml"
    log:
        "results/logs/report_rods.log",
    script:
        "../scripts/execute_notebook.py"


rule report_solids:
    input:
        notebook="notebooks/solids.py",
        data=expand("results/data/{scene}.json", scene=SOLID_SCENES),
        figures=expand("results/figures/{scene}.png", scene=SOLID_FIGURES),
    output:
        "results/reports/solids.html",
    benchmark:
        "results/benchmarks/report_solids.tsv"
    resources:
        runtime=20,
        mem_mb=2000,
    conda:
        "../envs/flutterfriction.yaml"
    log:
        "results/logs/report_solids.log",
    script:
        "../scripts/execute_notebook.py"


rule report_limit_cycles:
    input:
        notebook="notebooks/limit_cycles.py",
        data=expand("results/data/{scene}.json", scene=CYCLE_SCENES),  # incl. the rod cycle
        timings=expand("results/benchmarks/{scene}.timings.json", scene=CYCLE_SCENES),
        figures=expand("results/figures/{scene}.png", scene=CYCLE_FIGURES),
    output:
        "results/reports/limit_cycles.html",
    benchmark:
        "results/benchmarks/report_limit_cycles.tsv"
    resources:
        runtime=20,
        mem_mb=2000,
    conda:
        "../envs/flutterfriction.yaml"
    log:
        "results/logs/report_limit_cycles.log",
    script:
        "../scripts/execute_notebook.py"
