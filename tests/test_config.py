"""workflow/config.yaml and its schema: what the workflow accepts and what it rejects."""

from __future__ import annotations

import copy

import jsonschema
import pytest
import yaml
from conftest import ROOT

from flutterfriction.config import load_config, scene_params, validate_config
from flutterfriction.errors import ParameterError
from flutterfriction.registry import SCENES, build_scene


@pytest.fixture(scope="module")
def config():
    return load_config(ROOT / "workflow" / "config.yaml")


@pytest.fixture(scope="module")
def schema():
    return yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())


def test_shipped_config_is_valid(config, schema):
    jsonschema.validate(config, schema)
    assert set(config["scenes"]) == set(SCENES)


@pytest.mark.parametrize(("path", "value", "match"), [
    (("scenes", "eq47", "pendulum", "m1"), -0.5, "-0.5"),
    (("scenes", "eq47", "pendulum", "k2"), 0.0, "0.0"),
    (("scenes", "eq47", "pendulum", "mass"), 1.0, "mass"),
    (("scenes", "eq47", "n_pts"), 10, "n_pts"),
    (("scenes", "fig04", "cases", "flutter", "duration"), -1.0, "-1.0"),
    (("fidelity",), "draft", "draft"),
    (("colour",), "red", "colour"),
])
def test_schema_rejects_bad_config(config, schema, path, value, match):
    bad = copy.deepcopy(config)
    node = bad
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    with pytest.raises(jsonschema.ValidationError, match=match):
        jsonschema.validate(bad, schema)


def test_fidelity_preset_overrides_only_existing_keys(config):
    quick = {**config, "fidelity": "quick"}
    n_quick = config["fidelity_presets"]["quick"]["n_points"]
    assert scene_params(quick, "eq47")["n_points"] == n_quick
    assert "n_points" not in scene_params(quick, "fig04")


def test_a_scenes_own_value_is_what_the_paper_run_uses(config):
    """The paper preset overrides nothing: a scene's section means what it says."""
    edited = copy.deepcopy(config)
    edited["scenes"]["eq25"]["n_points"] = 101
    assert scene_params(edited, "eq25")["n_points"] == 101
    assert scene_params(edited, "eq46")["n_points"] == config["scenes"]["eq46"]["n_points"]


def test_a_section_naming_no_registered_scene_is_refused(config):
    bad = copy.deepcopy(config)
    bad["scenes"]["eq99"] = {}
    problems = validate_config(bad, SCHEMA_PATH, scenes=SCENES)
    assert any("scenes.eq99: no such scene" in p for p in problems)


def test_scene_builders_reject_unknown_parameters(config):
    params = {**scene_params(config, "eq47"), "n_pts": 5}
    with pytest.raises(ParameterError, match="n_pts"):
        build_scene("eq47", params)
    with pytest.raises(ParameterError, match="unknown scene"):
        build_scene("eq99", {})


def test_load_config_rejects_unknown_top_level_key(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text("fidelity: paper\nfidelity_presets: {}\nscenes: {}\nextra: 1\n")
    with pytest.raises(ParameterError, match="extra"):
        load_config(path)


def test_quick_preset_coarsens_one_scene_only(config):
    quick = dict(config, fidelity="quick")
    coarse = config["fidelity_presets"]["quick"]["scenes"]["beck_limit_cycle"]["meshes"]
    fine = config["scenes"]["beck_limit_cycle"]["meshes"]
    assert coarse != fine
    assert scene_params(quick, "beck_limit_cycle")["meshes"] == coarse
    assert scene_params(config, "beck_limit_cycle")["meshes"] == fine
    # beck_linearisation also has 'meshes', but the override names beck_limit_cycle only
    assert scene_params(quick, "beck_linearisation")["meshes"] == \
        config["scenes"]["beck_linearisation"]["meshes"]


@pytest.mark.parametrize("over, match", [({"no_such_scene": {"x": 1}}, "unknown scene"),
                                         ({"eq46": {"meshes": [1]}}, "not parameters")])
def test_preset_overrides_must_name_real_scenes_and_keys(tmp_path, config, over, match):
    bad = dict(config)
    bad["fidelity_presets"] = {**config["fidelity_presets"],
                               "quick": {**config["fidelity_presets"]["quick"], "scenes": over}}
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(bad))
    with pytest.raises(ParameterError, match=match):
        load_config(path)


SCHEMA_PATH = ROOT / "workflow" / "schemas" / "config.schema.yaml"


def _with(config, path, value):
    bad = copy.deepcopy(config)
    node = bad
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return bad


def test_validate_config_accepts_the_shipped_config(config):
    from flutterfriction.config import validate_config

    assert validate_config(config, SCHEMA_PATH, scenes=SCENES) == []


