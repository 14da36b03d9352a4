# Helpers shared by the rule files.
import sys
from pathlib import Path

from flutterfriction.config import scene_params

PKG = Path(workflow.basedir) / "src" / "flutterfriction"


def package_sources(*subpackages):
    """Source files a job depends on: editing the science reruns exactly the jobs using it."""
    files = []
    for sub in subpackages:
        path = PKG / sub
        files += sorted(str(p) for p in path.rglob("*.py")) if path.is_dir() else [str(path)]
    return files


SOLVER_SOURCES = package_sources(
    "models", "analysis", "closed_forms", "scenes", "errors.py", "io.py", "config.py"
)
PLOT_SOURCES = package_sources("plotting")


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


clear_interrupted_outputs()


# Functions of the rule files (Snakemake's lint wants functions and rules apart).
def sweep_parts(wildcards):
    if wildcards.scene not in SWEEP_SCENES:
        return []
    n = config.get("sweep_parts", 2)
    return [f"results/data/parts/{wildcards.scene}/{k}-of-{n}.json" for k in range(n)]


def benchmark_files(wildcards=None):
    n = config.get("sweep_parts", 2)
    return (
        expand("results/benchmarks/{scene}.solve.tsv", scene=ALL_SCENES)
        + [f"results/benchmarks/{s}.part{k}-of-{n}.tsv" for s in SWEEP_SCENES for k in range(n)]
        + expand("results/benchmarks/report_{nb}.tsv", nb=NOTEBOOK_REPORTS)
        + ["results/benchmarks/stress.tsv"]
    )


def solve_runtime(wildcards):
    """SLURM runtime [min] of a solve job: the slow scenes take 1-3 min here, the rest seconds
    (results/benchmarks/*.solve.tsv); a margin of 10x covers slower cluster nodes."""
    return 30 if wildcards.scene in SLOW_SCENES else 10
