#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks the recorded real-time benchmark run (benchmarks/qemu/results/tick_budget.json, made by
tick_budget.py) against what is shipped and what the examples hold, without running QEMU:

  * the job list (tick_budget_jobs.txt) names every example job: each examples/jobs/*.json that is a
    job (has "segments"), each examples/svg/*.svg and each G-code file under examples/gcode/;
  * the recorded run ran exactly that list (a job added to the list or to the examples without a
    new run fails here);
  * every shipped image (boards/shipped_images.cmake, --shipped) has a result on every job, none of
    them an error, each within budget, and its verdict in "images" says it meets the budget.

Usage: check_recorded_budget.py --results JSON --job-list FILE --examples DIR --shipped TARGET ...
Exit 0 if all hold, 1 with one line per failure otherwise."""
import argparse
import glob
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tick_budget import read_job_list  # noqa: E402

GCODE_EXTENSIONS = (".ngc", ".nc", ".gcode", ".tap", ".cnc")


def example_jobs(examples_dir):
    """The example jobs, as paths from the source tree (examples_dir's parent)."""
    root = os.path.dirname(os.path.abspath(examples_dir))
    found = []
    for path in sorted(glob.glob(os.path.join(examples_dir, "jobs", "*.json"))):
        with open(path, encoding="utf-8") as handle:
            if "segments" in json.load(handle):  # a job, not a machine file
                found.append(path)
    found += sorted(glob.glob(os.path.join(examples_dir, "svg", "*.svg")))
    found += sorted(p for p in glob.glob(os.path.join(examples_dir, "gcode", "**", "*"), recursive=True)
                    if p.lower().endswith(GCODE_EXTENSIONS))
    return [os.path.relpath(p, root) for p in found]


def failures(report, job_list, examples, shipped):
    out = []
    listed = set(job_list)
    out += [f"{job}: an example job the benchmark's job list does not name" for job in examples if job not in listed]
    recorded = report.get("jobs", [])
    out += [f"{job}: in the job list, not in the recorded run (run tick_budget.py again)" for job in job_list
            if job not in recorded]
    out += [f"{job}: in the recorded run, no longer in the job list" for job in recorded if job not in listed]
    results = report.get("results", [])
    for target in shipped:
        rows = {r["job"]: r for r in results if r.get("image_target") == target}
        if not rows:
            out.append(f"{target}: shipped, but the recorded run has no result for it")
            continue
        for job in job_list:
            row = rows.get(job)
            if row is None:
                out.append(f"{target} on {job}: no result")
            elif "error" in row:
                out.append(f"{target} on {job}: the run failed: {row['error']}")
            elif not row.get("within_budget"):
                out.append(f"{target} on {job}: over budget (worst tick {row['budget']['worst_tick_share_of_period'][1]:.0%} "
                           f"of the period at CPI 1.3, {row['budget']['segments_per_s_possible']} segments/s possible, "
                           f"{row['budget']['segments_per_s_needed']} needed)")
        verdicts = [v for v in report.get("images", []) if v.get("image_target") == target]
        if not verdicts or not all(v.get("meets_budget") for v in verdicts):
            out.append(f"{target}: the recorded verdict does not say it meets the budget")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", required=True)
    parser.add_argument("--job-list", required=True)
    parser.add_argument("--examples", required=True)
    parser.add_argument("--shipped", action="append", required=True)
    args = parser.parse_args()
    with open(args.results, encoding="utf-8") as handle:
        report = json.load(handle)
    job_list = read_job_list(args.job_list)
    problems = failures(report, job_list, example_jobs(args.examples), args.shipped)
    for line in problems:
        print("FAIL: " + line, file=sys.stderr)
    if problems:
        return 1
    print(f"PASS: {', '.join(args.shipped)} within the real-time budget on all {len(job_list)} jobs of the recorded run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
