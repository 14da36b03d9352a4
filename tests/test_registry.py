"""The scene registry is the one list of scenes: adding a scene is one entry plus its functions."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap

import pytest
from conftest import ROOT

from flutterfriction.registry import PARTS, SCENES, check_registry, figures
from flutterfriction.sources import import_path, module_sources, resolve


def test_the_registry_is_sound():
    assert check_registry() == []
    assert {s.part for s in SCENES.values()} == set(PARTS)


def test_a_job_finds_its_function_by_import_path():
    for scene in SCENES.values():
        assert resolve(import_path(scene.compute)) is scene.compute
        if scene.sweep is not None:
            assert resolve(import_path(scene.sweep, scene.compute.__module__)) is scene.sweep
    for _, spec in figures().values():
        assert resolve(import_path(spec.plot)) is spec.plot


def test_a_scene_depends_on_the_modules_it_imports_and_no_others():
    pkg = ROOT / "src" / "flutterfriction"
    solids = module_sources([SCENES["fig22"].compute.__module__], pkg)
    cycles = module_sources([SCENES["beck_hopf"].compute.__module__], pkg)
    assert str(pkg / "analysis" / "acoustic.py") in solids
    assert str(pkg / "analysis" / "acoustic.py") not in cycles
    assert str(pkg / "analysis" / "rod_cycles.py") in cycles
    assert str(pkg / "scenes" / "__init__.py") in cycles  # a parent package runs too
    # a solve job does not depend on the plotting code, nor a plot job on the solvers
    assert not any("/plotting/" in f for f in cycles)
    plot = module_sources([figures()["fig11"][1].plot.__module__], pkg)
    assert not any("/analysis/" in f for f in plot)


TOY_SCENE = '''
def compute(params):
    """A toy scene: the data of one straight line."""
    n = int(params.get("n_points", 5))
    return {"x": list(range(n)), "quantities": {}}
'''
TOY_PLOT = '''
from matplotlib.figure import Figure


def plot(data):
    fig = Figure(figsize=(3, 2))
    ax = fig.add_subplot()
    ax.plot(data["x"], data["x"])
    ax.set_xlabel("x [-]")
    ax.set_ylabel("y [-]")
    return fig
'''
TOY_ENTRY = '''    Scene("toy", _toy.compute, "rods",
          {"toy": FigureSpec(_toy_plots.plot, "A toy figure.")}),
'''


@pytest.mark.slow
def test_adding_a_scene_is_one_registry_entry(tmp_path):
    """A copy of the project gets a toy scene: its two modules plus one registry entry (no
    workflow file, no config, no report layout edited). The workflow plans its solve and plot
    jobs as part of the default target, builds them, and the report lists its figure."""
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
    for part in ("src", "workflow", "notebooks"):
        shutil.copytree(ROOT / part, tmp_path / part, ignore=ignore)
    shutil.copy(ROOT / "Snakefile", tmp_path / "Snakefile")
    pkg = tmp_path / "src" / "flutterfriction"
    (pkg / "scenes" / "toy.py").write_text(TOY_SCENE)
    (pkg / "plotting" / "toy.py").write_text(TOY_PLOT)
    registry = pkg / "registry.py"
    text = registry.read_text()
    text = text.replace("from flutterfriction.scenes.sweep import Sweep\n",
                        "from flutterfriction.scenes.sweep import Sweep\n"
                        "from flutterfriction.scenes import toy as _toy\n"
                        "from flutterfriction.plotting import toy as _toy_plots\n")
    marker = "]\n\n#: Scene name"
    assert marker in text
    registry.write_text(text.replace(marker, TOY_ENTRY + marker))

    env = {**os.environ, "PYTHONPATH": str(tmp_path / "src")}
    snakemake = [sys.executable, "-m", "snakemake", "--quiet", "rules"]
    plan = subprocess.run([*snakemake, "-n"], cwd=tmp_path, env=env, capture_output=True,
                          text=True)
    assert plan.returncode == 0, plan.stderr[-2000:]
    run = subprocess.run([*snakemake, "-j1", "results/figures/toy.png"], cwd=tmp_path, env=env,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-2000:]
    assert (tmp_path / "results" / "data" / "toy.json").is_file()
    assert (tmp_path / "results" / "figures" / "toy.png").stat().st_size > 1000
    probe = textwrap.dedent("""
        from flutterfriction.report import layout_figures, load_layout
        print(layout_figures(load_layout("workflow/report.yaml")))
    """)
    shown = subprocess.run([sys.executable, "-c", probe], cwd=tmp_path, env=env,
                           capture_output=True, text=True, check=True).stdout
    assert "'toy'" in shown


def test_the_import_scan_finds_every_import_statement_of_every_module():
    """The workflow's dependency scan reads import statements from their lines (fast); on every
    module of the package it finds exactly the statements of the full syntax tree."""
    import ast

    from flutterfriction.sources import _import_statements

    for path in sorted((ROOT / "src" / "flutterfriction").rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        full = sorted(ast.dump(n) for n in ast.walk(ast.parse(text))
                      if isinstance(n, ast.Import | ast.ImportFrom))
        assert sorted(ast.dump(n) for n in _import_statements(text, str(path))) == full, path


def test_the_registry_does_not_import_the_plotting_code():
    """Reading the registry (every `snakemake` call does) imports no matplotlib; a figure's
    plot function is imported when drawn, and check_registry finds a missing one."""
    code = ("import sys; from flutterfriction.registry import check_registry; "
            "assert not check_registry(); print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "False"
    from flutterfriction.registry import FigureSpec, Scene

    broken = Scene("toy", lambda p: {}, "ziegler",
                   {"toy": FigureSpec("flutterfriction.plotting.rod:no_such_plot", "caption")})
    assert check_registry({"toy": broken}) == [
        "figure 'toy': a plot function and a caption are required"]



def test_the_configuration_check_loads_no_compiled_kernels():
    """Every `snakemake` call checks the whole configuration before any job; the rod cycle's
    load check linearises the nonlinear rod, which needs no numba (importing it cost ~0.25 s
    of every call, no-op included, before the first job)."""
    code = ("import sys, yaml; from flutterfriction.config import validate_config; "
            "from flutterfriction.registry import SCENES; "
            "cfg = yaml.safe_load(open('workflow/config.yaml')); "
            "assert not validate_config(cfg, 'workflow/schemas/config.schema.yaml', "
            "scenes=SCENES); print('numba' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout
    assert out.strip() == "False"

@pytest.mark.slow  # two `snakemake -n` plans (~3 s each)
def test_the_longest_jobs_start_first_in_both_presets(tmp_path):
    """Snakemake runs the highest priority first: every solve job holding a slow scene (the
    quick preset batches them with the cheap ones of their part) starts with the slow solvers,
    before the cheap solves, and every figure job (batch or single) before the notebooks that
    wait for it. Measured: the quick preset's limit-cycle batch (~9 s) started among the cheap
    batches ended the run with a 4.6 s serial tail (its figures, its notebook)."""
    from flutterfriction.registry import scenes_of

    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
    for part in ("src", "workflow", "notebooks"):
        shutil.copytree(ROOT / part, tmp_path / part, ignore=ignore)
    shutil.copy(ROOT / "Snakefile", tmp_path / "Snakefile")
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "src")}
    slow = {s.name for s in SCENES.values() if s.slow}
    for preset in ("quick", "paper"):
        plan = subprocess.run([sys.executable, "-m", "snakemake", "-n", "--config",
                               f"fidelity={preset}"], cwd=tmp_path, env=env,
                              capture_output=True, text=True)
        assert plan.returncode == 0, plan.stderr[-2000:]
        jobs = [(block.split(":", 1)[0].strip(), block) for block in
                plan.stdout.split("\nrule ")[1:]]
        priority = {}
        for rule, block in jobs:
            line = next((x for x in block.splitlines() if x.strip().startswith("priority:")),
                        "priority: 0")
            priority.setdefault(rule, set()).add(float(line.split(":")[1]))
        for part in PARTS:
            batch = priority.get(f"solve_{part}")
            if batch is None:
                continue
            holds_slow = preset == "quick" and any(s.name in slow for s in scenes_of(part))
            assert batch == ({10} if holds_slow else {5}), (preset, part, batch)
        notebook = max(priority["notebook"])
        assert all(min(p) > notebook for r, p in priority.items() if r.startswith("plot")), \
            (preset, priority)
        # the notebooks longest first (one priority each), the figure batches before the
        # one-figure jobs (an arbitrary order among equals left a long job for last)
        assert len(priority["notebook"]) == len(PARTS), (preset, priority["notebook"])
        singles = max(priority.get("plot", {3.0}))
        assert all(min(p) > singles for r, p in priority.items()
                   if r.startswith("plot_") and r != "plot"), (preset, priority)
