"""The run's last step: fail (listing why) when the report found a failed entry, a figure
missing from the layout, a figure failing the figure check or a broken link; the summary and
the report stay on disk."""

import sys

from flutterfriction.io import read_json, write_text

problems = read_json(snakemake.input.problems)["problems"]
summary = read_json(snakemake.input.summary)
# The summary goes to this job's log; the verdict to the terminal too (it is the run's last word).
write_text(snakemake.log[0], open(snakemake.input.summary_md, encoding="utf-8").read()
           + ("\n".join(["", "FAILED:", *problems]) if problems else ""))
if problems:
    sys.exit("the check failed (see results/reports/index.html and results/checks/summary.md):"
             "\n  " + "\n  ".join(problems))
figures = summary.get("figures", {"n_figures": 0})
skipped = summary.get("n_not_applicable", 0)
checked = summary["n_entries"] - skipped
write_text(snakemake.output[0],
           f"{checked - summary['n_failed']} of {checked} entries pass"
           + (f" ({skipped} not applicable: their scenes ran with other parameters than the "
              "chapter's)" if skipped else "")
           + f"; {figures['n_figures']} figures pass the figure check; every figure shown, "
           "every report link resolves\n")
