"""workflow/config.yaml and its schema: what the workflow accepts and what it rejects."""

from __future__ import annotations

import copy

import jsonschema
import pytest
import yaml
from conftest import ROOT

from flutterfriction.config import load_config, scene_params
from flutterfriction.errors import ParameterError
from flutterfriction.scenes import SCENES, build_scene


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
