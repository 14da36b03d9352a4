"""Rerun every solver, plot and animation job and compare the results byte for byte: data files
and figures must be identical, except the figures that draw wall-clock times (work-precision),
whose timings live in results/benchmarks/*.timings.json."""

import hashlib
import subprocess
import sys
from pathlib import Path

RESULTS = Path("results")


def digests() -> dict[str, str]:
    files = sorted(RESULTS.glob("data/**/*.json")) + sorted(RESULTS.glob("figures/*"))
    return {str(f): hashlib.sha256(f.read_bytes()).hexdigest() for f in files}


from flutterfriction.registry import SCENES  # noqa: E402

# The figures that draw wall-clock times (work-precision): the only ones allowed to differ.
DRAWS_TIMES = {f for s in SCENES.values() if s.draws_wall_times for f in s.figures}


def timed_figures() -> set[str]:
    return {str(f) for f in RESULTS.glob("figures/*") if f.stem in DRAWS_TIMES}


before = digests()

listed = subprocess.run([sys.executable, "-m", "snakemake", "--list-rules"], capture_output=True,
                        text=True, check=True).stdout.split()
# the batches: a part's (solve_<part>, plot_<part>) and a multi-figure scene's (plot_<scene>)
batches = [r for r in listed if r.startswith(("solve_", "plot_")) and r != "solve_part"]
subprocess.run([sys.executable, "-m", "snakemake", "-j2", "--quiet", "rules", "--forcerun",
                "solve", "solve_part", "plot", *[b for b in batches if b in listed],
                "animate_pendulum_cycle", "animate_rod_cycle"], check=True)
after = digests()
exempt = timed_figures()
changed = sorted(f for f in before if before[f] != after.get(f) and f not in exempt)
missing = sorted(set(before) ^ set(after))
drawn_times = sorted(f for f in exempt if before.get(f) != after.get(f))
if changed or missing:
    sys.exit(f"not reproducible: changed {changed}, missing/new {missing}")
print(f"reproducibility: {len(before)} data files and figures rerun; all byte-identical except "
      f"{len(drawn_times)} figures that draw wall-clock times ({', '.join(drawn_times)})")
