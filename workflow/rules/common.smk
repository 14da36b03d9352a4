# Helpers shared by the rule files.
import sys
from pathlib import Path

from flutterfriction.config import scene_params

# Every list of scenes and figures comes from the registry (src/flutterfriction/registry.py),
# as PLAN gives it (the Snakefile; flutterfriction.workflow_plan): plain data, import paths.
SCENES = PLAN.scenes
FIGURES = PLAN.figures()  # figure -> (its scene, its plot function's path and caption)
ALL_SCENES = list(SCENES)
ALL_FIGURES = list(FIGURES)
FIGURE_DATA = {f: scene.name for f, (scene, _) in FIGURES.items()}  # figure -> data it draws
SWEEP_SCENES = [n for n, s in SCENES.items() if s.sweep]
# The slow solvers (~10-45 s each, the rest ~1 s) start first, so that the many short jobs
# fill the other core around them instead of leaving a long tail.
SLOW_SCENES = [n for n, s in SCENES.items() if s.slow]
# The quick preset (a smoke test) draws PNG only; the paper run also the PDF (vector, for print).
DRAFT = config.get("fidelity", "paper") == "quick"
FIGURE_FORMATS = ["png"] if DRAFT else ["pdf", "png"]
PDF = [] if DRAFT else ["pdf"]
# The cheap scenes of each chapter part are solved by one job, and their figures drawn by one:
# a job is a Python process whose start-up and imports (~0.5 s here) outweigh a cheap scene's
# computation (~0.1-1 s), so 30 such jobs would spend most of their time starting. Slow scenes
# and sweeps keep a job each (they start first, and scatter on a cluster). In the quick preset
# no scene is slow (0.3-2 s each), so every scene but the sweeps joins its part's batch.
BATCHES = {
    part: [s.name for s in PLAN.scenes_of(part) if (DRAFT or not s.slow) and not s.sweep]
    for part in PLAN.parts
}
BATCHES = {part: names for part, names in BATCHES.items() if names}
BATCHED = {name: part for part, names in BATCHES.items() for name in names}
SINGLE_SCENES = [n for n in ALL_SCENES if n not in BATCHED]
FIGURE_BATCHES = {
    part: [f for n in names for f in SCENES[n].figures] for part, names in BATCHES.items()
}
FIGURE_BATCHES = {part: figs for part, figs in FIGURE_BATCHES.items() if figs}
FIGURE_BATCH_SCENES = {part: BATCHES[part] for part in FIGURE_BATCHES}
# A slow scene that draws several figures (Figs. 15-17, from the rod's one cycle) draws them in
# one job too, named by the scene: they always rerun together, and each job more would pay
# its start-up and imports again (~1.7 CPU-s a plot job here).
MULTI_FIGURE_SCENES = {
    n: list(SCENES[n].figures) for n in SINGLE_SCENES if len(SCENES[n].figures) > 1
}
FIGURE_BATCHES.update(MULTI_FIGURE_SCENES)
FIGURE_BATCH_SCENES.update({n: [n] for n in MULTI_FIGURE_SCENES})
SINGLE_FIGURES = [
    f
    for f in ALL_FIGURES
    if FIGURE_DATA[f] not in BATCHED and FIGURE_DATA[f] not in MULTI_FIGURE_SCENES
]


def job_sources(*modules):
    """Source files of the package modules a job runs, with everything they import."""
    return PLAN.sources(*modules, "flutterfriction.io")


# A job depends on exactly the package modules it runs (its function's module and everything
# that imports, transitively): editing one science module reruns only the scenes using it.
SCENE_SOURCES = {
    n: job_sources(s.module, "flutterfriction.scenes", "flutterfriction.sources")
    for n, s in SCENES.items()
}
# ... and the jobs importing the rod's compiled kernels wait for them to be compiled once.
KERNELS = str(PKG / "models" / "rod_kernel.py")
SCENE_SOURCES = {
    n: files + (["results/benchmarks/kernels.json"] if KERNELS in files else [])
    for n, files in SCENE_SOURCES.items()
}
FIGURE_SOURCES = {
    f: job_sources(spec.module, "flutterfriction.plotting", "flutterfriction.sources")
    for f, (_, spec) in FIGURES.items()
}


def clear_interrupted_outputs(metadata=Path(".snakemake") / "incomplete"):
    """What `--rerun-incomplete` does, so that the README's one command resumes a run stopped
    by Ctrl-C or a kill: the outputs of jobs that did not finish are removed (they are rebuilt)
    and their markers dropped. (A workflow profile could set rerun-incomplete, but next to a
    top-level Snakefile Snakemake reads one only from profiles/default/, outside our layout.)
    Snakemake names a marker by the URL-safe base64 of the output's path."""
    import base64

    if not metadata.is_dir():
        return
    for marker in sorted(metadata.rglob("*")):
        if not marker.is_file():
            continue
        try:
            name = base64.urlsafe_b64decode(marker.name.encode()).decode()
        except (ValueError, UnicodeDecodeError):
            continue
        output = Path(name)
        if output.parts and output.parts[0] == "results":
            output.unlink(missing_ok=True)
            marker.unlink()
            print(f"removed {output}: its job was interrupted; it will be rebuilt", file=sys.stderr)


