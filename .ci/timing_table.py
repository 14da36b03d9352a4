"""Write the README's timing table from Snakemake's benchmark files (never typed by hand).

usage: python .ci/timing_table.py AFTER_DIR [--before BEFORE_DIR] [--totals TOTALS.json]
       [--readme README.md] [--baseline NAME]

AFTER_DIR/BEFORE_DIR: the results/benchmarks/ folders of this checkout's and the previous main's
paper runs from clean (same machine, same hour); TOTALS.json: {"what": {"before": s, "after": s}}
whole-command medians measured around them. Without --readme, prints the table."""

import argparse
import json
from pathlib import Path

from flutterfriction.benchmarks import read_benchmarks, replace_timing_block, timing_markdown

parser = argparse.ArgumentParser()
parser.add_argument("after")
parser.add_argument("--before")
parser.add_argument("--totals")
parser.add_argument("--readme")
parser.add_argument("--baseline", default="previous main",
                    help="what BEFORE_DIR is, as the headers name it (e.g. 7ecfb71)")
args = parser.parse_args()


def jobs(folder):
    return read_benchmarks(sorted(Path(folder).glob("*.tsv"))) if folder else None


totals = json.loads(Path(args.totals).read_text()) if args.totals else None
table = timing_markdown(jobs(args.after), jobs(args.before), totals, baseline=args.baseline)
if args.readme:
    readme = Path(args.readme)
    readme.write_text(replace_timing_block(readme.read_text(), table))
else:
    print(table)
