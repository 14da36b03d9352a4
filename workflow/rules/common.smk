# Helpers shared by the rule files.
import sys
from pathlib import Path

from flutterfriction.config import scene_params

PKG = Path(workflow.basedir) / "src" / "flutterfriction"


def package_sources(*subpackages):
    """Source files a rule depends on: editing the science reruns exactly the rules using it."""
    files = []
    for sub in subpackages:
        path = PKG / sub
        files += sorted(str(p) for p in path.rglob("*.py")) if path.is_dir() else [str(path)]
    return files


SOLVER_SOURCES = package_sources(
    "models", "analysis", "closed_forms", "scenes", "errors.py", "io.py", "config.py")
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
            print(f"removed {output}: its job was interrupted; it will be rebuilt",
                  file=sys.stderr)


clear_interrupted_outputs()