def may_clear_interrupted_outputs(locks=Path(".snakemake") / "locks"):
    """Only a real run of the main process, with no other run holding the directory: every
    Snakemake call reads this file, and clearing there removed the outputs of jobs still
    running (a dry run beside a run, a second run refused the lock, a cluster job's own
    Snakemake process; found by an outside audit). After a hard kill the README's recipe
    unlocks first, so the next run still resumes."""
    short = [a[1:] for a in sys.argv[1:] if a.startswith("-") and not a.startswith("--")]
    dry = any(
        a in ("--dry-run", "--dryrun", "--lint", "--summary", "--detailed-summary")
        for a in sys.argv[1:]
    ) or any(a.isalpha() and "n" in a for a in short)
    held = locks.is_dir() and any(locks.iterdir())
    return workflow.is_main_process and not dry and not held


def clear_paper_pdfs():
    """The quick preset draws no PDF: a paper run's PDFs left beside the quick PNGs would go
    stale as soon as a parameter changes (an outside audit took eq47.pdf of list 47 next to
    an eq47.png of another pendulum). Removed; the next paper run draws them again."""
    for pdf in [*Path("results/figures").glob("*.pdf"), Path(WORK_PRECISION_PDF)]:
        if pdf.is_file():
            pdf.unlink()
            print(f"removed {pdf}: the quick preset draws PNG only", file=sys.stderr)


def clear_temporary_files(root=Path("results")):
    """The temporary files of atomic writes (flutterfriction.io: ``.<name>.<random><suffix>``
    beside the output) that a killed job left behind (an outside audit found a 0-byte
    ``.fig07.png.10anujk6.png``): never mistaken for outputs, but litter."""
    for tmp in root.rglob(".*.*"):
        if tmp.is_file():
            tmp.unlink()
            print(f"removed {tmp}: a killed job's temporary file", file=sys.stderr)


WORK_PRECISION_PDF = "results/benchmarks/work_precision.pdf"
if may_clear_interrupted_outputs():
    clear_interrupted_outputs()
    clear_temporary_files()
    if DRAFT:
        clear_paper_pdfs()


# Functions of the rule files (Snakemake's lint wants functions and rules apart).
def sweep_parts(wildcards):
    if wildcards.scene not in SWEEP_SCENES:
        return []
    parts = gather.sweep(f"results/data/parts/{wildcards.scene}/{{scatteritem}}.json")
    # `--set-scatter sweep=N` bypasses the config's check of sweep_parts: the same range here
    if not 1 <= len(parts) <= 10000:
        raise ValueError(
            f"sweep parts (sweep_parts or --set-scatter sweep=N) must be in [1, 10000], "
            f"got {len(parts)}"
        )
    return parts


def benchmark_files(wildcards=None):
    return (
        expand("results/benchmarks/{scene}.solve.tsv", scene=SINGLE_SCENES)
        + expand("results/benchmarks/solve_{part}.tsv", part=BATCHES)
        + [
            f
            for s in SWEEP_SCENES
            for f in gather.sweep(f"results/benchmarks/{s}.part{{scatteritem}}.tsv")
        ]
        + expand("results/benchmarks/report_{nb}.tsv", nb=NOTEBOOK_REPORTS)
        + ["results/benchmarks/stress.tsv"]
        # the figures' jobs too: every job but this table's own, the report and the check
        + expand("results/benchmarks/plot_{figure}.tsv", figure=SINGLE_FIGURES)
        + expand("results/benchmarks/plot_{part}.tsv", part=FIGURE_BATCHES)
        + [
            f"results/benchmarks/{job}.tsv"
            for job in ("animate_pendulum_cycle", "animate_rod_cycle", "work_precision_figure")
        ]
    )


def solve_runtime(wildcards):
    """SLURM runtime [min] of a solve job: the slow scenes take 1-3 min here, the rest seconds
    (results/benchmarks/*.solve.tsv); a margin of 10x covers slower cluster nodes."""
    return 30 if wildcards.scene in SLOW_SCENES else 10


def scene_sources(wildcards):
    return SCENE_SOURCES[wildcards.scene]


def figure_sources(wildcards):
    return FIGURE_SOURCES[wildcards.scene]


def figure_data(wildcards):
    return f"results/data/{FIGURE_DATA[wildcards.scene]}.json"