@pytest.mark.parametrize(("path", "value", "match"), [
    # a misspelled per-scene preset override (was dropped silently: paper settings in quick)
    (("fidelity_presets", "quick", "scenes", "beck_hopf", "n_elemnts"), 3, "n_elemnts"),
    # a preset override outside the scene's range (checked as the preset resolves it)
    (("fidelity_presets", "quick", "scenes", "beck_hopf", "n_elements"), -3,
     "fidelity quick.*beck_hopf.n_elements"),
    (("fidelity_presets", "quick", "floquet_evry"), 3, "floquet_evry"),
    # cross-field geometry, caught before any job
    (("scenes", "fig02", "pendulum", "d"), 5.0, "fig02.pendulum: d must lie on rod AB"),
    (("scenes", "fig02", "pendulum", "h"), 5.0, "fig02.pendulum: h"),
    (("scenes", "acoustic_eigenvalues", "g_min"), 1e9, "g_min: must be < g_max"),
    # YAML's .nan and .inf pass a JSON schema's 'number'
    (("scenes", "fig02", "pendulum", "m1"), float("nan"), "m1: must be a finite number"),
    (("scenes", "beck_hopf", "A_max"), float("inf"), "A_max"),
    (("sweep_parts",), 0, "sweep_parts"),
    # a viscous pendulum in the undamped scenes (computed as undamped; an outside audit)
    (("scenes", "eq47", "pendulum"), "list47_viscous", "eq47.pendulum: c1 = c2 = 0 here"),
    (("scenes", "eq25", "pendulum", "c2"), 0.1, "eq25.pendulum: c1 = c2 = 0 here.*c2 = 0.1"),
])
def test_validate_config_names_the_key(config, path, value, match):
    from flutterfriction.config import validate_config

    problems = validate_config(_with(config, path, value), SCHEMA_PATH)
    assert problems and any(__import__("re").search(match, p) for p in problems), problems


@pytest.mark.parametrize(("path", "value", "match"), [
    (("scenes", "errata_solids", "Q"), [1.0, -0.5, -0.5, 0.0, 0.0, 0.8],
     "errata_solids: P, Q, n: this case has no flutter interval"),
    (("scenes", "acoustic_eigenvalues", "g_max"), 1e-3,
     "acoustic_eigenvalues: g_min, g_max: .* must contain the flutter interval"),
    (("scenes", "flutter_map", "anisotropy", "sigma"), [1.0, 1.0, 1.0],
     "flutter_map: sigma must have a non-zero deviator"),
    (("scenes", "localization_directions", "mu_f"), -5.0,
     r"localization_directions: mu_f must lie in \[0, sqrt3"),
    (("scenes", "localization_directions", "beta"), 1e300, "localization_directions: beta"),
    (("scenes", "flutter_map", "anisotropy", "eps_values"), [0.0, 100.0],
     "eps = 100 makes the elasticity E0 \\+ eps T not positive definite"),
])
def test_scene_checks_refuse_cases_their_jobs_fail_on(config, path, value, match):
    """The solids' cases refused before any job, naming the keys (an outside audit: each
    passed the dry run and failed in its job, two with a traceback)."""
    problems = validate_config(_with(config, path, value), SCHEMA_PATH, scenes=SCENES)
    assert problems and any(__import__("re").search(match, p) for p in problems), problems
    # one short line per problem, never a schema dump
    assert all("\n" not in p and len(p) < 400 for p in problems)


def test_unknown_key_is_one_line(config):
    from flutterfriction.config import validate_config

    problems = validate_config(_with(config, ("scenes", "eq25", "n_pionts"), 3), SCHEMA_PATH)
    assert len(problems) == 1 and "n_pionts" in problems[0]


def test_the_chapters_lists_as_the_chapter_states_them():
    from flutterfriction.parameters import LIST_47, LIST_119, SEC_29

    # list (47): l = 3d = 3h = 100 mm, m1 = 12 m2 = 4 m3 = 552 g, k1 = k2 = 0.189 N m
    assert LIST_47["l1"] == LIST_47["l2"] == 0.1
    assert 3 * LIST_47["d"] == pytest.approx(0.1, rel=1e-15) and LIST_47["h"] == LIST_47["d"]
    assert LIST_47["m1"] == pytest.approx(12 * LIST_47["m2"]) == pytest.approx(4 * LIST_47["m3"])
    assert LIST_47["m1"] == 0.552 and LIST_47["k1"] == LIST_47["k2"] == 0.189
    # list (119): l = 0.350 m, rho = 0.0546 kg/m, B = 0.0332 N m^2, D = 7.078e-6 N m^2 s
    assert dict(LIST_119) == {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 7.078e-6}
    assert SEC_29["d"] == SEC_29["l1"] and SEC_29["m3"] == 0.0 and SEC_29["c1"] == 0.006


