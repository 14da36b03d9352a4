"""The workflow's plan (what the Snakefile reads at every start) is the registry's, and its cache
is read only for the very configuration, sources and files it was worked out from."""

from __future__ import annotations

import copy
import json
import os
import shutil

import pytest
import yaml
from conftest import ROOT

from flutterfriction import workflow_plan as wp
from flutterfriction.registry import PARTS, SCENES
from flutterfriction.sources import import_path, module_sources

PKG = ROOT / "src" / "flutterfriction"


@pytest.fixture(scope="module")
def plan() -> wp.WorkflowPlan:
    return wp.build_plan(PKG)


@pytest.fixture
def in_repo(monkeypatch):
    """The workflow's files are read relative to the working directory, as in the Snakefile."""
    monkeypatch.chdir(ROOT)


@pytest.fixture(scope="module")
def config() -> dict:
    with open(ROOT / "workflow" / "config.yaml", encoding="utf-8") as fh:
        return yaml.safe_load(fh)


def test_the_plan_is_the_registry(plan):
    assert plan.parts == PARTS
    assert list(plan.scenes) == list(SCENES)
    for name, scene in SCENES.items():
        got = plan.scenes[name]
        assert (got.name, got.part, got.slow) == (scene.name, scene.part, scene.slow)
        assert got.compute == import_path(scene.compute)
        assert got.module == scene.compute.__module__
        assert got.sweep == (import_path(scene.sweep, scene.compute.__module__)
                             if scene.sweep else "")
        assert list(got.figures) == list(scene.figures)
        for f, spec in scene.figures.items():
            assert (got.figures[f].path, got.figures[f].caption) == (spec.path, spec.caption)
            assert got.figures[f].module == spec.module
    assert list(plan.figures()) == [f for s in SCENES.values() for f in s.figures]
    assert [s.name for s in plan.scenes_of("solids")] == [
        n for n, s in SCENES.items() if s.part == "solids"]


def test_the_plans_sources_are_module_sources_for_every_module(plan):
    assert len(plan.modules) == len(list(PKG.rglob("*.py")))
    for module in plan.modules:
        assert plan.sources(module) == module_sources([module], PKG), module
    pair = ("flutterfriction.scenes.rod", "flutterfriction.io")
    assert plan.sources(*pair) == module_sources(pair, PKG)
    with pytest.raises(ValueError, match="is not a module"):
        plan.sources("flutterfriction.no_such_module")


def test_the_plan_survives_its_json(plan):
    data = json.loads(json.dumps(plan.to_json()))
    assert wp.WorkflowPlan.from_json(data, PKG) == plan


def test_a_valid_configuration_is_worked_out_once(tmp_path, in_repo, config, monkeypatch):
    calls = []
    real = wp.configuration_problems
    monkeypatch.setattr(wp, "configuration_problems",
                        lambda *a: calls.append(a) or real(*a))
    files = ["workflow/config.yaml"]
    first, problems = wp.workflow_plan(config, files, PKG, cache=tmp_path)
    assert problems == [] and len(calls) == 1
    assert len(list(tmp_path.glob("plan-*.json"))) == 1
    again, problems = wp.workflow_plan(config, files, PKG, cache=tmp_path)
    assert problems == [] and len(calls) == 1  # read from the cache
    assert again == first == wp.build_plan(PKG)
    # another configuration (a --config override): worked out again, a second entry
    quick = {**config, "fidelity": "quick"}
    wp.workflow_plan(quick, files, PKG, cache=tmp_path)
    assert len(calls) == 2 and len(list(tmp_path.glob("plan-*.json"))) == 2


def test_a_bad_configuration_is_never_cached(tmp_path, in_repo, config):
    bad = copy.deepcopy(config)
    bad["sweep_parts"] = 0
    for _ in range(2):
        plan, problems = wp.workflow_plan(bad, ["workflow/config.yaml"], PKG, cache=tmp_path)
        assert plan is None
        assert "config: sweep_parts: 0 is less than the minimum of 1" in problems
    assert list(tmp_path.iterdir()) == []


def test_the_key_follows_every_input(tmp_path, in_repo, config):
    files = ["workflow/config.yaml"]
    key = wp.plan_key(config, files, PKG)
    assert key == wp.plan_key(copy.deepcopy(config), files, PKG)
    changed = copy.deepcopy(config)
    changed["scenes"]["eq48"]["pendulum"]["k1"] *= 1.5
    assert wp.plan_key(changed, files, PKG) != key
    # a config file's text (a key written twice is a problem its parsed values do not show)
    own = tmp_path / "own.yaml"
    own.write_text("fidelity: paper\n")
    with_own = wp.plan_key(config, [*files, str(own)], PKG)
    assert with_own != key
    own.write_text("fidelity: paper\nfidelity: paper\n")
    assert wp.plan_key(config, [*files, str(own)], PKG) != with_own
    # a package source file (a copy of the package as the jobs' root), by content, not time
    pkg = tmp_path / "flutterfriction"
    shutil.copytree(PKG, pkg, ignore=shutil.ignore_patterns("__pycache__"))
    copied = wp.plan_key(config, files, pkg)
    assert copied != key  # another root
    module = pkg / "analysis" / "acoustic.py"
    module.write_text(module.read_text() + "\n# an edit\n")
    assert wp.plan_key(config, files, pkg) != copied
    # a library's version
    versions = {n: wp._version(n) for n in wp.LIBRARIES}
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(wp, "_version", lambda n: versions[n] + ("x" if n == "scipy" else ""))
        assert wp.plan_key(config, files, PKG) != key
    assert wp.plan_key(config, files, PKG) == key