def figure_timings(wildcards):
    return f"results/benchmarks/{FIGURE_DATA[wildcards.scene]}.timings.json"


def scene_compute(wildcards):
    """Import path of the scene's function: the job imports that module only."""
    return SCENES[wildcards.scene].compute


def scene_sweep(wildcards):
    return SCENES[wildcards.scene].sweep


def figure_plot(wildcards):
    return FIGURES[wildcards.scene][1].path


def scene_priority(wildcards):
    return 10 if wildcards.scene in SLOW_SCENES else 5


def batch_priority(part):
    """A batch holding a slow scene (the quick preset's limit-cycle batch: ~9 s, the longest
    job there) starts with the slow solvers, not after the cheap batches: started among them
    it ended the run with a serial tail of its figures and notebook (measured: 4.6 s later)."""
    return 10 if any(name in SLOW_SCENES for name in BATCHES[part]) else 5


def figure_caption(wildcards):
    return FIGURES[wildcards.scene][1].caption


def figure_part(wildcards):
    return FIGURES[wildcards.scene][0].part


def batch_sources(part):
    return sorted({f for n in BATCHES[part] for f in SCENE_SOURCES[n]})


def figure_batch_sources(part):
    return sorted({f for fig in FIGURE_BATCHES[part] for f in FIGURE_SOURCES[fig]})


def batch_figure_outputs(part):
    """The figures of one part's batch, each PNG in `snakemake --report` with its caption."""
    out = []
    for f in FIGURE_BATCHES[part]:
        # (not at the start of a line: Snakemake's parser takes `report` there for its directive)
        png = report(
            f"results/figures/{f}.png",
            caption="../report/batch_figure.rst",
            category="Figures",
            labels={"figure": f, "caption": FIGURES[f][1].caption},
        )
        out += [f"results/figures/{f}.{ext}" for ext in PDF]
        out += [png, f"results/checks/figures/{f}.json"]
    return out


#: Snakemake's default job rate limit (--max-jobs-per-timespan 100/1s) and the timespan [s] it
#: becomes here (see rate_limit_rounds_every).
DEFAULT_RATE_LIMIT, RATE_LIMIT_TIMESPAN = (100, 1), 10


def rate_limit_rounds_every(workflow):
    """Snakemake's job rate limit runs the scheduler again one timespan after every scheduling
    round, and each of those rounds arms its timer again: the rounds grow like jobs x seconds
    (3108 in a paper run's 43 jobs with the default 1 s, each reading the size of every ready
    job's inputs), 27-28 CPU-s of Snakemake's own process taken from the jobs on two cores
    (measured; 13-14 CPU-s with 10 s). The default limit's timespan becomes
    RATE_LIMIT_TIMESPAN: the same jobs are submitted (two cores never near 100 jobs in 10 s; a
    cluster profile's 100 in 10 s is no limit either). A limit given on the command line or in
    a profile is kept (only the default's value is changed). Called by onstart, after the
    scheduler took the limit and before it runs."""
    settings = getattr(workflow, "scheduling_settings", None)
    limit = getattr(settings, "max_jobs_per_timespan", None)
    if (getattr(limit, "max_jobs", None), getattr(limit, "timespan", None)) == DEFAULT_RATE_LIMIT:
        limit.timespan = RATE_LIMIT_TIMESPAN


def compile_package_bytecode(root):
    """Write the package's bytecode (``__pycache__``) once, before the jobs: where Python may
    not write it itself (``PYTHONDONTWRITEBYTECODE=1``, as on the machines of this kind),
    every job, notebook kernel and check compiled the modules it imports from source again
    (0.3 s for all of them; the paper run from clean 4 % faster, 3.4 CPU-s less: three pairs
    on 2026-12-06). Python reads a .pyc only while its source is unchanged, so an edited
    module is compiled from source as before until the next run writes it again. A tree
    that cannot be written is left as it is (compileall, quiet, never raises on a failed
    write). It writes into src/flutterfriction's __pycache__, where numba's cache of the
    rod's kernels already lives. Called by onstart: not in a dry or no-op run, nor in a
    cluster job's own Snakemake (spawned without hooks)."""
    import compileall

    compileall.compile_dir(str(root), quiet=2)


def stop_rate_limit_timers():
    """Snakemake's job rate limit (--max-jobs-per-timespan; its timespan here 10 s, see
    rate_limit_rounds_every) starts a timer thread at each scheduling round, not a daemon: the
    last one held the finished run for up to a timespan (measured 0.96 s after the check at
    1 s). Called by onsuccess/onerror, when nothing is
    left to schedule: stop them."""
    import threading

    for thread in threading.enumerate():
        if isinstance(thread, threading.Timer):
            thread.cancel()


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
