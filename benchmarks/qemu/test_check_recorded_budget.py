#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""check_recorded_budget.py on hand-made reports: it passes a complete run within budget and names
each gap: an example job missing from the list, a listed job not run, a shipped image over budget,
failed, missing, or with a verdict that says no. Exit 0 if every case behaves."""
import copy
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_recorded_budget import example_jobs, failures  # noqa: E402

SHIPPED = ["curvestep_stm32f1_executor"]


def row(job, within=True, target="curvestep_stm32f1_executor"):
    return {"board": "stm32f1", "image": "executor", "image_target": target, "elf": "x.elf", "job": job,
            "within_budget": within, "budget": {"worst_tick_share_of_period": [0.3, 0.39 if within else 0.7],
                                                "segments_per_s_possible": 1400.0, "segments_per_s_needed": 186.4}}


def report(jobs, rows, meets=True):
    return {"jobs": jobs, "results": rows,
            "images": [{"image_target": "curvestep_stm32f1_executor", "meets_budget": meets}]}


def main():
    checks = []
    with tempfile.TemporaryDirectory(prefix=f"curvestep-check-budget-{os.getpid()}-") as work:
        examples = os.path.join(work, "examples")
        for sub in ("jobs", "svg", "gcode/cam"):
            os.makedirs(os.path.join(examples, sub))
        for name, text in (("jobs/a.json", {"segments": []}), ("jobs/machine.json", {"rate_hz": 1000})):
            with open(os.path.join(examples, name), "w", encoding="utf-8") as handle:
                json.dump(text, handle)
        for name in ("svg/b.svg", "gcode/cam/c.nc", "gcode/README.md"):
            open(os.path.join(examples, name), "w", encoding="utf-8").close()
        found = example_jobs(examples)
        checks.append(("the examples are the job, the SVG and the G-code, not the machine or the README",
                       found == ["examples/jobs/a.json", "examples/svg/b.svg", "examples/gcode/cam/c.nc"]))
    jobs = ["examples/jobs/a.json", "examples/svg/b.svg", "examples/gcode/cam/c.nc", "path_speed/d.ngc"]
    good = report(jobs, [row(j) for j in jobs])
    checks.append(("a complete run within budget passes", failures(good, jobs, found, SHIPPED) == []))
    problems = failures(good, jobs[1:], found, SHIPPED)
    checks.append(("an example job missing from the list fails",
                   any("examples/jobs/a.json: an example job" in p for p in problems)))
    problems = failures(report(jobs[:3], [row(j) for j in jobs[:3]]), jobs, found, SHIPPED)
    checks.append(("a listed job the recorded run lacks fails", any("path_speed/d.ngc: in the job list, not in" in p
                                                                     for p in problems)))
    over = copy.deepcopy(good)
    over["results"][2] = row(jobs[2], within=False)
    checks.append(("a shipped image over budget on one job fails",
                   any("on examples/gcode/cam/c.nc: over budget" in p for p in failures(over, jobs, found, SHIPPED))))
    failed = copy.deepcopy(good)
    failed["results"][0] = {"job": jobs[0], "image_target": SHIPPED[0], "error": "curvestep stream exited with 4"}
    checks.append(("a failed run fails", any("the run failed" in p for p in failures(failed, jobs, found, SHIPPED))))
    checks.append(("a verdict that says no fails",
                   any("does not say it meets" in p
                       for p in failures(report(jobs, [row(j) for j in jobs], meets=False), jobs, found, SHIPPED))))
    checks.append(("a shipped image without results fails",
                   any("no result for it" in p for p in failures(good, jobs, found, ["curvestep_stm32f4_executor"]))))
    planner_over = copy.deepcopy(good)
    planner_over["results"].append(row(jobs[0], within=False, target="curvestep_stm32f1_firmware"))
    checks.append(("an image not shipped may be over budget", failures(planner_over, jobs, found, SHIPPED) == []))
    for name, ok in checks:
        print(("PASS: " if ok else "FAIL: ") + name)
    return 0 if all(ok for _, ok in checks) else 1


if __name__ == "__main__":
    sys.exit(main())
