"""What the Snakefile reads at every start, as plain data, and the check of the configuration:
worked out once, then read from a cache whose key hashes everything they depend on.

Every ``snakemake`` call (a run, a no-op rerun, a dry run, each cluster job's own Snakemake)
parses the Snakefile, which needs the scenes' names, parts, figures and the package files each
job imports (:mod:`flutterfriction.registry`, :mod:`flutterfriction.sources`), and refuses a bad
configuration before any job (the schema, the models' ranges, each scene's own check, the
reference and coverage files). Worked out from scratch, these import every scene's solvers
(scipy) and solve small problems: 2.5-3 s of a 6 s no-op rerun here (measured), while 7ecfb71,
which checked only the schema, took 3.5 s in all.

What they give is a function of the package's source files, the workflow's configuration,
schema, reference and coverage files, the configuration as Snakemake resolved it (config
files and ``--config``), and the versions of Python and of the libraries the checks compute
with. The key hashes all of them (file contents, not times), so any edit, a new ``--config``
or another library misses the cache and everything is worked out anew. Only a valid
configuration is cached: a bad one is checked again at every call and says why.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any

#: Bumped when the cached data's shape changes (older entries are then never read).
CACHE_FORMAT = 1
#: The libraries whose versions enter the key: the configuration's checks compute with them.
LIBRARIES = ("numpy", "scipy", "numba", "llvmlite", "scikit-fem", "sympy", "mpmath",
             "jsonschema", "jsonschema-specifications", "referencing", "PyYAML")
#: How many entries the cache keeps (the newest; one per configuration and source state).
KEEP = 8
#: The workflow's files the configuration's check reads (relative to the working directory).
WORKFLOW_FILES = ("workflow/*.yaml", "workflow/*.json", "workflow/schemas/*.yaml")


@dataclass(frozen=True)
class PlanFigure:
    """One figure: its plot function's import path (``"module:function"``) and its caption."""

    path: str
    caption: str

    @property
    def module(self) -> str:
        return self.path.partition(":")[0]


@dataclass(frozen=True)
class PlanScene:
    """One scene as the rules need it: import paths instead of functions."""

    name: str
    part: str
    compute: str
    sweep: str = ""
    slow: bool = False
    figures: dict[str, PlanFigure] = field(default_factory=dict)

    @property
    def module(self) -> str:
        """The module of the scene's function (its job imports that module only)."""
        return self.compute.partition(":")[0]


@dataclass(frozen=True)
class WorkflowPlan:
    """The registry's scenes and the package's import graph, as plain data.

    Attributes
    ----------
    parts
        The chapter's parts, in order (:data:`flutterfriction.registry.PARTS`).
    scenes
        Scene name -> :class:`PlanScene`, in the chapter's order.
    modules
        Package module -> (its file relative to ``root``, the package modules it imports
        directly, with their parent packages): :func:`flutterfriction.sources.module_sources`
        without reading the files again.
    root
        The package directory the files are under.
    """

    parts: tuple[str, ...]
    scenes: dict[str, PlanScene]
    modules: dict[str, tuple[str, tuple[str, ...]]]
    root: Path

    def scenes_of(self, part: str) -> list[PlanScene]:
        """The scenes of one chapter part."""
        return [s for s in self.scenes.values() if s.part == part]

    def figures(self) -> dict[str, tuple[PlanScene, PlanFigure]]:
        """Figure name -> (the scene whose data it draws, the figure), in the chapter's order."""
        return {f: (s, spec) for s in self.scenes.values() for f, spec in s.figures.items()}

    def sources(self, *modules: str) -> list[str]:
        """The same list as :func:`flutterfriction.sources.module_sources` of ``modules``:
        their files and those of every package module they import, transitively."""
        from flutterfriction.sources import import_closure

        seen = import_closure(modules, self.modules.__contains__,
                              lambda m: self.modules[m][1], self.root)
        return sorted(str(self.root / self.modules[m][0]) for m in seen)

    def to_json(self) -> dict[str, Any]:
        return {"parts": list(self.parts),
                "scenes": {n: asdict(s) for n, s in self.scenes.items()},
                "modules": {m: [f, list(i)] for m, (f, i) in self.modules.items()}}

    @classmethod
    def from_json(cls, data: Mapping[str, Any], root: Path) -> WorkflowPlan:
        scenes = {n: PlanScene(**{**s, "figures": {f: PlanFigure(**v)
                                                   for f, v in s["figures"].items()}})
                  for n, s in data["scenes"].items()}
        modules = {m: (f, tuple(i)) for m, (f, i) in data["modules"].items()}
        return cls(tuple(data["parts"]), scenes, modules, Path(root))


