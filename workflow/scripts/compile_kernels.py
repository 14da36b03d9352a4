"""Compile the nonlinear rod's kernels once (numba's cache), before the jobs that use them
(thin: the package call, the seconds it took as JSON)."""

from flutterfriction.io import log_job_output, write_json
from flutterfriction.models.rod_nonlinear import compile_kernels

log_job_output(snakemake.log[0])  # this job's output goes to its log file

seconds = compile_kernels()
print("kernels ready:", ", ".join(f"{k} {v:.2f} s" for k, v in seconds.items()), flush=True)
write_json(snakemake.output[0], {"seconds": seconds})
