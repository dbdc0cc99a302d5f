# SPDX-License-Identifier: MIT
"""Path-speed benchmark: polyline jobs through `curvestep sim` against the length/feed bound, the same
circle as one arc, and a model of grbl's junction-deviation planner (grbl_model.py); and an
independent check of the deviation from the programmed path (computed here from the generated moves
and the simulator's double-precision setpoints, not by the code under test).

    python3 run_path_speed.py CURVESTEP MACHINE.json [--small] [--check] [--out results.json]

Prints JSON. With --check, exits 1 unless these goals hold: circles of 360 and 3600 chords within
1.15x the arc, the spiral within 1.15x length/feed, no limit exceeded, no job slower smoothed than as
programmed, and every setpoint within the tolerance of the programmed path. The CAM raster against the grbl model (16-block buffer, same a_max)
is reported in "open_goals" while it is slower: its row turnarounds are 90-degree corners, which a
jerk-limited machine stops at (faster than any blend within 10 um) and grbl's jerk-free model passes
at its junction speed. turnaround_bound.py shows that no jerk-limited machine can lose as little time
on such a turnaround as grbl's model (docs/motion.md, "Turnarounds").
"""
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import grbl_model  # noqa: E402
import make_jobs  # noqa: E402


def run_sim(curvestep, job_file, machine_file, extra, csv_file=None):
    args = [curvestep, "sim", job_file, "--machine", machine_file] + extra
    if csv_file:
        args += ["--double", "-o", csv_file]
    result = subprocess.run(args, capture_output=True, text=True, timeout=600)
    if result.returncode not in (0, 3):
        raise RuntimeError("curvestep sim failed: " + result.stdout + result.stderr)
    text = result.stdout
    summary = {"duration_s": float(re.search(r"duration:\s+([0-9.e+-]+) s", text).group(1)),
               "violations": re.findall(r"LIMIT VIOLATION:\s+(.*)", text)}
    for key, pattern in (("corners_blended", r"corners blended:\s+(\d+) of (\d+)"),
                         ("runs_fitted", r"line runs fitted:\s+(\d+) \((\d+) lines -> (\d+) curves\)"),
                         ("reported_deviation_um", r"path deviation:\s+([0-9.e+-]+) um"),
                         ("segments", r"smoothing:\s+tolerance [0-9.e+-]+ um; (\d+) segments -> (\d+)")):
        m = re.search(pattern, text)
        if m:
            summary[key] = [float(g) for g in m.groups()] if len(m.groups()) > 1 else float(m.group(1))
    return summary


class SegmentGrid:
    """Segments bucketed in square cells, for distances below one cell."""

    def __init__(self, segments, cell):
        self.cell = cell
        self.cells = {}
        for index, (a, b) in enumerate(segments):
            lo = [math.floor(min(a[k], b[k]) / cell) for k in range(3)]
            hi = [math.floor(max(a[k], b[k]) / cell) for k in range(3)]
            for i in range(lo[0], hi[0] + 1):
                for j in range(lo[1], hi[1] + 1):
                    for k in range(lo[2], hi[2] + 1):
                        self.cells.setdefault((i, j, k), []).append(index)
        self.segments = segments

    def distance(self, p):
        c = [math.floor(p[k] / self.cell) for k in range(3)]
        best = math.inf
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for k in (-1, 0, 1):
                    for index in self.cells.get((c[0] + i, c[1] + j, c[2] + k), ()):
                        best = min(best, point_to_segment(p, *self.segments[index]))
        return best


def point_to_segment(p, a, b):
    d = [b[k] - a[k] for k in range(3)]
    l2 = sum(x * x for x in d)
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, sum((p[k] - a[k]) * d[k] for k in range(3)) / l2))
    return math.dist(p, [a[k] + t * d[k] for k in range(3)])


def independent_deviation(job, csv_file):
    """Largest distance of a setpoint from the programmed polyline, and of a programmed vertex from the
    setpoint polyline, mm (within 1 mm; farther counts as 1 mm)."""
    with open(csv_file) as f:
        rows = list(csv.DictReader(f))
    points = [(float(r["x"]), float(r["y"]), float(r["z"])) for r in rows]
    programmed = [(s, e) for s, e, _kind, _feed in job.moves]
    grid = SegmentGrid(programmed, 1.0)
    to_programmed = max(min(grid.distance(p), 1.0) for p in points)
    path = SegmentGrid(list(zip(points[:-1], points[1:])), 1.0)
    vertices = [job.moves[0][0]] + [e for _s, e, _k, _f in job.moves]
    to_path = max(min(path.distance(v), 1.0) for v in vertices)
    return to_programmed, to_path


