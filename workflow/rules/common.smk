# Helpers shared by the rule files.
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
