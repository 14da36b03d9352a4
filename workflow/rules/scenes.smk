# Every scene of src/flutterfriction/registry.py: a solver rule writing results/data/<scene>.json,
# then one plot rule per figure drawn from it, writing results/figures/<figure>.{pdf,png}.
# Sweeps (bifurcation diagrams, stability maps) scatter their points over the `sweep` jobs of
# Snakemake's scatter-gather (`sweep_parts` in the config, or `--set-scatter sweep=64`; one SLURM
# job each on a cluster), gathered by the scene's solve job.


scattergather:
    sweep=config.get("sweep_parts", 2),


# `--set-scatter sweep=N` bypasses the config's check of sweep_parts: refused here, in one line
# before any job (as an input function's error it came with a traceback; an outside audit).
_unknown_scatter = sorted(set(getattr(workflow, "_scatter", {})) - {"sweep"})
if _unknown_scatter:  # (an outside audit: --set-scatter foo=3 was accepted silently)
    sys.exit(
        f"invalid configuration:\n  --set-scatter: unknown scatter name(s) {_unknown_scatter}; "
        f"the workflow has one, sweep (--set-scatter sweep=N)"
    )
_sweep_parts = getattr(workflow, "_scatter", {}).get("sweep", 1)
if not (isinstance(_sweep_parts, int) and 1 <= _sweep_parts <= 10000):
    sys.exit(
        f"invalid configuration:\n  sweep parts (sweep_parts or --set-scatter sweep=N) must be "
        f"in [1, 10000], got {_sweep_parts!r}"
    )


# The nonlinear rod's compiled kernels (models/rod_kernel.py), built once into numba's cache
# before the jobs that import them (~8 s of compilation; side by side, each would compile).
rule compile_kernels:
    input:
        job_sources("flutterfriction.models.rod_nonlinear"),
    output:
        "results/benchmarks/kernels.json",
    log:
        "results/logs/compile_kernels.log",
    priority: 20
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    script:
        "../scripts/compile_kernels.py"


rule solve_part:
    input:
        scene_sources,
    output:
        "results/data/parts/{scene}/{scatteritem}.json",
    log:
        "results/logs/solve_part/{scene}/{scatteritem}.log",
    benchmark:
        "results/benchmarks/{scene}.part{scatteritem}.tsv"
    wildcard_constraints:
        scene="|".join(SWEEP_SCENES),
        scatteritem=r"\d+-of-\d+",
    priority: 5
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=20,
        mem_mb=1000,
    params:
        cfg=lambda w: scene_params(config, w.scene),
        sweep=scene_sweep,
    script:
        "../scripts/solve_part.py"


rule solve:
    input:
        scene_sources,
        parts=sweep_parts,
    output:
        data="results/data/{scene}.json",
        # wall-clock measurements, kept out of the data so that reruns are byte-identical
        timings="results/benchmarks/{scene}.timings.json",
    log:
        "results/logs/solve/{scene}.log",
    benchmark:
        "results/benchmarks/{scene}.solve.tsv"
    wildcard_constraints:
        scene="|".join(SINGLE_SCENES),
    priority: scene_priority
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=solve_runtime,
        mem_mb=1000,
    params:
        # The resolved parameters: editing one scene's config reruns that scene only.
        cfg=lambda w: scene_params(config, w.scene),
        compute=scene_compute,
        sweep=scene_sweep,
    script:
        "../scripts/solve_scene.py"


rule plot:
    input:
        figure_sources,
        data=figure_data,
        timings=figure_timings,
    output:
        # the PDF (not in the quick preset: PNG only there)
        *[f"results/figures/{{scene}}.{ext}" for ext in PDF],
        # in `snakemake --report`, with the figure's caption from the registry
        png=report(
            "results/figures/{scene}.png",
            caption="../report/figure.rst",
            category="Figures",
            labels={"figure": "{scene}"},
        ),
        # the figure check's offences (flutterfriction.figure_check; the check fails on any)
        check="results/checks/figures/{scene}.json",
    log:
        "results/logs/plot/{scene}.log",
    benchmark:
        "results/benchmarks/plot_{scene}.tsv"
    wildcard_constraints:
        scene="|".join(SINGLE_FIGURES),
    # as the batches' figures: a notebook waits for its part's figures (drawn last, a sweep's
    # figure left its notebook and the report a serial tail)
    priority: 3
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        # quick preset: cheaper PNG/PDF rendering (see plotting.save_figure)
        draft=DRAFT,
        plot=figure_plot,
        caption=figure_caption,
        part=figure_part,
    script:
        "../scripts/plot_scene.py"


