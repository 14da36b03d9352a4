"""Atomic writes: a run interrupted mid-write never leaves a file that looks finished."""

from __future__ import annotations

import contextlib
import json
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np


def _default(obj: Any) -> Any:
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def make_readable(tmp: str | os.PathLike) -> None:
    """Give a temporary file the permissions a plain ``open(..., "w")`` would (mkstemp: 0600)."""
    os.chmod(tmp, 0o666 & ~_umask())


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[str]:
    """Yield a temporary file name beside ``path`` (same suffix); on success it is renamed to
    ``path`` with ordinary permissions, on failure removed: nothing half-written is left."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=path.suffix)
    os.close(fd)
    try:
        yield tmp
        make_readable(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def write_text(path: str | os.PathLike, text: str) -> None:
    """Write ``text`` to a temporary file beside ``path``, then rename it into place."""
    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8") as fh:
        fh.write(text)


def write_json(path: str | os.PathLike, data: Any) -> None:
    """Atomic strict JSON write; keys sorted and no timestamps, so reruns give identical files.

    A NaN or an infinity is refused (:class:`ValueError` naming the file and where in the
    data), nothing is written: JSON has no such numbers, and a non-finite result is a
    failure, not data (an outside audit found 210 NaN written silently into a scene's data)."""
    try:
        text = json.dumps(data, indent=1, sort_keys=True, default=_default, allow_nan=False)
    except ValueError:
        where = _non_finite_at(data)
        if where is None:  # another ValueError of json (a circular reference): as it is
            raise
        raise ValueError(f"{path}: not written: a non-finite number (NaN or inf) at "
                         f"{where}") from None
    write_text(path, text + "\n")


def _non_finite_at(data: Any, where: str = "") -> str | None:
    """The path (``key/3/key``) of the first NaN or infinity in ``data``, else None."""
    if isinstance(data, np.ndarray | list | tuple):
        items = enumerate(data.tolist() if isinstance(data, np.ndarray) else data)
    elif isinstance(data, dict):
        items = ((k, data[k]) for k in sorted(data, key=str))
    else:
        value = data.item() if isinstance(data, np.generic) else data
        bad = isinstance(value, float) and value - value != 0
        return (where or "the top level") if bad else None
    for key, value in items:
        found = _non_finite_at(value, f"{where}/{key}" if where else str(key))
        if found:
            return found
    return None


def read_json(path: str | os.PathLike) -> Any:
    with open(path, encoding="utf-8") as fh:
        return json.load(fh)


#: Keys whose values are measured wall-clock or CPU times: they differ from run to run, so they
#: are kept out of the data files (which reruns reproduce byte for byte) in a timings file
#: beside the benchmarks.
TIMING_KEYS = frozenset({"wall_s", "time_s", "cpu_s"})


def split_timings(data: Any) -> tuple[Any, Any]:
    """``(data without timing keys, the timings at the same paths)``; dicts and lists are
    walked recursively, and the timings are ``None`` where there are none."""
    if isinstance(data, dict):
        kept, timings = {}, {}
        for k, v in data.items():
            if k in TIMING_KEYS:
                timings[k] = v
                continue
            kept[k], t = split_timings(v)
            if t is not None:
                timings[k] = t
        return kept, (timings or None)
    if isinstance(data, list):
        pairs = [split_timings(v) for v in data]
        timings = [t for _, t in pairs]
        return [d for d, _ in pairs], (timings if any(t is not None for t in timings) else None)
    return data, None


def merge_timings(data: Any, timings: Any) -> Any:
    """The inverse of :func:`split_timings`."""
    if timings is None:
        return data
    if isinstance(data, dict):
        out = dict(data)
        for k, t in timings.items():
            out[k] = t if k in TIMING_KEYS else merge_timings(data[k], t)
        return out
    if isinstance(data, list):
        return [merge_timings(d, t) for d, t in zip(data, timings, strict=True)]
    raise ValueError("timings do not match the data's structure")


def markdown_table(header: list[str], rows: list[list[Any]]) -> list[str]:
    """Lines of a Markdown table; ``|`` inside a cell is escaped (``\\|``, shown as ``|``) so it
    cannot split the row, and a line break becomes a space."""
    def row(cells):
        return "| " + " | ".join(str(c).replace("|", "\\|").replace("\n", " ")
                                 for c in cells) + " |"

    return [row(header), "|" + "---|" * len(header), *(row(r) for r in rows)]


def log_job_output(path: str | Path) -> None:
    """Send this process's stdout and stderr (prints, warnings, a traceback) to the job's log
    file ``path`` (Snakemake's ``log:``), line-buffered, so concurrent jobs do not interleave on
    the terminal and a failed job's output is kept next to its results."""
    import sys

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    stream = open(path, "w", encoding="utf-8", buffering=1)  # noqa: SIM115 (lives with the job)
    sys.stdout = sys.stderr = stream
