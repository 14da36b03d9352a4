"""Atomic, deterministic outputs."""

from __future__ import annotations

import os

import numpy as np
import pytest

from flutterfriction.io import read_json, write_json, write_text


def test_write_json_is_deterministic_and_leaves_no_temp_files(tmp_path):
    path = tmp_path / "sub" / "x.json"
    write_json(path, {"b": np.float64(1.5), "a": np.arange(3)})
    first = path.read_bytes()
    write_json(path, {"a": [0, 1, 2], "b": 1.5})
    assert path.read_bytes() == first
    assert read_json(path) == {"a": [0, 1, 2], "b": 1.5}
    assert os.listdir(path.parent) == ["x.json"]


def test_failed_write_keeps_the_old_file(tmp_path):
    path = tmp_path / "x.json"
    write_text(path, "old")
    with pytest.raises(TypeError):
        write_json(path, {"bad": object()})
    assert path.read_text() == "old"
    assert os.listdir(tmp_path) == ["x.json"]