def build_plan(root: Path) -> WorkflowPlan:
    """The plan from the registry itself (imports every scene's module) and the import
    statements of every module under ``root``."""
    from flutterfriction.registry import PARTS, SCENES
    from flutterfriction.sources import PACKAGE, _imports, import_path, module_file

    root = Path(root)
    modules = {}
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).with_suffix("")
        parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
        name = ".".join((PACKAGE, *parts))
        if module_file(name, root) == path:  # not a stray file beside a package of its name
            modules[name] = (path.relative_to(root).as_posix(),
                             tuple(sorted(_imports(name, root))))
    scenes = {
        n: PlanScene(
            name=n, part=s.part, compute=import_path(s.compute),
            sweep=import_path(s.sweep, s.compute.__module__) if s.sweep else "",
            slow=s.slow,
            figures={f: PlanFigure(spec.path, spec.caption) for f, spec in s.figures.items()})
        for n, s in SCENES.items()
    }
    return WorkflowPlan(tuple(PARTS), scenes, modules, root)


def configuration_problems(config: Mapping[str, Any], configfiles: Iterable[str]) -> list[str]:
    """Every problem of the workflow's configuration, one line each (empty when valid): the
    registry; a key written twice in any config file (Snakemake keeps the last silently); the
    configuration, every preset as it resolves (:func:`flutterfriction.config.validate_config`,
    with each scene's own check); the reference and coverage files, which the last jobs read.
    Paths are relative to the workflow's directory (the working directory)."""
    import yaml

    from flutterfriction.config import validate_config, yaml_file_problems
    from flutterfriction.errors import ParameterError
    from flutterfriction.reference import parameters_file_problems, reference_file_problems
    from flutterfriction.registry import SCENES, check_registry
    from flutterfriction.report import coverage_problems, load_coverage, registry_figure_scenes

    problems = (
        check_registry()
        + [line for path in dict.fromkeys(map(str, configfiles))
           for line in yaml_file_problems(path)]
        + validate_config(dict(config), "workflow/schemas/config.schema.yaml", scenes=SCENES)
        + reference_file_problems("workflow/reference.yaml", scenes=SCENES)
        + parameters_file_problems(scenes=SCENES)
        + yaml_file_problems("workflow/coverage.yaml")
    )
    try:
        entries = load_coverage("workflow/coverage.yaml")
    except (ParameterError, OSError, yaml.YAMLError) as exc:
        lines = str(exc).splitlines()
        problems += [f"workflow/coverage.yaml: {line.strip()}" for line in lines[1:] or lines]
    else:  # what it claims of the registry, at the start, not at the final check
        problems += coverage_problems(entries, registry_figure_scenes())
    return problems


def _str_keys(value: Any) -> bool:
    """Whether every mapping key in ``value`` is a string."""
    if isinstance(value, Mapping):
        return all(isinstance(k, str) and _str_keys(v) for k, v in value.items())
    if isinstance(value, list | tuple):
        return all(_str_keys(v) for v in value)
    return True


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "-"