def test_the_config_names_the_lists_and_an_unknown_name_is_refused(config):
    from flutterfriction.parameters import LIST_119

    assert config["scenes"]["fig11"]["rod"] == dict(LIST_119)  # `rod: list119` resolved
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["fig11"]["rod"] = "list911"
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert problems == [problems[0]] and "scenes.fig11.rod: unknown parameter list 'list911'" \
        in problems[0]
    raw["scenes"]["fig11"]["rod"] = "list47"  # a pendulum's list where a rod's is expected
    assert "unknown parameter list 'list47'" in validate_config(raw, SCHEMA_PATH)[0]


@pytest.mark.parametrize(("scene", "key", "value", "match"), [
    ("eq25", "n_points", 101.0, "101.0 is not of type 'integer'"),
    ("fig13", "load_factor", 0.5, "fig13.load_factor: 0.5 is less than or equal to the min"),
    ("fig11", "P_N", -5.5, "fig11.P_N: -5.5 is less than or equal to the minimum of 0"),
    ("beck_limit_cycle", "meshes", [16, 8, 4], "meshes: must be strictly increasing"),
    ("rod_fe_convergence", "elements", [4, 4, 4], "elements: must be strictly increasing"),
    ("elastica", "part", [0.75, 0.3], "part: must be strictly increasing"),
    ("acoustic_eigenvalues", "n", [0, 0, 0], "n: must be a non-zero direction"),
    # a second outside audit: each of these ended in a traceback in its job's log
    ("acoustic_eigenvalues", "lam", -5.0, "acoustic_eigenvalues: needs mu > 0 and -2/3 < lam/mu"),
    ("acoustic_eigenvalues", "lam", 1e9, "acoustic_eigenvalues: needs mu > 0 and -2/3 < lam/mu"),
    ("flutter_map", "plane_case", {"lam": -5.0, "mu": 1.0, "P": [1.0, -0.5, -0.5, 0.0, 0.0, 0.8],
                                   "Q": [0.6, -0.3, -0.3, 0.0, 0.0, -0.8]},
     "flutter_map.plane_case: needs mu > 0 and -2/3 < lam/mu"),
    ("fig04", "dt", 1000.0, "fig04.dt: must be <= cases.divergence.duration = 0.2 s"),
    ("fig18", "wheel_radius", 1.0, "fig18.wheel_radius: mu * wheel_radius = 0.25 m must be <"),
])
def test_values_the_scenes_refuse_are_refused_before_any_job(config, scene, key, value, match):
    """Outside audit: these passed `snakemake -n` and failed (or computed nonsense) only when
    their job ran: an integer written 101.0, a cycle below the flutter load, a negative load,
    meshes not increasing, a part [s1, s2] with s1 > s2."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"][scene][key] = value
    problems = validate_config(raw, ROOT / "workflow" / "schemas" / "config.schema.yaml",
                               scenes=SCENES)
    assert any(match in p for p in problems), problems


def test_an_unknown_list_name_does_not_hide_the_other_problems():
    """Outside audit: an unknown parameter-list name returned at once, hiding every other
    problem of the file (3 problems, 1 line)."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["eq47"]["pendulum"] = "list99"
    raw["scenes"]["eq25"]["n_pts"] = 3
    raw["scenes"]["fig05"]["n_points"] = -1
    problems = validate_config(raw, ROOT / "workflow" / "schemas" / "config.schema.yaml",
                               scenes=SCENES)
    assert len(problems) == 3, problems
    assert "unknown parameter list 'list99'" in problems[0]
    assert any("n_pts" in p for p in problems) and any("fig05.n_points" in p for p in problems)


