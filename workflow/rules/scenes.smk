# Every scene: a solver rule writing results/data/<scene>.json, then (for figures) a plot rule
# writing results/figures/<scene>.{pdf,png}. The scene lists say which chapter part is which.

# §2.1–2.3 (undamped) and §2.2/2.4/2.10 (viscous hinges, the Ziegler paradox).
ZIEGLER_FIGURES = ["eq25", "eq46", "eq47", "eq48", "fig02", "fig03", "fig04"]
ZIEGLER_SCENES = ZIEGLER_FIGURES + ["errata_ziegler"]
PARADOX_FIGURES = ["fig05", "paradox_limit", "fig19_theory", "paradox_map"]
PARADOX_SCENES = PARADOX_FIGURES + ["damped_dead_load", "errata_damped"]
# §2.5–2.8: the Beck and Pflüger rods.
ROD_FIGURES = ["fig11", "fig12", "rod_fe_convergence", "rod_stability_map"]
ROD_SCENES = ROD_FIGURES + ["errata_rods", "self_adjoint"]
# §3: frictional solids.
SOLID_FIGURES = ["fig22", "acoustic_eigenvalues", "localization_directions", "flutter_map"]
SOLID_SCENES = SOLID_FIGURES + ["solids_statements", "errata_solids"]
# §2.9–2.11: nonlinear dynamics and limit cycles (the Ziegler pendulum so far).
CYCLE_FIGURES = [
    "fig13",
    "fig14",
    "fig20",
    "fig21",
    "fig15",
    "fig16",
    "fig17",
    "limit_cycle_amplitude",
    "beck_work_precision",
    "beck_linearisation",
    "beck_hopf",
]
CYCLE_SCENES = [
    "fig13",
    "fig14",
    "fig20",
    "fig21",
    "beck_limit_cycle",
    "limit_cycle_amplitude",
    "beck_work_precision",
    "beck_linearisation",
    "pendulum_work_precision",
    "beck_hopf",
]
# Figures drawn from another scene's data (one computation, several views).
FIGURE_DATA = {
    "fig15": "beck_limit_cycle",
    "fig16": "beck_limit_cycle",
    "fig17": "beck_limit_cycle",
}
# Sweeps (bifurcation diagrams, stability maps): their points scatter over `sweep_parts` jobs
# (one SLURM job each on a cluster), gathered by the scene's solve job.
SWEEP_SCENES = ["limit_cycle_amplitude", "rod_stability_map"]
# The slow solvers (~10-45 s each, the rest ~1 s) start first, so that the many short jobs
# fill the other core around them instead of leaving a long tail.
SLOW_SCENES = [
    "beck_hopf",
    "beck_limit_cycle",
    "beck_work_precision",
    "rod_fe_convergence",
    "pendulum_work_precision",
]
ALL_FIGURES = ZIEGLER_FIGURES + PARADOX_FIGURES + ROD_FIGURES + SOLID_FIGURES + CYCLE_FIGURES
ALL_SCENES = ZIEGLER_SCENES + PARADOX_SCENES + ROD_SCENES + SOLID_SCENES + CYCLE_SCENES


rule solve_part:
    input:
        SOLVER_SOURCES,
    output:
        "results/data/parts/{scene}/{part}-of-{n}.json",
    log:
        "results/logs/solve_part/{scene}/{part}-of-{n}.log",
    benchmark:
        "results/benchmarks/{scene}.part{part}-of-{n}.tsv"
    wildcard_constraints:
        scene="|".join(SWEEP_SCENES),
        part=r"\d+",
        n=r"\d+",
    priority: 5
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=20,
        mem_mb=1000,
    params:
        cfg=lambda w: scene_params(config, w.scene),
    script:
        "../scripts/solve_part.py"


rule solve:
    input:
        SOLVER_SOURCES,
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
        scene="|".join(ALL_SCENES),
    priority: lambda w: 10 if w.scene in SLOW_SCENES else 0
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=solve_runtime,
        mem_mb=1000,
    params:
        # The resolved parameters: editing one scene's config reruns that scene only.
        cfg=lambda w: scene_params(config, w.scene),
    script:
        "../scripts/solve_scene.py"


rule plot:
    input:
        PLOT_SOURCES,
        data=lambda w: f"results/data/{FIGURE_DATA.get(w.scene, w.scene)}.json",
        timings=lambda w: f"results/benchmarks/{FIGURE_DATA.get(w.scene, w.scene)}.timings.json",
    output:
        pdf="results/figures/{scene}.pdf",
        png="results/figures/{scene}.png",
    log:
        "results/logs/plot/{scene}.log",
    wildcard_constraints:
        scene="|".join(ALL_FIGURES),
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        # quick preset: cheaper PNG/PDF rendering (see plotting.save_figure)
        draft=config.get("fidelity", "paper") == "quick",
    script:
        "../scripts/plot_scene.py"


rule animate_pendulum_cycle:
    input:
        PLOT_SOURCES,
        data="results/data/fig14.json",
    output:
        "results/figures/pendulum_cycle.gif",
    log:
        "results/logs/animate_pendulum_cycle.log",
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    script:
        "../scripts/animate_pendulum.py"


rule animate_rod_cycle:
    input:
        PLOT_SOURCES,
        data="results/data/beck_limit_cycle.json",
    output:
        "results/figures/beck_cycle.gif",
    log:
        "results/logs/animate_rod_cycle.log",
    conda:
        "../envs/flutterfriction.yaml"
    resources:
        runtime=10,
        mem_mb=1000,
    script:
        "../scripts/animate_rod.py"