# One job per chapter part for its cheap scenes, and one for their figures (see BATCHES).
for _part in BATCHES:

    rule:
        name:
            f"solve_{_part}"
        input:
            batch_sources(_part),
        output:
            data=expand("results/data/{scene}.json", scene=BATCHES[_part]),
            timings=expand("results/benchmarks/{scene}.timings.json", scene=BATCHES[_part]),
        log:
            f"results/logs/solve/{_part}.log",
        benchmark:
            f"results/benchmarks/solve_{_part}.tsv"
        # before any figure or notebook (all solves first, longest first; the many short plot
        # and notebook jobs then fill both cores to the end instead of a serial tail)
        priority: batch_priority(_part)
        conda:
            "../envs/flutterfriction.yaml"
        resources:
            runtime=10,
            mem_mb=1000,
        params:
            scenes=BATCHES[_part],
            # The resolved parameters: editing a scene's config reruns its part's batch.
            cfg={n: scene_params(config, n) for n in BATCHES[_part]},
            compute={n: SCENES[n].compute for n in BATCHES[_part]},
        script:
            "../scripts/solve_batch.py"


for _part in FIGURE_BATCHES:

    rule:
        name:
            f"plot_{_part}"
        input:
            figure_batch_sources(_part),
            data=expand("results/data/{scene}.json", scene=FIGURE_BATCH_SCENES[_part]),
            timings=expand(
                "results/benchmarks/{scene}.timings.json", scene=FIGURE_BATCH_SCENES[_part]
            ),
        output:
            batch_figure_outputs(_part),
        log:
            f"results/logs/plot/{_part}.log",
        benchmark:
            f"results/benchmarks/plot_{_part}.tsv"
        # before the notebooks and the one-figure jobs, the most figures first: the batches are
        # the longest plot jobs (~0.5-1 s a figure; the paper run's rods batch, 9 figures, took
        # 11 s), and one started last leaves a serial tail (its notebook waits for it; measured
        # on 2026-11-30: started among the one-figure jobs, the rods and Ziegler batches ran
        # until the notebooks' turn)
        priority: 3 + len(FIGURE_BATCHES[_part]) / 100
        conda:
            "../envs/flutterfriction.yaml"
        resources:
            runtime=10,
            mem_mb=1000,
        params:
            figures={f: (FIGURE_DATA[f], FIGURES[f][1].path) for f in FIGURE_BATCHES[_part]},
            draft=DRAFT,
        script:
            "../scripts/plot_batch.py"


rule animate_pendulum_cycle:
    input:
        job_sources("flutterfriction.plotting.animation"),
        data="results/data/fig14.json",
    output:
        "results/figures/pendulum_cycle.gif",
    log:
        "results/logs/animate_pendulum_cycle.log",
    benchmark:
        "results/benchmarks/animate_pendulum_cycle.tsv"
    # with the figures, not after them: a 2.4 s GIF started last ran alone at the end of
    # the paper run (measured: 2.4 s of one idle core before the report)
    priority: 3
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        quick=config.get("fidelity", "paper") == "quick",
    script:
        "../scripts/animate_pendulum.py"


rule animate_rod_cycle:
    input:
        job_sources("flutterfriction.plotting.animation"),
        data="results/data/beck_limit_cycle.json",
    output:
        "results/figures/beck_cycle.gif",
    log:
        "results/logs/animate_rod_cycle.log",
    benchmark:
        "results/benchmarks/animate_rod_cycle.tsv"
    # with the figures, not after them: a 2.4 s GIF started last ran alone at the end of
    # the paper run (measured: 2.4 s of one idle core before the report)
    priority: 3
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        quick=config.get("fidelity", "paper") == "quick",
    script:
        "../scripts/animate_rod.py"
