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