# ---------------------------------------------------------------------- models' own ranges
@pytest.mark.parametrize(("scene", "key", "value", "match"), [
    # the pendulum's numerical range (the job raised "k1/k2 = 10^10 outside [1e-6, 1e6]")
    ("eq25", "pendulum", {"l1": 1.0, "l2": 1.0, "d": 1.0, "h": 0.0, "m1": 1.0, "m2": 1.0,
                          "m3": 0.0, "k1": 1.0e10, "k2": 1.0},
     "config (fidelity paper): scenes.eq25.pendulum: k1, k2: the ratio k1/k2 = 10^10 is "
     "outside the model's numerical range [1e-6, 1e6]"),
    # tip-mass ratios up to 10^8 (the job raised "tan_alpha must be [0, 10000]")
    ("rod_stability_map", "log10_ratio_range", [-2, 8],
     "scenes.rod_stability_map.log10_ratio_range: the largest tip-mass ratio 10^8 must be <= "
     "10000"),
    # the vanishing damping: above the solver's eta range, and below its damping floor (hung)
    ("rod_stability_map", "eta_small", 1.0e300,
     "scenes.rod_stability_map.eta_small: must be in [1e-06, 1]: at least "
     "analysis.rod.DAMPING_FLOOR"),
    ("rod_stability_map", "eta_small", 1.0e-20,
     "scenes.rod_stability_map.eta_small: must be in [1e-06, 1]"),
    # eq. (106)'s eta of the rod out of range (D = 7e6 N m^2 s)
    ("errata_rods", "rod", {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 7.0e6},
     "scenes.errata_rods.rod: eta must be 0 or in [1e-100, 1] (the rod solver's numerical "
     "range, analysis.rod.GROUP_RANGES), got 1.34214e+09; eta = D/(B l^2) sqrt(B/rho)"),
    # the damped rod of Fig. 11 below the FE twin's damping floor
    ("fig11", "rod", {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 1.0e-12},
     "scenes.fig11.rod: the damping max(eta, gamma) = 1.92e-10 (eq. 106) must be 0 or >= "
     "1e-06"),
    ("fig12", "tan_alpha", 1.0e5, "scenes.fig12.tan_alpha: must be in [0, 10000]"),
    ("fig11", "p_max", 5000.0, "scenes.fig11.p_max: must be in (0, 1000]"),
    ("errata_rods", "bracket", [1.3, 2.0e4], "scenes.errata_rods.bracket: the tan(alpha) "
                                             "bracket must lie in [0, 10000]"),
    # a pulling end force nearly along the axis: the closed form loses digits there (the job
    # failed after its shooting and collocation solves)
    ("elastica", "P1", -100.0, "scenes.elastica: P2: with a pulling end force (P1 < 0)"),
])
def test_the_scenes_models_refuse_before_any_job(scene, key, value, match):
    """Outside audit: each of these passed `snakemake -n` and failed (or hung, for
    eta_small = 1e-20) only when its job ran; now one line naming the scene and the key."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"][scene][key] = value
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert any(match in p for p in problems), problems
    assert len(problems) == 1 and "\n" not in problems[0], problems


def test_a_rod_whose_eta_underflows_is_refused():
    """Outside audit: length 1e100 m with D = 1e-150 N m^2 s underflowed eta to 0 (the
    undamped answer for a damped rod, silently)."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["errata_rods"]["rod"] = {"length": 1.0e100, "B": 1.0, "rho": 1.0,
                                           "D": 1.0e-150}
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert len(problems) == 1 and "scenes.errata_rods.rod: " in problems[0], problems
    assert "rescale" in problems[0]


def test_a_fe_convergence_case_below_the_damping_floor_is_refused():
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["rod_fe_convergence"]["cases"]["tiny"] = {"eta": 1.0e-9}
    raw["scenes"]["rod_fe_convergence"]["cases"]["huge"] = {"tan_alpha": 1.0e6}
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert sorted(problems) == [
        "config (fidelity paper): scenes.rod_fe_convergence.cases.huge: tan_alpha must be "
        "in [0, 10000] (the rod solver's numerical range, analysis.rod.GROUP_RANGES), got 1e+06",
        "config (fidelity paper): scenes.rod_fe_convergence.cases.tiny: the damping "
        "max(eta, gamma) = 1e-09 (eq. 106) must be 0 or >= 1e-06: the scene's "
        "finite-element twin cannot resolve the flutter crossing below "
        "analysis.rod.DAMPING_FLOOR"]


def test_a_preset_override_outside_a_models_range_is_refused():
    """Every preset is resolved and checked: the quick preset's override too."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["fidelity_presets"]["quick"]["scenes"]["rod_stability_map"]["eta_small"] = 1.0e-9
    raw["scenes"]["rod_stability_map"]["eta_small"] = 1.0e-6
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert len(problems) == 1 and problems[0].startswith(
        "config (fidelity quick): scenes.rod_stability_map.eta_small: must be in [1e-06, 1]")


# ---------------------------------------------------------------------- strings for numbers
@pytest.mark.parametrize(("value", "extra"), [
    ("1e-20", "; in a YAML file write 1.0e-20"),  # what `--config scenes={...}` and YAML give
    ("0.5", ""),
])
def test_a_number_given_as_a_string_says_why(value, extra):
    """Outside audit: `snakemake --config "scenes={rod_stability_map: {eta_small: 1e-20}}"`
    said "'1e-20' is not of type 'number'": Snakemake passes nested --config values as
    strings (and YAML 1.1 reads 1e-20, without a decimal point, as a string too)."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["rod_stability_map"]["eta_small"] = value
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert problems == [
        f"config: scenes.rod_stability_map.eta_small: {value!r} is a string, not a number "
        "(quoted in a YAML file, or nested in snakemake --config, which passes scenes={...} "
        "as strings: give nested values unquoted in a --configfile)"
        + (extra + " (YAML 1.1 reads an exponent without a decimal point or without its sign "
           "as a string)" if extra else "")]


