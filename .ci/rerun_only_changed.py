"""Change one scene's parameter in a copy of the config; Snakemake must plan to rerun only the
job computing that scene (its part's batch of cheap scenes) and its figures (plus the report and
the check that read every scene). Then "edit" one science module: only the scenes importing it
rerun."""

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
jobs = dict(re.findall(r"^(\w+)\s+(\d+)$", out, flags=re.M))
# eq48 is a cheap scene of the Ziegler part: its batch job reruns (the 7 cheap scenes of §2.1-2.3,
# ~2 s), not the other parts nor any slow scene. work_precision reruns too: its job-timing table
# reads every job's benchmark file.
expected = {"solve_ziegler": "1", "plot_ziegler": "1", "notebook": "1", "work_precision": "1",
            "report": "1", "check": "1", "all": "1"}
if {k: v for k, v in jobs.items() if k != "total"} != expected:
    sys.exit(f"expected only eq48's batch to rerun, got jobs {jobs}")
print("rerun check: changing eq48's k1 reruns only its part's batch (solve, plot), its notebook, "
      "the timing table and the check")

# Editing one science module reruns only the scenes whose jobs import it (transitively): the
# acoustic tensor is §3's, so the solids scenes rerun and the rod's slow cycle scenes do not.
module = "src/flutterfriction/analysis/acoustic.py"
import os  # noqa: E402

# An edit changes the file's content (Snakemake compares the checksum of an input newer than the
# outputs, so touching it is not enough); the original bytes and times are put back after.
st, original = os.stat(module), open(module, "rb").read()
try:
    with open(module, "ab") as fh:
        fh.write(b"\n# an edit\n")
    out = subprocess.run([sys.executable, "-m", "snakemake", "-n", "-j2"], capture_output=True,
                         text=True, check=True).stdout
finally:
    with open(module, "wb") as fh:
        fh.write(original)
    os.utime(module, ns=(st.st_atime_ns, st.st_mtime_ns))
rerun = set(re.findall(r"wildcards: scene=(\w+)", out)) | set(re.findall(r"^rule (\w+):", out,
                                                                          flags=re.M))
must = {"solve_solids", "plot_solids"}  # the §3 scenes (acoustic tensor) and their figures
must_not = {"beck_hopf", "beck_limit_cycle", "beck_work_precision", "solve_rods",
            "solve_ziegler", "solve_ziegler_paradox", "solve_limit_cycles"}
if not must <= rerun or rerun & must_not:
    sys.exit(f"editing {module} reruns {sorted(rerun)}: expected all of {sorted(must)} and none "
             f"of {sorted(must_not)}")
print(f"rerun check: editing {module} reruns {', '.join(sorted(rerun))}; none of the rod's "
      "cycles nor the other parts")
