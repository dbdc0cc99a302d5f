# SPDX-License-Identifier: MIT
"""Polyline jobs of the kinds users have (CAM posts, plotter art), as G-code, with their programmed
moves for independent checks. Deterministic: the same files every run.

    python3 make_jobs.py OUT_DIR [--small]

Each job is a list of moves (start, end, 'rapid' | 'feed', feed_mm_per_s) and its G-code text.
"""
import math
import os
import sys

FEED = 50.0  # mm/s (F3000)

# A stroke font of straight lines for the letters the text job writes: strokes of (x, y) in a
# 4 x 6 box; each stroke is drawn pen-down, pen-up rapids between strokes.
STROKES = {
    "C": [[(4, 1), (3, 0), (1, 0), (0, 1), (0, 5), (1, 6), (3, 6), (4, 5)]],
    "U": [[(0, 6), (0, 1), (1, 0), (3, 0), (4, 1), (4, 6)]],
    "R": [[(0, 0), (0, 6), (3, 6), (4, 5), (4, 4), (3, 3), (0, 3)], [(2, 3), (4, 0)]],
    "V": [[(0, 6), (2, 0), (4, 6)]],
    "E": [[(4, 0), (0, 0), (0, 6), (4, 6)], [(0, 3), (3, 3)]],
    "S": [[(4, 5), (3, 6), (1, 6), (0, 5), (0, 4), (1, 3), (3, 3), (4, 2), (4, 1), (3, 0), (1, 0), (0, 1)]],
    "T": [[(0, 6), (4, 6)], [(2, 6), (2, 0)]],
    "P": [[(0, 0), (0, 6), (3, 6), (4, 5), (4, 4), (3, 3), (0, 3)]],
}


class Job:
    def __init__(self, name):
        self.name = name
        self.moves = []
        self.position = (0.0, 0.0, 0.0)
        self.arc = None  # (centre, radius) for the one-arc circle

    def rapid(self, p):
        p = tuple(round(c, 4) for c in p)
        if p != self.position:
            self.moves.append((self.position, p, "rapid", 0.0))
        self.position = p

    def feed(self, p):
        p = tuple(round(c, 4) for c in p)
        if p != self.position:
            self.moves.append((self.position, p, "feed", FEED))
        self.position = p

    def gcode(self):
        lines = ["%", "(curvestep path_speed benchmark: %s)" % self.name, "G21 G90 G17"]
        if self.arc is not None:
            (cx, cy), r = self.arc
            lines.append("G0 X%.4f Y%.4f" % (cx + r, cy))
            lines.append("G3 X%.4f Y%.4f I%.4f J0 F3000" % (cx + r, cy, -r))
        for _start, end, kind, _feed in self.moves:
            if kind == "rapid":
                lines.append("G0 X%.4f Y%.4f Z%.4f" % end)
            else:
                lines.append("G1 X%.4f Y%.4f Z%.4f F3000" % end)
        lines += ["M2", "%"]
        return "\n".join(lines) + "\n"

    def length(self, kind="feed"):
        return sum(math.dist(s, e) for s, e, k, _ in self.moves if k == kind)


def circle_arc():
    job = Job("circle_arc")
    job.arc = ((0.0, 0.0), 20.0)
    return job


def circle_chords(n):
    job = Job("circle_%d_chords" % n)
    job.rapid((20.0, 0.0, 0.0))
    for i in range(1, n + 1):
        a = 2 * math.pi * i / n
        job.feed((20 * math.cos(a), 20 * math.sin(a), 0.0))
    return job


def spiral(points):
    job = Job("spiral_%d_points" % points)
    for i in range(points):
        t = i / (points - 1)
        a = t * 5 * 2 * math.pi
        r = 2 + 38 * t
        p = (r * math.cos(a), r * math.sin(a), 0.0)
        job.rapid(p) if i == 0 else job.feed(p)
    return job


def raster(rows, width=50.0):
    """A 3-axis finishing pass over z = 2 sin(x/8) cos(y/10): rows in x with steps of 0.1 to 0.5 mm."""
    job = Job("cam_raster_%d_rows" % rows)
    xs = [0.0]
    i = 0
    while xs[-1] < width:
        i += 1
        xs.append(min(width, xs[-1] + 0.3 + 0.2 * math.sin(1.7 * i)))
    surface = lambda x, y: 2 * math.sin(x / 8) * math.cos(y / 10)  # noqa: E731
    job.rapid((0.0, 0.0, surface(0, 0) + 5))
    for row in range(rows):
        y = 0.5 * row
        order = xs if row % 2 == 0 else xs[::-1]
        for x in order:
            job.feed((x, y, surface(x, y)))
    return job


def zigzag_pocket(rows, width=30.0, step=1.0):
    job = Job("zigzag_pocket_%d_rows" % rows)
    job.rapid((0.0, 0.0, 0.0))
    for row in range(rows):
        y = row * step
        x_end = width if row % 2 == 0 else 0.0
        job.feed((x_end, y, 0.0))
        job.feed((x_end, y + step, 0.0))
    return job


def text(word="CURVESTEP", size=2.0):
    job = Job("text_" + word.lower())
    for index, letter in enumerate(word):
        x0 = index * 6 * size / 1.0
        for stroke in STROKES[letter]:
            points = [(x0 + x * size, y * size, 0.0) for x, y in stroke]
            job.rapid(points[0])
            for p in points[1:]:
                job.feed(p)
    return job


def hatch(lines=100, length=10.0, pitch=0.2):
    job = Job("hatch_%d_lines" % lines)
    for i in range(lines):
        y = i * pitch
        a, b = ((0.0, y, 0.0), (length, y, 0.0)) if i % 2 == 0 else ((length, y, 0.0), (0.0, y, 0.0))
        job.rapid(a)
        job.feed(b)
    return job


def all_jobs(small=False):
    jobs = [circle_arc(), circle_chords(36), circle_chords(360), circle_chords(3600 if not small else 1000), spiral(2000),
            raster(20 if not small else 6), zigzag_pocket(20), text(), hatch()]
    return jobs


def main():
    if "-h" in sys.argv or "--help" in sys.argv:
        print(__doc__)
        return
    unknown = [a for a in sys.argv[1:] if a.startswith("-") and a != "--small"]
    if unknown:
        sys.exit("make_jobs.py: unknown option " + unknown[0] + " (usage: make_jobs.py OUT_DIR [--small])")
    folders = [a for a in sys.argv[1:] if not a.startswith("-")]
    out = folders[0] if folders else "."
    small = "--small" in sys.argv
    os.makedirs(out, exist_ok=True)
    for job in all_jobs(small):
        with open(os.path.join(out, job.name + ".ngc"), "w") as f:
            f.write(job.gcode())
    print(out)


if __name__ == "__main__":
    main()