def main():
    curvestep, machine_file = sys.argv[1], sys.argv[2]
    small = "--small" in sys.argv
    check = "--check" in sys.argv
    out_file = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else None
    with open(machine_file) as f:
        machine = json.load(f)
    tolerance = machine.get("blend_tolerance", 0.0)
    deviation_mm = machine.get("junction_deviation", 0.05)
    results = []
    failures = []
    open_goals = []
    with tempfile.TemporaryDirectory() as scratch:
        jobs = make_jobs.all_jobs(small)
        arc_time = None
        for job in jobs:
            path = os.path.join(scratch, job.name + ".ngc")
            with open(path, "w") as f:
                f.write(job.gcode())
            setpoints = os.path.join(scratch, job.name + ".csv")
            smoothed = run_sim(curvestep, path, machine_file, [], setpoints)
            raw = run_sim(curvestep, path, machine_file, ["--blend-tolerance", "0"])
            entry = {"job": job.name, "feed_length_mm": round(job.length(), 4), "curvestep_s": smoothed["duration_s"],
                     "curvestep_unsmoothed_s": raw["duration_s"], "violations": smoothed["violations"]}
            entry.update({k: v for k, v in smoothed.items() if k not in ("duration_s", "violations")})
            if job.arc is not None:
                arc_time = smoothed["duration_s"]
                entry["note"] = "the reference: the circle as one G3"
                results.append(entry)
                continue
            feed_bound = job.length() / make_jobs.FEED
            blocks = grbl_model.blocks_from_moves(job.moves, machine)
            entry["length_over_feed_s"] = round(feed_bound, 4)
            entry["grbl_model_16_blocks_s"] = round(grbl_model.job_time(blocks, deviation_mm, 16), 4)
            entry["grbl_model_unbounded_s"] = round(grbl_model.job_time(blocks, deviation_mm, None), 4)
            if tolerance > 0:  # the junction deviation equal to the blend tolerance: its circles lie as far inside
                entry["grbl_model_16_blocks_at_tolerance_s"] = round(grbl_model.job_time(blocks, tolerance, 16), 4)
            entry["ratio_to_length_over_feed"] = round(smoothed["duration_s"] / feed_bound, 4)
            entry["ratio_to_grbl_16"] = round(smoothed["duration_s"] / entry["grbl_model_16_blocks_s"], 4)
            if job.name.startswith("circle") and arc_time:
                entry["ratio_to_arc"] = round(smoothed["duration_s"] / arc_time, 4)
            to_programmed, to_path = independent_deviation(job, setpoints)
            entry["deviation_setpoints_to_programmed_um"] = round(to_programmed * 1000, 3)
            entry["deviation_programmed_to_setpoints_um"] = round(to_path * 1000, 3)
            results.append(entry)
            # The goals of the issue.
            if smoothed["violations"]:
                failures.append(job.name + ": limit exceeded: " + "; ".join(smoothed["violations"]))
            if job.name in ("circle_360_chords", "circle_3600_chords") and entry["ratio_to_arc"] > 1.15:
                failures.append(job.name + ": %.3fx the arc's time" % entry["ratio_to_arc"])
            if job.name.startswith("spiral") and entry["ratio_to_length_over_feed"] > 1.15:
                failures.append(job.name + ": %.3fx length/feed" % entry["ratio_to_length_over_feed"])
            # Smoothing never makes a job slower than as programmed (a blend is made only where the
            # planner passes it faster than the corner); one tick of slack.
            if smoothed["duration_s"] > raw["duration_s"] + 0.0015:
                failures.append(job.name + ": smoothed %.3f s, slower than as programmed %.3f s" % (smoothed["duration_s"], raw["duration_s"]))
            if job.name.startswith("cam_raster") and entry["ratio_to_grbl_16"] > 1.0:
                open_goals.append(job.name + ": slower than the grbl model (%.3fx)" % entry["ratio_to_grbl_16"])
            # Setpoints lie on the smoothed path (chord and Q16.16 effects are far below a micrometre),
            # so their distance from the programmed path is the smoothing's deviation.
            if tolerance > 0 and to_programmed > tolerance + 1e-4:
                failures.append(job.name + ": a setpoint %.2f um from the programmed path" % (to_programmed * 1000))
    report = {"benchmark": "path_speed", "machine": os.path.basename(machine_file), "blend_tolerance_mm": tolerance,
              "junction_deviation_mm": deviation_mm, "jobs": results, "goals_failed": failures, "open_goals": open_goals}
    text = json.dumps(report, indent=2)
    print(text)
    if out_file:
        with open(out_file, "w") as f:
            f.write(text + "\n")
    return 1 if (check and failures) else 0


if __name__ == "__main__":
    sys.exit(main())