def plan_key(config: Mapping[str, Any], configfiles: Iterable[str], root: Path) -> str | None:
    """The cache key: a hash of everything the plan and the configuration's check depend on
    (see the module's docstring); None when the configuration cannot be written as JSON (it
    is then checked every time)."""
    import flutterfriction

    if not _str_keys(config):  # JSON writes the key 1 as "1": no cache for such a config
        return None
    try:
        resolved = json.dumps(config, sort_keys=True, allow_nan=True,
                              default=lambda o: f"<{type(o).__qualname__}> {o!r}")
    except (TypeError, ValueError):
        return None
    # the jobs' package and the one imported here (the same but in an unusual setup)
    packages = dict.fromkeys([Path(root).resolve(),
                              Path(flutterfriction.__file__).parent.resolve()])
    files = [p for pkg in packages for p in sorted(pkg.rglob("*.py"))]
    # the workflow's files where the check reads them: the working directory's, and the
    # schemas some loaders find beside the package (<checkout>/workflow/schemas)
    for base in dict.fromkeys([Path.cwd(), *(pkg.parents[1] for pkg in packages)]):
        files += [p for pattern in WORKFLOW_FILES for p in sorted(base.glob(pattern))]
    files += [Path(p) for p in dict.fromkeys(map(str, configfiles))]
    h = hashlib.sha256()
    for item in (str(CACHE_FORMAT), sys.version, *map(str, packages), resolved,
                 *(f"{n}={_version(n)}" for n in LIBRARIES)):
        h.update(item.encode() + b"\0")
    for path in files:
        h.update(str(path).encode() + b"\0")
        try:
            h.update(path.read_bytes())
        except OSError:
            h.update(b"\0missing\0")
        h.update(b"\0")
    return h.hexdigest()


def workflow_plan(config: Mapping[str, Any], configfiles: Iterable[str], root: Path,
                  cache: Path | None = Path(".snakemake") / "flutterfriction"
                  ) -> tuple[WorkflowPlan | None, list[str]]:
    """The plan and the configuration's problems: from the cache when this configuration, in
    this state of the sources, was found valid before; else worked out (and cached if valid).

    Parameters
    ----------
    config
        The configuration as Snakemake resolved it (before parameter lists are expanded).
    configfiles
        The config files Snakemake read (their text is checked for keys written twice).
    root
        The package directory the jobs' source files are listed under.
    cache
        The cache's directory (None: no cache).

    Returns
    -------
    plan, problems
        ``plan`` is None when there are problems.
    """
    configfiles = list(configfiles)
    key = plan_key(config, configfiles, root) if cache is not None else None
    entry = Path(cache) / f"plan-{key}.json" if key else None
    if entry is not None:
        try:
            data = json.loads(entry.read_text(encoding="utf-8"))
            if data.get("key") == key:
                plan = WorkflowPlan.from_json(data["plan"], root)
                with contextlib.suppress(OSError):
                    os.utime(entry)  # used: kept before entries written since
                return plan, []
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            pass  # no entry, or an unreadable one: worked out anew
    problems = configuration_problems(config, configfiles)
    if problems:
        return None, problems
    try:
        plan = build_plan(root)
    except ValueError as exc:  # a scene's function that a job cannot import by name
        return None, [f"registry: {exc}"]
    if entry is not None:
        _store(entry, {"key": key, "plan": plan.to_json()})
    return plan, []


def _store(entry: Path, data: dict[str, Any]) -> None:
    """Write one entry atomically, readable as any file the workflow writes (concurrent
    Snakemake processes on a cluster may write the same one), and keep the :data:`KEEP` most
    recently used; a cache that cannot be written is no cache."""
    from flutterfriction.io import atomic_path

    try:
        with atomic_path(entry) as tmp, open(tmp, "w", encoding="utf-8") as fh:
            json.dump(data, fh)
        old = sorted(entry.parent.glob("plan-*.json"), key=lambda p: p.stat().st_mtime)
        for p in old[:-KEEP]:
            p.unlink(missing_ok=True)
    except OSError:
        pass
