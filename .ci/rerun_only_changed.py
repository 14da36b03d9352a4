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

# Editing one science module reruns only the scenes whose jobs import it (transitively): the
# acoustic tensor is §3's, so the solids scenes rerun and the rod's slow cycle scenes do not.
module = "src/flutterfriction/analysis/acoustic.py"
import os  # noqa: E402

st = os.stat(module)
try:
    os.utime(module, ns=(st.st_atime_ns, st.st_mtime_ns + 10**12 * 3600))  # "edited" later
    out = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-j2"], capture_output=True,
                         text=True, check=True).stdout
finally:
    os.utime(module, ns=(st.st_atime_ns, st.st_mtime_ns))
rerun = set(re.findall(r"wildcards: scene=(\w+)", out))
must = {"fig22", "acoustic_eigenvalues", "localization_directions", "flutter_map",
        "solids_statements", "errata_solids"}
must_not = {"beck_hopf", "beck_limit_cycle", "beck_work_precision", "fig11", "fig05", "eq25"}
if not must <= rerun or rerun & must_not:
    sys.exit(f"editing {module} reruns {sorted(rerun)}: expected all of {sorted(must)} and none "
             f"of {sorted(must_not)}")
print(f"rerun check: editing {module} reruns {len(rerun)} scenes and figures "
      f"({', '.join(sorted(rerun))}), none of the rod's cycles")