# ---------------------------------------------------------------------- duplicate keys
def test_a_key_given_twice_is_refused(tmp_path):
    """Outside audit: YAML kept the last of two keys silently (`fidelity: quick` then
    `fidelity: paper` ran the paper preset; a pendulum section given twice)."""
    from flutterfriction.config import yaml_file_problems

    path = tmp_path / "c.yaml"
    path.write_text("fidelity: quick\nfidelity: paper\nscenes:\n  eq25:\n"
                    "    pendulum: {l1: 1.0}\n    n_points: 11\n    pendulum: {l1: 2.0}\n"
                    "base: &b {x: 1}\nmerged: {<<: *b, x: 2}\n")  # an override is no duplicate
    assert yaml_file_problems(path) == [
        f"{path}: (top level): key 'fidelity' given twice at line 2 (first at line 1; YAML "
        "would keep the last silently)",
        f"{path}: scenes.eq25: key 'pendulum' given twice at line 7 (first at line 5; YAML "
        "would keep the last silently)"]
    with pytest.raises(ParameterError, match="key 'fidelity' given twice at line 2"):
        load_config(path)
    assert yaml_file_problems(ROOT / "workflow" / "config.yaml") == []
    assert yaml_file_problems(ROOT / "workflow" / "coverage.yaml") == []


def test_a_number_that_underflows_to_zero_is_refused(tmp_path):
    """An outside review: a damping written 1.0e-400 is read by YAML as 0.0 (no damping: the
    chapter's paradox turned into a silent wrong answer). Refused with its place and line."""
    from flutterfriction.config import yaml_file_problems

    path = tmp_path / "c.yaml"
    path.write_text("scenes:\n  fig19:\n    pendulum: {c1: 1.0e-400, c2: 0.0}\n"
                    "    n_points: 11\n")
    assert yaml_file_problems(path) == [
        f"{path}: scenes.fig19.pendulum.c1: 1.0e-400 (line 3) underflows to 0 in double "
        "precision (below 2.5e-324): give a value in the parameter's range"]
    with pytest.raises(ParameterError, match="underflows to 0"):
        load_config(path)


