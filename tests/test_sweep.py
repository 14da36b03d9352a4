"""Sweeps scattered over jobs give the data of the one-process run."""

import json

import numpy as np
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


@pytest.mark.parametrize("part, n_parts", [
    (2, 2), (-1, 2), (0, 0), (0, True),
    # never truncated or coerced (an outside audit: 0.9 ran as part 0, "2" was taken, NaN
    # raised a bare ValueError, 1e7 parts were accepted)
    (0.9, 2), (0, "2"), (float("nan"), 2), (True, 2), (0, 10**7), (0, 2.0)])
def test_bad_part_indices_are_refused(part, n_parts):
    with pytest.raises(ParameterError, match=r"^(n_)?part(s)? must be an integer in \["):
        compute_part(TOY, {"n": 3}, part, n_parts)


def test_numpy_integers_are_part_indices():
    assert compute_part(TOY, {"n": 3}, np.int64(1), np.int64(2)) == compute_part(
        TOY, {"n": 3}, 1, 2)


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