def test_the_key_follows_the_workflows_files(tmp_path, monkeypatch, config):
    """The reference, coverage and schema files are read by the check: part of the key."""
    shutil.copytree(ROOT / "workflow", tmp_path / "workflow",
                    ignore=shutil.ignore_patterns("scripts", "rules", "report", "envs",
                                                  "profiles"))
    monkeypatch.chdir(tmp_path)
    key = wp.plan_key(config, ["workflow/config.yaml"], PKG)
    for name in ("reference.yaml", "coverage.yaml", "schemas/config.schema.yaml",
                 "reference_parameters.json"):
        path = tmp_path / "workflow" / name
        original = path.read_text()
        path.write_text(original + "\n")
        assert wp.plan_key(config, ["workflow/config.yaml"], PKG) != key, name
        path.write_text(original)
    assert wp.plan_key(config, ["workflow/config.yaml"], PKG) == key


def test_an_unreadable_or_unwritable_cache_is_no_cache(tmp_path, in_repo, config):
    files = ["workflow/config.yaml"]
    key = wp.plan_key(config, files, PKG)
    (tmp_path / f"plan-{key}.json").write_text("{not json")
    plan, problems = wp.workflow_plan(config, files, PKG, cache=tmp_path)
    assert problems == [] and plan == wp.build_plan(PKG)
    assert json.loads((tmp_path / f"plan-{key}.json").read_text())["key"] == key  # rewritten
    blocked = tmp_path / "a_file"
    blocked.write_text("")
    plan, problems = wp.workflow_plan(config, files, PKG, cache=blocked / "cache")
    assert problems == [] and plan is not None
    assert not any(p.name.startswith(".plan-") for p in tmp_path.iterdir())


def test_the_cache_keeps_the_newest_entries(tmp_path, in_repo, config, monkeypatch):
    monkeypatch.setattr(wp, "configuration_problems", lambda *a: [])
    for k in range(wp.KEEP + 3):
        wp.workflow_plan({**config, "sweep_parts": k + 1}, ["workflow/config.yaml"], PKG,
                         cache=tmp_path)
    assert len(list(tmp_path.glob("plan-*.json"))) == wp.KEEP
    assert list(tmp_path.glob(".plan-*")) == []


def test_an_unhashable_configuration_is_checked_every_time(tmp_path, in_repo, config):
    odd = {**config, 1: "a key of another type"}
    assert wp.plan_key(odd, ["workflow/config.yaml"], PKG) is None
    plan, problems = wp.workflow_plan(odd, ["workflow/config.yaml"], PKG, cache=tmp_path)
    assert plan is None and problems  # the schema refuses it
    assert list(tmp_path.iterdir()) == []


def test_the_key_follows_the_schemas_beside_the_jobs_package(tmp_path, monkeypatch, config):
    """Some loaders read their schema beside the package (<checkout>/workflow/schemas), not
    under the working directory: in a setup where the two differ, both are in the key."""
    checkout = tmp_path / "checkout"
    shutil.copytree(PKG, checkout / "src" / "flutterfriction",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(ROOT / "workflow" / "schemas", checkout / "workflow" / "schemas")
    monkeypatch.chdir(ROOT)
    root = checkout / "src" / "flutterfriction"
    key = wp.plan_key(config, ["workflow/config.yaml"], root)
    schema = checkout / "workflow" / "schemas" / "reference.schema.yaml"
    schema.write_text(schema.read_text() + "\n")
    assert wp.plan_key(config, ["workflow/config.yaml"], root) != key


def test_a_configuration_with_keys_json_would_merge_is_not_cached(in_repo, config):
    assert wp.plan_key({**config, "cases": {1: "a"}}, ["workflow/config.yaml"], PKG) is None
    assert wp.plan_key({**config, "cases": {"1": "a"}}, ["workflow/config.yaml"], PKG)


def test_a_cache_hit_keeps_its_entry(tmp_path, in_repo, config, monkeypatch):
    """An entry read is marked used: the most recently used entries are kept."""
    monkeypatch.setattr(wp, "configuration_problems", lambda *a: [])
    files = ["workflow/config.yaml"]
    wp.workflow_plan(config, files, PKG, cache=tmp_path)
    first = tmp_path / f"plan-{wp.plan_key(config, files, PKG)}.json"
    os.utime(first, (0, 0))
    wp.workflow_plan(config, files, PKG, cache=tmp_path)
    assert first.stat().st_mtime > 0
    mask = os.umask(0)
    os.umask(mask)
    assert first.stat().st_mode & 0o777 == 0o666 & ~mask  # as any file the workflow writes


def test_a_scene_function_a_job_cannot_import_is_a_problem_line(tmp_path, in_repo, config,
                                                                 monkeypatch):
    from flutterfriction import registry

    monkeypatch.setattr(wp, "configuration_problems", lambda *a: [])
    odd = registry.Scene("odd", lambda p: {}, "rods")
    monkeypatch.setattr(registry, "SCENES", {**registry.SCENES, "odd": odd})
    plan, problems = wp.workflow_plan(config, ["workflow/config.yaml"], PKG, cache=tmp_path)
    assert plan is None and len(problems) == 1
    assert problems[0].startswith("registry: ") and "is not a module-level name" in problems[0]
    assert list(tmp_path.iterdir()) == []