def _scratch_workflow(tmp_path):
    import shutil

    for part in ("src", "workflow", "notebooks"):
        shutil.copytree(ROOT / part, tmp_path / part,
                        ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    shutil.copy(ROOT / "Snakefile", tmp_path / "Snakefile")


def _dry_run(tmp_path, *args):
    import os
    import subprocess
    import sys

    return subprocess.run([sys.executable, "-m", "snakemake", "-n", *args], cwd=tmp_path,
                          env={**os.environ, "PYTHONPATH": str(tmp_path / "src")},
                          capture_output=True, text=True, timeout=300)


@pytest.mark.slow  # three `snakemake -n` runs (~3 s each)
def test_the_workflow_refuses_duplicate_keys_and_model_ranges_before_any_job(tmp_path):
    """`snakemake -n` refuses a key given twice in workflow/config.yaml or in a --configfile,
    and a pendulum outside the model's range, one line each, before planning any job."""
    _scratch_workflow(tmp_path)
    (tmp_path / "over.yaml").write_text(
        "fidelity: quick\nfidelity: paper\nscenes:\n  eq25:\n    pendulum: {l1: 1.0, l2: 1.0, "
        "d: 1.0, h: 0.0, m1: 1.0, m2: 1.0, m3: 0.0, k1: 1.0e+10, k2: 1.0}\n")
    run = _dry_run(tmp_path, "--configfile", "over.yaml")
    out = run.stdout + run.stderr
    assert run.returncode != 0 and "invalid configuration:" in out
    assert "over.yaml: (top level): key 'fidelity' given twice at line 2 (first at line 1" in out
    assert "scenes.eq25.pendulum: k1, k2: the ratio k1/k2 = 10^10 is outside" in out
    # Snakemake passes a nested --config value as a string: the message says so
    run = _dry_run(tmp_path, "--config", "scenes={rod_stability_map: {eta_small: 1e-20}}")
    out = run.stdout + run.stderr
    assert run.returncode != 0
    assert ("config: scenes.rod_stability_map.eta_small: '1e-20' is a string, not a number "
            "(quoted in a YAML file, or nested in snakemake --config, which passes "
            "scenes={...} as strings: give nested values unquoted in a --configfile)") in out
    config = tmp_path / "workflow" / "config.yaml"
    config.write_text(config.read_text() + "fidelity: quick\n")
    run = _dry_run(tmp_path)
    out = run.stdout + run.stderr
    assert run.returncode != 0 and "key 'fidelity' given twice at line" in out


def test_scenes_that_are_not_a_mapping_are_one_line(config):
    """``--config scenes=foo`` (or ``scenes: foo`` in a file) was an AttributeError traceback
    from the list expansion (an outside audit); now the schema's one line."""
    bad = dict(config, scenes="foo")
    assert validate_config(bad, SCHEMA_PATH, scenes=SCENES) == [
        "config: scenes: 'foo' is not of type 'object'"]


#: List (119)'s rod with a tip mass M = 3 rho l (tan(alpha) = 3).
_ROD_TAN_3 = {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 7.078e-6, "tip_mass": 0.05733}


@pytest.mark.parametrize(("scene", "key", "value", "match"), [
    # P = 100 P*_flu, beyond the damped divergence load: 92 s of integration, then a failure
    ("fig13", "load_factor", 100.0, "scenes.fig13: load_factor must be in (1, 3.79856)"),
    ("fig14", "load_factor", 4.0, "scenes.fig14: load_factor must be in (1, 3.79856)"),
    ("fig13", "alpha0_deg", 0.0, "scenes.fig13: alpha0_deg must be non-zero"),
    ("fig13", "pendulum", {"l1": 0.1, "l2": 0.1, "d": 0.1, "h": 0.0, "m1": 0.1, "m2": 0.1,
                           "m3": 0.0, "k1": 0.2, "k2": 0.2},
     "scenes.fig13: pendulum: a limit cycle needs hinge viscosity"),
    # a motion of 1e300 s ran until killed
    ("fig20", "t_nonlinear", 1.0e300, "scenes.fig20: t_nonlinear must be in (0, 493.3] s"),
    ("fig20", "t_linear", 7.0, "scenes.fig20: t_linear must be <= t_nonlinear = 6 s"),
    ("fig21", "duration", 1.0e300, "scenes.fig21: duration must be in (0, 493.3] s"),
    # far above the rod's flutter load the stiff integration ran until killed; below it no cycle
    ("fig21", "omega0", 1.0e6, "scenes.fig21: omega0 must be in [-2027, 2027] rad/s"),
    ("beck_work_precision", "t_end", 1.0e300, "scenes.beck_work_precision: t_end must be in "
                                              "(0, 31.42] s"),
    ("beck_work_precision", "P_N", 1.0e6, "scenes.beck_work_precision: P_N must be in ("),
    ("pendulum_work_precision", "load_factor", 100.0,
     "scenes.pendulum_work_precision: cycle_pendulum, load_factor: load_factor must be in"),
    ("beck_limit_cycle", "rod", {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 1.0e-12},
     "scenes.beck_limit_cycle: rod.D: eta = D/(B l^2) sqrt(B/rho) = 1.92e-10 must be >="),
    ("beck_limit_cycle", "rod", {"length": 0.35, "B": 0.0332, "rho": 0.0546, "D": 7.078e-6,
                                 "tip_mass": 100.0},
     "scenes.beck_limit_cycle: rod.tip_mass: M/(rho l) must be <= 100"),
    ("limit_cycle_amplitude", "load_factors", [1.5, 2.0, 100.0],
     "scenes.limit_cycle_amplitude: load_factors must lie in (1, 3.79856)"),
    ("limit_cycle_amplitude", "pendulum", {"l1": 0.1, "l2": 0.1, "d": 0.1, "h": 0.0,
                                           "m1": 0.1, "m2": 0.1, "m3": 0.0, "k1": 0.2,
                                           "k2": 0.2},
     "scenes.limit_cycle_amplitude: pendulum: a limit cycle needs hinge viscosity"),
    # a tip mass in the rod of a scene whose tip mass is its own key was silently ignored: the
    # loads of another rod under your rod's title (an outside audit)
    ("fig11", "rod", _ROD_TAN_3, "scenes.fig11: rod.tip_mass must be 0 here: fig11 is the Beck "
                                 "rod, without a tip mass; for a tip mass draw fig12 with "
                                 "tan_alpha = M/(rho l) = 3; got 0.05733 kg"),
    ("fig12", "rod", _ROD_TAN_3, "scenes.fig12: rod.tip_mass must be 0 here: fig12 sets the tip "
                                 "mass by its key tan_alpha = M/(rho l): give tan_alpha: 3"),
    ("errata_rods", "rod", _ROD_TAN_3, "scenes.errata_rods: rod.tip_mass must be 0 here"),
    # accepted by the check, refused in the job (an outside audit)
    ("acoustic_eigenvalues", "g_min", 1.0e-200, "scenes.acoustic_eigenvalues: g_min: |p.q|/g = "
                                                "1.6e+199 takes eq. (184) beyond the double"),
    ("acoustic_eigenvalues", "g_max", 1.0e200, "scenes.acoustic_eigenvalues: g_max must be <= "
                                               "10000 |p| |q| / ||A_el|| = 15444.9 here"),
    ("fig05", "eps_values", [0.1, 1.0e200], "scenes.fig05: eps_values: c1: the relative "
                                            "viscosity"),
    ("paradox_limit", "eps_min", 1.0e-200, "scenes.paradox_limit: eps_min: c1: the relative"),
    ("damped_dead_load", "eps_values", [1.0e200], "scenes.damped_dead_load: eps_values: c1:"),
    ("fig11", "P_N", 1.0e200, "scenes.fig11: P_N must be in [-271.02, 271.02] N (p = P l^2/B "
                              "within the rod solver's range +-1000)"),
    ("fig22", "path", [[0.0, 0.0], [1.0e308, 0.0]], "scenes.fig22: path: the path's forces "
                                                    "(stiffness x displacements"),
    ("beck_branch", "check_loads", [3.5, 5.5, 7.5], "scenes.beck_branch: check_loads: 7.5 N is "
                                                    "outside the branch (2.9645"),
    ("beck_branch", "P_cycle", 7.5, "scenes.beck_branch: P_cycle must be in (2.9"),
    # 10^200 as a damping ratio wrote NaN into the data; d/l1 up to 2 failed in the job
    ("paradox_map", "log10_c_range", [-2.0, 200.0], "scenes.paradox_map: log10_c_range must be "
                                                    "an increasing range within [-6, 6]"),
    ("paradox_map", "d_ratio_range", [0.1, 2.0], "scenes.paradox_map: d_ratio_range must be an "
                                                 "increasing range within [1e-06, 1]"),
    # a ratio out of reach ended in scipy's "f(a) and f(b) must have different signs"
    ("fig19_theory", "flutter_ratio", 1.5, "scenes.fig19_theory: flutter_ratio must lie in "
                                           "(0.646986, 1.19003)"),
    ("fig19_theory", "divergence_ratio", 3.0, "scenes.fig19_theory: divergence_ratio must lie "
                                              "in ("),
    # (the quick preset's first mesh has 2 elements: its own interval, its own line)
    ("beck_limit_cycle", "P_N", 1.0e6, "scenes.beck_limit_cycle: P_N must be in ("),
    ("beck_limit_cycle", "P_N", 1.0, "scenes.beck_limit_cycle: P_N must be in ("),
])
def test_a_scene_refuses_what_its_job_would_find_only_after_costly_work(scene, key, value,
                                                                         match):
    """Outside audit: these passed the configuration check and then hung or failed after
    minutes in their job. Each scene's own check (registry `check`) now runs in the
    configuration check, and first thing in the scene (a ParameterError, not an integration
    that fails)."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"][scene][key] = value
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert problems and all(match in p and "\n" not in p for p in problems), problems
    if key == "P_N" and scene == "beck_limit_cycle":
        assert "P_N must be in (2.96454, 8.89361] N" in problems[0]  # paper: 4 elements
    params = scene_params(load_config(ROOT / "workflow" / "config.yaml") | {
        "scenes": {**load_config(ROOT / "workflow" / "config.yaml")["scenes"],
                   scene: {**load_config(ROOT / "workflow" / "config.yaml")["scenes"][scene],
                           key: value}}}, scene)
    if SCENES[scene].sweep is not None:  # its parts' computation refuses the same way
        scene_check = SCENES[scene].check
        with pytest.raises(ParameterError, match={"pendulum": "viscosity"}.get(key, key)):
            scene_check(params)
        return
    with pytest.raises(ParameterError, match={"pendulum": "viscosity", "rod": "rod."}.get(
            key, key)):
        build_scene(scene, params)


def test_fig04_refuses_more_frames_than_it_can_draw():
    """A case of 1e300 s ended in numpy's "Maximum allowed size exceeded" in the job (an
    outside audit); now one line naming the case's duration."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["fig04"]["cases"]["flutter"]["duration"] = 1.0e300
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert problems == ["config (fidelity paper): scenes.fig04.cases.flutter.duration: at most "
                        "1000 frames of dt = 0.04 s, got 2.5e+301"], problems


