"""Delete outputs a reader sees (a figure, a data file, a notebook's HTML, a GIF, the
work-precision figure; then the report and the check table alone): Snakemake must plan to
rebuild each and to refresh the report and the check."""

import os
import re
import subprocess
import sys
from pathlib import Path


def planned_after_deleting(victims: list[str]) -> tuple[list[str], dict[str, str]]:
    """Delete ``victims``, dry-run, put them back as they were: (not rebuilt, jobs planned)."""
    saved = {v: (Path(v).read_bytes(), os.stat(v)) for v in victims}
    try:
        for v in victims:
            Path(v).unlink()
        out = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-j2"],
                             capture_output=True, text=True, check=True).stdout
    finally:
        for v, (data, st) in saved.items():  # this only plans
            Path(v).write_bytes(data)
            os.utime(v, ns=(st.st_atime_ns, st.st_mtime_ns))
    planned = set(re.findall(r"output: ([^\n]+)", out))
    missing = [v for v in victims if not any(v in line for line in planned)]
    return missing, dict(re.findall(r"^(\w+)\s+(\d+)$", out, flags=re.M))


for victims in (["results/figures/fig03.png", "results/data/eq46.json",
                 "results/reports/solids.html", "results/figures/pendulum_cycle.gif",
                 "results/benchmarks/work_precision.png"],
                # the report alone (as after a failed or interrupted report job): it was not a
                # target, so an old passed.txt stood and nothing was rebuilt (outside audit)
                ["results/reports/index.html", "results/checks/summary.md"]):
    missing, jobs = planned_after_deleting(victims)
    if missing or "report" not in jobs or "check" not in jobs:
        sys.exit(f"deleted outputs not rebuilt: {missing}; jobs planned {jobs}")
    print(f"rebuild check: {len(victims)} deleted outputs are rebuilt and the report and the "
          f"check refreshed (jobs planned: {jobs.get('total')})")
