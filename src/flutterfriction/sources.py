"""The code a workflow job runs: a function by its import path, and the package's source files
it depends on (the modules it imports, transitively).

The workflow makes each job depend on exactly these files, so editing one science module
reruns only the scenes that use it (``.ci/rerun_only_changed.py`` checks it). The analysis is
static (``ast``) and conservative: every ``import`` statement counts, including those inside
functions (imported lazily on purpose, to keep a job's start-up cheap, but run all the same),
and importing ``a.b.c`` counts the ``__init__`` of ``a`` and ``a.b``, which Python executes.
"""

from __future__ import annotations

import ast
import importlib
import re
from collections.abc import Callable, Iterable
from functools import cache
from pathlib import Path
from typing import Any

PACKAGE = "flutterfriction"
ROOT = Path(__file__).resolve().parent


def module_file(name: str, root: Path = ROOT) -> Path | None:
    """The file of package module ``name`` (a module or a package's ``__init__``), if any."""
    parts = name.split(".")
    if parts[0] != PACKAGE:
        return None
    base = root.joinpath(*parts[1:])
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    return None


def _parents(name: str) -> list[str]:
    parts = name.split(".")
    return [".".join(parts[:k]) for k in range(1, len(parts) + 1)]


# An import statement on its own line(s): `import a.b, c` or `from x import y` (parenthesised
# names may span lines). Statements can be indented (inside functions), never share a line
# with other code in this package (ruff's E401/E701/E702 forbid it).
_IMPORT_LINE = re.compile(r"^[ \t]*(?:from[ \t]+[\w.]+[ \t]+import[ \t]+(?:\([^)]*\)|[^\n]*)"
                          r"|import[ \t]+[^\n]*)", re.M)


def _import_statements(text: str, filename: str) -> list[ast.stmt]:
    """The ``import`` statements of a module's source: the lines the pattern finds, parsed
    alone (~20x cheaper than parsing and walking the whole module, which the workflow's
    start-up would pay for every module of the package); the whole module's syntax tree when
    those lines do not parse alone (a docstring line that looks like an import). The lines
    found are a superset of the statements: never fewer dependencies (tested against the
    full syntax tree for every module)."""
    lines = [m.group(0).strip() for m in _IMPORT_LINE.finditer(text)]
    try:
        return list(ast.parse("\n".join(lines), filename).body)
    except SyntaxError:
        return [n for n in ast.walk(ast.parse(text, filename))
                if isinstance(n, ast.Import | ast.ImportFrom)]


@cache
def _imports(name: str, root: Path) -> frozenset[str]:
    """Package modules that module ``name`` imports directly (with their parent packages)."""
    path = module_file(name, root)
    if path is None:
        return frozenset()
    is_package = path.name == "__init__.py"
    found: set[str] = set()
    for node in _import_statements(path.read_text(encoding="utf-8"), str(path)):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:  # relative: resolve against this module's package
                here = name.split(".") if is_package else name.split(".")[:-1]
                base = ".".join(here[: len(here) - node.level + 1])
                module = f"{base}.{node.module}" if node.module else base
            else:
                module = node.module or ""
            # `from pkg import sub` imports the submodule `pkg.sub` when there is one
            targets = [module] + [f"{module}.{a.name}" for a in node.names]
        else:
            continue
        for target in targets:
            if module_file(target, root) is not None:
                found.update(p for p in _parents(target) if module_file(p, root) is not None)
    return frozenset(found)


def module_sources(modules: Iterable[str], root: Path = ROOT) -> list[str]:
    """Sorted source files of ``modules`` and of every package module they import,
    transitively (paths as ``root`` gives them).

    Parameters
    ----------
    modules
        Dotted names inside the package, e.g. ``"flutterfriction.scenes.rod"``.
    root
        The package directory (``src/flutterfriction`` of the checkout the workflow runs).
    """
    seen = import_closure(modules, lambda m: module_file(m, root) is not None,
                          lambda m: _imports(m, root), root)
    return sorted(str(module_file(m, root)) for m in seen)


def import_closure(modules: Iterable[str], known: Callable[[str], bool],
                   imports: Callable[[str], Iterable[str]], root: Path) -> set[str]:
    """``modules``, their parent packages and every package module they import, transitively:
    ``known(m)`` says whether ``m`` is a module of the package, ``imports(m)`` what it imports
    directly (from its file, or from a cached import graph:
    :meth:`flutterfriction.workflow_plan.WorkflowPlan.sources`)."""
    seen: set[str] = set()
    todo = []
    for m in modules:
        if not known(m):
            raise ValueError(f"{m!r} is not a module of {root}")
        todo += _parents(m)
    while todo:
        m = todo.pop()
        if m in seen or not known(m):
            continue
        seen.add(m)
        todo.extend(i for i in imports(m) if i not in seen)
    return seen


def import_path(obj: Any, module: str | None = None) -> str:
    """``"package.module:name"`` of a module-level function or object (``module``: where to
    look, by default the object's own module), for a job that imports only that module."""
    module = module or obj.__module__
    found = [k for k, v in vars(importlib.import_module(module)).items() if v is obj]
    if not found:
        raise ValueError(f"{obj!r} is not a module-level name of {module}")
    return f"{module}:{sorted(found)[0]}"


def resolve(path: str) -> Any:
    """The object at an :func:`import_path` (imports its module only)."""
    from flutterfriction.errors import ParameterError

    module, _, attr = path.partition(":")
    if not module.startswith(f"{PACKAGE}.") or not attr:
        raise ParameterError(f"not an import path of this package: {path!r}")
    return getattr(importlib.import_module(module), attr)