def test_a_check_that_does_not_converge_is_one_problem_line_not_a_traceback():
    """A scene's check that solves (here the acoustic tensor's interval, brute force) raised
    its ConvergenceError through the whole configuration check: a traceback, and no scene
    ran (the review of this session's change). Which end Newton fails to confirm first
    depends on the CPU's rounding (this input is nearly isotropic: ill-conditioned): g = 48.98
    on one machine, 4.57737 on another (an AVX-512 host; measured), 4.87335 since the general
    acoustic functions compute in power-of-two units (an outside audit's scales), so the test
    names none."""
    import re

    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["acoustic_eigenvalues"].update(P=[1.0, 0, 0, 0, 0, 1.0],
                                                 Q=[1.0, 0, 0, 0, 0, -1e-6], n=[1.0, 0, 0],
                                                 g_min=1e-4, g_max=50.0)
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert len(problems) == 1 and "\n" not in problems[0]
    # (either refusal of the interval's solver: an end Newton does not confirm, or a
    # discriminant sign the eigenvalues do not confirm; measured here: the first)
    assert re.fullmatch(r"config \(fidelity paper\): scenes\.acoustic_eigenvalues: the "
                        r"(flutter interval's end near g = [0-9.e+-]+ was not resolved|"
                        r"discriminant's sign at g = [0-9.e+-]+ is not confirmed) \(.*\); "
                        r"use flutter_interval_isotropic \(isotropic solids\)", problems[0]), \
        problems[0]


