# Notebooks (jupytext percent format) executed into HTML reports: one rule over the notebook's
# name; each reads the data and figures of its part of the chapter.
NOTEBOOK_INPUTS = {
    part: (
        [s.name for s in PLAN.scenes_of(part)],
        [f for s in PLAN.scenes_of(part) for f in s.figures],
    )
    for part in PLAN.parts
}
NOTEBOOK_REPORTS = list(NOTEBOOK_INPUTS)
# The notebooks run last, after every figure, on both cores: the longest first, so that the run
# does not end on one long notebook with the other core idle (measured on 2026-11-30, seconds,
# paper / quick: limit_cycles 5.2 / 4.9, ziegler_paradox 5.0 / 4.2, ziegler 4.4 / 3.7, rods
# 4.2 / 3.4, solids 3.0 / 2.7; in the order Snakemake picked, the paper run ended ~5 s on one
# core). Below the figures' priority 3: a figure is never delayed by a notebook.
_NOTEBOOKS_LONGEST_FIRST = ("limit_cycles", "ziegler_paradox", "ziegler", "rods", "solids")


def notebook_priority(wildcards):
    order = _NOTEBOOKS_LONGEST_FIRST
    rank = order.index(wildcards.nb) if wildcards.nb in order else len(order)
    return 1 - rank / (len(order) + 1)


rule notebook:
    input:
        notebook="notebooks/{nb}.py",
        data=lambda w: expand("results/data/{scene}.json", scene=NOTEBOOK_INPUTS[w.nb][0]),
        timings=lambda w: expand(
            "results/benchmarks/{scene}.timings.json", scene=NOTEBOOK_INPUTS[w.nb][0]
        ),
        figures=lambda w: expand("results/figures/{scene}.png", scene=NOTEBOOK_INPUTS[w.nb][1]),
        # the chapter's parameters: the note on scenes computed with your own
        reference_parameters="workflow/reference_parameters.json",
    output:
        "results/reports/{nb}.html",
    log:
        "results/logs/notebook/{nb}.log",
    benchmark:
        "results/benchmarks/report_{nb}.tsv"
    wildcard_constraints:
        nb="|".join(NOTEBOOK_INPUTS),
    priority: notebook_priority
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=20,
        mem_mb=2000,
    script:
        "../scripts/execute_notebook.py"
