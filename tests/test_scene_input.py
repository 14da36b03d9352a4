"""The scenes' Python entry point (flutterfriction.registry.build_scene) refuses bad parameters
before any work, as the workflow's configuration check does: an outside audit found 2.5, True
and "3" accepted for integers (truncated, or a numba SystemError minutes later), NaN tolerances
integrating, and Fig. 11's load of 1e200 N refused only after 3 s of branches."""

from __future__ import annotations

import copy
import math

import pytest
from conftest import ROOT

from flutterfriction.config import load_config, scene_params
from flutterfriction.errors import ParameterError
from flutterfriction.registry import SCENES, build_scene, build_scene_part, checked_params

CONFIG = load_config(ROOT / "workflow" / "config.yaml")


def _params(scene: str) -> dict:
    return copy.deepcopy(scene_params(CONFIG, scene))


@pytest.fixture
def no_work(monkeypatch):
    """Every scene's computation fails the test if it starts."""
    import flutterfriction.scenes as scenes

    def refuse(*_args, **_kwargs):
        raise AssertionError("the scene started computing before refusing its parameters")

    monkeypatch.setattr(scenes, "build_scene", refuse)
    monkeypatch.setattr(scenes, "build_scene_part", refuse)


@pytest.mark.parametrize(("scene", "key", "value", "match"), [
    ("fig11", "n_modes", 2.5, r"scenes\.fig11\.n_modes: 2\.5 is not of type 'integer'"),
    ("fig11", "n_modes", True, r"scenes\.fig11\.n_modes: True is not of type 'integer'"),
    ("fig11", "n_modes", "3", r"scenes\.fig11\.n_modes: '3' is a string, not a integer"),
    ("fig11", "n_modes", 11, r"scenes\.fig11\.n_modes: 11 is greater than the maximum of 10"),
    ("fig11", "P_N", 1.0e200, r"scenes\.fig11: P_N must be in \[-271\.02, 271\.02\] N"),
    ("fig11", "P_N", math.nan, r"scenes\.fig11\.P_N: must be a finite number, got nan"),
    ("rod_fe_convergence", "repeats", 2.5, r"scenes\.rod_fe_convergence\.repeats: 2\.5 is not"),
    ("beck_limit_cycle", "samples_per_period", 2.5, r"samples_per_period: 2\.5 is not"),
    ("beck_limit_cycle", "tol", math.inf, r"beck_limit_cycle\.tol: inf is greater than the max"),
    ("beck_limit_cycle", "rtol", math.nan, r"beck_limit_cycle\.rtol: must be a finite number"),
    ("fig13", "tol", True, r"scenes\.fig13\.tol: True is not of type 'number'"),
    ("errata_damped", "H", "3", r"scenes\.errata_damped\.H: '3' is a string"),
    ("self_adjoint", "p_test", math.nan, r"scenes\.self_adjoint\.p_test: must be a finite"),
    ("fig01", "n_points", 2.5, r"scenes\.fig01\.n_points: 2\.5 is not of type 'integer'"),
    ("fig01", "n_pts", 5, r"scenes\.fig01: unknown key\(s\) \['n_pts'\]"),
])
def test_bad_parameters_are_refused_before_any_work(no_work, scene, key, value, match):
    params = _params(scene)
    params[key] = value
    with pytest.raises(ParameterError, match=match) as err:
        build_scene(scene, params)
    assert "\n" not in str(err.value)


def test_a_sweeps_part_is_checked_too(no_work):
    params = _params("rod_stability_map")
    params["n_ratios"] = 2.5
    with pytest.raises(ParameterError, match=r"rod_stability_map\.n_ratios: 2\.5 is not"):
        build_scene_part("rod_stability_map", params, 0, 2)


def test_the_shipped_parameters_pass_and_chapter_lists_may_be_named():
    for fidelity in ("quick", "paper"):
        config = copy.deepcopy(CONFIG) | {"fidelity": fidelity}
        for name in SCENES:
            params = scene_params(config, name)
            assert checked_params(name, params) == params, name
    named = _params("fig11") | {"rod": "list119"}
    assert checked_params("fig11", named) == _params("fig11")
    with pytest.raises(ParameterError, match=r"scenes\.fig11\.rod: .*list999"):
        checked_params("fig11", _params("fig11") | {"rod": "list999"})
    with pytest.raises(ParameterError, match="must be a mapping"):
        checked_params("fig11", [1, 2])


def test_fig11_called_directly_refuses_its_load_before_the_branches(monkeypatch):
    """The scene function itself (not only the registry's check) refuses first thing."""
    from flutterfriction.analysis import rod as ar
    from flutterfriction.scenes import rod

    def no_branches(*_args, **_kwargs):
        raise AssertionError("branches computed before the load was checked")

    monkeypatch.setattr(ar, "branches", no_branches)
    params = _params("fig11") | {"P_N": 1.0e200}
    with pytest.raises(ParameterError, match="P_N must be in"):
        rod.fig11(params)
    with pytest.raises(ParameterError, match=r"n_modes must be an integer in \[1, 16\]"):
        rod.fig11(_params("fig11") | {"n_modes": 2.5})


def test_numpy_numbers_and_arrays_are_taken_as_the_numbers_they_hold(no_work):
    """A sweep written with numpy passes np.int64 and arrays; they were refused ("np.int64(5)
    is not of type 'integer'") though the Python API's models take them. Taken as the plain
    numbers and lists a configuration file gives; a float for an integer is still refused."""
    import numpy as np

    params = _params("rod_stability_map")
    given = params | {"n_ratios": np.int64(5), "log10_ratio_range": np.array([-1.0, 1.0]),
                      "eta_small": np.float32(0.5)}
    checked = checked_params("rod_stability_map", given)
    assert checked["n_ratios"] == 5 and type(checked["n_ratios"]) is int
    assert checked["log10_ratio_range"] == [-1.0, 1.0]
    assert type(checked["eta_small"]) is float
    with pytest.raises(ParameterError, match=r"n_ratios: 5\.0 is not of type 'integer'"):
        checked_params("rod_stability_map", params | {"n_ratios": np.float64(5.0)})
    with pytest.raises(ParameterError, match=r"n_ratios: True is not of type 'integer'"):
        checked_params("rod_stability_map", params | {"n_ratios": np.bool_(True)})
    with pytest.raises(ParameterError, match=r"eta_small: must be a finite number, got nan"):
        checked_params("rod_stability_map", params | {"eta_small": np.float64("nan")})
