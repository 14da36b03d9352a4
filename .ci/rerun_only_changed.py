"""Change one scene's parameter in a copy of the config; Snakemake must plan to rerun only that
scene's solver and plot (plus the report and the check that read every scene)."""

import re
import subprocess
import sys
import tempfile

import yaml

with open("workflow/config.yaml", encoding="utf-8") as fh:
    config = yaml.safe_load(fh)
config["scenes"]["eq48"]["pendulum"]["k1"] *= 1.5
with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as tmp:
    yaml.safe_dump(config, tmp)
out = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-j2", "--configfile", tmp.name],
                     capture_output=True, text=True, check=True).stdout
scenes = sorted(set(re.findall(r"wildcards: scene=(\w+)", out)))
jobs = dict(re.findall(r"^(\w+)\s+(\d+)$", out, flags=re.M))
# work_precision reruns too: its job-timing table reads every job's benchmark file.
expected = {"solve": "1", "plot": "1", "notebook": "1", "work_precision": "1",
            "report": "1", "check": "1", "all": "1"}
if scenes != ["eq48"] or {k: v for k, v in jobs.items() if k != "total"} != expected:
    sys.exit(f"expected only eq48 to rerun, got scenes {scenes} and jobs {jobs}")
print("rerun check: changing eq48's k1 reruns only eq48 (solve, plot), its notebook, the timing "
      "table and the check")