def test_a_scene_checks_verdict_is_computed_once_per_parameters():
    """The configuration check keeps each scene check's verdict for the process (the checks
    are pure functions of their parameters): the same parameters are not solved again, a
    refusal is repeated word for word, and an error that is not a model's refusal propagates
    and is not kept."""
    from flutterfriction import config as cfg
    from flutterfriction.errors import ParameterError

    calls = []

    def check(params):
        calls.append(dict(params))
        if params["P"] > 1:
            raise ParameterError("P must be in [0, 1]\n  (the cycle's load range)")
        if params["P"] < 0:
            raise RuntimeError("not a refusal")

    assert cfg._check_verdict(check, {"P": 0.5}) is None
    assert cfg._check_verdict(check, {"P": 0.5}) is None
    refusal = "P must be in [0, 1] (the cycle's load range)"
    assert cfg._check_verdict(check, {"P": 2.0}) == refusal
    assert cfg._check_verdict(check, {"P": 2.0}) == refusal
    assert calls == [{"P": 0.5}, {"P": 2.0}]
    assert cfg._check_verdict(check, {"P": 2}) == refusal  # another value: 2 is not 2.0
    assert len(calls) == 3
    for _ in range(2):
        with pytest.raises(RuntimeError):
            cfg._check_verdict(check, {"P": -1.0})
    assert len(calls) == 5


@pytest.mark.parametrize("scene, key, value, expected", [
    ("eq25", "eta_max", 1.0e160, "1e+160 is greater than the maximum of 1000000.0"),
    ("eq46", "gamma_max", 1.0e7, "10000000.0 is greater than the maximum of 1000000.0"),
    ("self_adjoint", "p_test", 1.0e200, "1e+200 is greater than the maximum of 1000"),
    ("beck_work_precision", "methods", [], "[] should be non-empty"),
    ("beck_work_precision", "rtols", [], "[] should be non-empty"),
    ("limit_cycle_amplitude", "load_factors", [1.1, 1.05, 1.2],
     "load_factors must increase strictly, got [1.1, 1.05, 1.2]"),
    ("limit_cycle_amplitude", "load_factors", [1.1, 1.1, 1.2],
     "load_factors must increase strictly, got [1.1, 1.1, 1.2]"),
    ("acoustic_eigenvalues", "P", [1.0e300, 0, 0, 0, 0, 0],
     "P, Q: with lam = 1, mu = 1 the vectors p = E[P] n, q = E[Q] n of eq. (180) have squares "
     "beyond 1e300"),
    # scenes that had no configuration check, or one that let these through to the job
    ("fig01", "P_rod", 1.0e20, "P_rod must be in (0, 271.02] N (1000 B/l^2"),
    ("fig01", "P_rod", 10.69945685277279,
     "P_rod = 10.6995 N: p = 39.4784 is a buckling load of the clamped beam-column"),
    ("errata_damped", "H", 1.0e300, "H = 1e+300 N: eta = H l1/k2 = 5.29e+299 must be within"),
    ("localization_directions", "G", 1.0e300, "G = 1e+300 Pa: E, P and Q put the plastic"),
    ("elastica", "q2", 1000.0, "q2 must be within +-200 B/l^3 = +-154.869 N/m for this rod"),
    ("elastica", "P1", 1.0e300, "P1 must be within +-200 B/l^2 = +-54.2041 N for this rod"),
    ("elastica", "P2", 1.0e-100, "P2 must be nonzero and at least 1e-30 B/l^2 = 2.71e-31 N"),
    ("pendulum_work_precision", "c_values", [1.0e-3, 1.0e300],
     "c_values: c1: the relative viscosity c1/(l2 sqrt(k2 m2)) = 10^302 must be 0 or within"),
])
def test_values_a_job_would_fail_on_are_refused_at_the_start(scene, key, value, expected):
    """An outside audit: eta_max = 1e160 and p_test = 1e200 gave NaN data silently, empty
    methods or rtols a KeyError after the study's references, unsorted or repeated load
    factors a meaningless Hopf fit, and P = 1e300 a bare OverflowError message. Each is now
    one line naming the key, before any job."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"][scene][key] = value
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert problems and all(f"scenes.{scene}" in p for p in problems), problems
    assert any(expected in p for p in problems), problems


def test_a_fig04_case_whose_response_overflows_is_refused_naming_its_load():
    """An outside audit: a case's P = 1e300 N was refused in the job as "times: ..."."""
    raw = yaml.safe_load((ROOT / "workflow" / "config.yaml").read_text())
    raw["scenes"]["fig04"]["cases"]["flutter"]["P"] = 1.0e300
    problems = validate_config(raw, SCHEMA_PATH, scenes=SCENES)
    assert len(problems) == 1 and "scenes.fig04: cases.flutter.P = 1e+300 N: " in problems[0]
