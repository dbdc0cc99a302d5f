# SPDX-License-Identifier: MIT
"""Random jobs of lines and tangent arcs with feed changes, run through one or two curvestep binaries on
five machines, smoothed and as programmed: a regression check for planner and smoothing changes, on
inputs nobody shaped to the code. Prints JSON: per binary and machine the total time smoothed and as
programmed, the jobs slower smoothed than as programmed, the jobs with a limit violation, and (with two
binaries) the jobs the second runs slower than the first.

    python3 random_jobs.py CURVESTEP [CURVESTEP_BEFORE] [--jobs 40] [--seed 15]

The jobs are deterministic for a seed (Python's random): 20-80 moves each, lines of 0.1-30 mm turning
by 0-135 degrees, arcs of R 0.5-50 mm tangent to the path (sometimes followed by a small kink), F
changes among 600-9000 mm/min. The machines: examples/jobs/machine.json as it is, with j_max 5000 and
a_max 1000, with j_max 500 000, a_max 3000 and v_max 300, and with the trapezoid profile.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MACHINE = os.path.join(HERE, "..", "..", "examples", "jobs", "machine.json")
VARIANTS = {
    "machine.json": {},
    "low_jerk": {"j_max": 5000, "a_max": 1000},
    "high_jerk": {"j_max": 500000, "a_max": 3000, "v_max": 300},
    "trapezoid": {"profile": "trapezoid"},
}
SLOWER_S = 0.0006  # more than half a tick at 1 kHz


def random_job(rng):
    lines = ["G21 G90 G17", "G0 X0 Y0 Z0", "F%d" % rng.choice([600, 1500, 3000, 6000])]
    x = y = 0.0
    heading = rng.uniform(0, 2 * math.pi)
    for _ in range(rng.randint(20, 80)):
        if rng.random() < 0.15:
            lines.append("F%d" % rng.choice([600, 1500, 3000, 6000, 9000]))
        if rng.random() < 0.5:
            length = rng.choice([0.2, 0.5, 1, 3, 8, 20]) * rng.uniform(0.5, 1.5)
            heading += math.radians(rng.choice([0, 1, 3, 5, 10, 20, 45, 90, 135]) * rng.choice([-1, 1]))
            x += length * math.cos(heading)
            y += length * math.sin(heading)
            lines.append("G1 X%.4f Y%.4f" % (x, y))
            continue
        radius = rng.choice([0.5, 2, 5, 20, 50])
        sweep = math.radians(rng.uniform(5, 170))
        clockwise = rng.random() < 0.5
        side = -1 if clockwise else 1
        cx, cy = x - side * radius * math.sin(heading), y + side * radius * math.cos(heading)
        end_angle = math.atan2(y - cy, x - cx) + side * sweep
        ex, ey = cx + radius * math.cos(end_angle), cy + radius * math.sin(end_angle)
        lines.append("%s X%.4f Y%.4f I%.4f J%.4f" % ("G2" if clockwise else "G3", ex, ey, cx - x, cy - y))
        x, y = ex, ey
        heading += side * sweep + math.radians(rng.choice([0, 0, 2, 30]) * rng.choice([-1, 1]))
    return "\n".join(lines + ["M2"]) + "\n"


def run(curvestep, job, machine, smoothed):
    extra = [] if smoothed else ["--blend-tolerance", "0"]
    done = subprocess.run([curvestep, "sim", job, "--machine", machine] + extra, capture_output=True, text=True)
    if done.returncode not in (0, 3):  # 3: the run exceeded a limit, which the report below counts
        raise RuntimeError("%s sim %s failed (%d): %s" % (curvestep, job, done.returncode, done.stderr.strip()))
    out = done.stdout
    duration = next(float(l.split()[1]) for l in out.splitlines() if l.strip().startswith("duration:"))
    return duration, done.returncode == 3


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("curvestep")
    parser.add_argument("before", nargs="?")
    parser.add_argument("--jobs", type=int, default=40)
    parser.add_argument("--seed", type=int, default=15)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    with open(MACHINE) as f:
        base = json.load(f)
    results = {}
    failed = False
    with tempfile.TemporaryDirectory() as scratch:
        jobs = []
        for n in range(args.jobs):
            jobs.append(os.path.join(scratch, "job%02d.ngc" % n))
            with open(jobs[-1], "w") as f:
                f.write(random_job(rng))
        for name, change in VARIANTS.items():
            machine = os.path.join(scratch, name if name.endswith(".json") else name + ".json")
            with open(machine, "w") as f:
                json.dump({**base, **change}, f)
            entry = {}
            times = {}
            for label, binary in (("after", args.curvestep), ("before", args.before)):
                if binary is None:
                    continue
                smoothed = [run(binary, job, machine, True) for job in jobs]
                raw = [run(binary, job, machine, False) for job in jobs]
                times[label] = [s for s, _ in smoothed]
                entry[label] = {
                    "smoothed_s": round(sum(times[label]), 3),
                    "as_programmed_s": round(sum(r for r, _ in raw), 3),
                    "slower_smoothed": [os.path.basename(j) for j, (s, _), (r, _) in zip(jobs, smoothed, raw) if s > r + SLOWER_S],
                    "violations": [os.path.basename(j) for j, (_, vs), (_, vr) in zip(jobs, smoothed, raw) if vs or vr],
                }
                failed = failed or bool(entry[label]["violations"])
            if "before" in times:
                entry["slower_than_before"] = [os.path.basename(j) for j, a, b in zip(jobs, times["after"], times["before"])
                                               if a > b + SLOWER_S]
            results[name] = entry
    print(json.dumps({"benchmark": "random_jobs", "jobs": args.jobs, "seed": args.seed, "machines": results}, indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
