"""Sweeps scattered over jobs give the data of the one-process run."""

import json

import pytest
from conftest import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from flutterfriction.config import load_config, scene_params
from flutterfriction.errors import ParameterError
from flutterfriction.registry import SCENES, build_scene, build_scene_part, combine_scene_parts
from flutterfriction.scenes.sweep import Sweep, combine_parts, compute_part

# A toy sweep whose result depends on the order of the points within a block (as continuation
# does): the combined data must still follow the points' order.
TOY = Sweep(points=lambda p: list(range(p["n"])),
            compute=lambda p, pts: [x * x for x in pts],
            combine=lambda p, res: {"squares": res})


@settings(max_examples=60)
@given(n=st.integers(1, 30), n_parts=st.integers(1, 40))
def test_any_partition_gives_the_whole(n, n_parts):
    params = {"n": n}
    parts = [compute_part(TOY, params, k, n_parts) for k in range(n_parts)]
    assert combine_parts(TOY, params, parts[::-1]) == TOY.run(params)
    assert sorted(i for p in parts for i in p["indices"]) == list(range(n))


def test_missing_or_repeated_parts_are_refused():
    params = {"n": 5}
    parts = [compute_part(TOY, params, k, 2) for k in range(2)]
    with pytest.raises(ParameterError, match="cover 3 of 5"):
        combine_parts(TOY, params, parts[1:])
    with pytest.raises(ParameterError, match="repeated"):
        combine_parts(TOY, params, parts + parts[:1])


@pytest.mark.parametrize("part, n_parts", [(2, 2), (-1, 2), (0, 0), (0, True)])
def test_bad_part_indices_are_refused(part, n_parts):
    with pytest.raises(ParameterError, match="part"):
        compute_part(TOY, {"n": 3}, part, n_parts)


def test_rod_stability_map_in_parts_matches_one_process():
    params = scene_params(load_config(ROOT / "workflow" / "config.yaml"), "rod_stability_map")
    params["n_ratios"] = 3  # 8 points over 3 parts: blocks start afresh and continue within
    whole = build_scene("rod_stability_map", params)
    parts = [json.loads(json.dumps(build_scene_part("rod_stability_map", params, k, 3)))
             for k in range(3)]
    gathered = combine_scene_parts("rod_stability_map", params, parts)
    assert gathered["mass_ratio"] == whole["mass_ratio"]
    for case in ("undamped", "vanishing_damping"):
        for key in ("p_flu", "p_div"):
            for a, b in zip(whole[case][key], gathered[case][key], strict=True):
                # Blocks start afresh where one process continues: Newton's tolerance apart.
                assert (a is None and b is None) or abs(a - b) <= 1e-10 * abs(a)


def test_only_sweeps_can_be_split():
    assert {k for k, s in SCENES.items() if s.sweep} == {"limit_cycle_amplitude",
                                                          "rod_stability_map"}
    with pytest.raises(ParameterError, match="not a sweep"):
        build_scene_part("eq46", {}, 0, 1)
