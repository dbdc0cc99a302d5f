# SPDX-License-Identifier: MIT
"""The least time a jerk-limited machine can lose on a raster's row turnaround, within a path tolerance,
found by linear programming (needs SciPy: Debian's python3-scipy), against grbl's model of the same
turnaround. An independent bound: it knows nothing of curvestep's planner or blends.

    /usr/bin/python3 turnaround_bound.py [--a 2000] [--j 50000] [--feed 50] [--step 0.5] [--tol 0.01]
                                         [--dt 0.0005] [--deviation 0.02 0.01] [--checks 4]

The turnaround: a row along +x ends at the corner (0, 0), a step of `step` mm along +y, the next row
back along -x. The tool comes in at the feed with zero acceleration and must leave at the feed along
-x with zero acceleration. Lost time = the turnaround's time - the programmed length covered / feed.

The bound is a relaxation of the real problem, so its least lost time is at most that of any machine
with these limits:
  * the whole-vector limits |v| <= feed, |a| <= a_max, |j| <= j_max are relaxed to the octagons
    |c_x|, |c_y| <= L and |c_x +- c_y| <= sqrt(2) L, which contain the discs;
  * the path tolerance is checked only at the check points (every sample `dt`, and `checks` - 1
    points between two samples), as the tubes of radius `tol` around the programmed row 1, step and
    row 2, passed in that order (after check point p_a the tool is in the step's tube, from p_b on in
    row 2's); the switches are searched on a grid of samples, then point by point. Checked only at
    the samples (--checks 1), the optimum cuts a corner between two samples;
  * the jerk is constant between samples. This one restricts rather than relaxes: a switch of the
    jerk between samples costs at most one sample, so the bound is shown at two `dt`.

It prints JSON: the least lost time per turnaround, the grbl model's lost time for the same geometry
(trapezoids, velocity jumps at its junction speeds: no jerk limit) at each junction deviation, and
each path's deviation from the programmed corner (the grbl model follows the polyline with velocity
jumps, so its own path deviation is 0; the circle its junction speed stands for lies delta inside the
corner).
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy import sparse
from scipy.optimize import linprog

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import grbl_model  # noqa: E402


class Turnaround:
    """The LP of one turnaround, sampled every dt: per axis the jerks j_0..j_{n-1} and the states
    a, v, s at the samples 0..n, tied by the exact integration of a constant jerk over dt."""

    def __init__(self, a_max, j_max, feed, step, tol, dt, horizon_s, lead_mm, checks=1):
        self.checks = checks
        self.a_max, self.j_max, self.feed, self.step, self.tol, self.dt = a_max, j_max, feed, step, tol, dt
        self.n = int(round(horizon_s / dt))
        self.lead = lead_mm
        n = self.n
        self.size = 2 * (n + 3 * (n + 1))
        self._equalities()
        self._diagonals()

    def index(self, axis, quantity, k):
        """Variable index: axis 0 (x) or 1 (y); quantity 'j' (k < n), 'a', 'v' or 's' (k <= n)."""
        n = self.n
        base = axis * (n + 3 * (n + 1))
        if quantity == "j":
            return base + k
        return base + n + "avs".index(quantity) * (n + 1) + k

    def _equalities(self):
        n, dt = self.n, self.dt
        rows, cols, vals = [], [], []
        row = 0
        for axis in (0, 1):
            for k in range(n):
                terms = (
                    ((("a", k + 1), 1.0), (("a", k), -1.0), (("j", k), -dt)),
                    ((("v", k + 1), 1.0), (("v", k), -1.0), (("a", k), -dt), (("j", k), -dt * dt / 2)),
                    ((("s", k + 1), 1.0), (("s", k), -1.0), (("v", k), -dt), (("a", k), -dt * dt / 2),
                     (("j", k), -dt ** 3 / 6)),
                )
                for equation in terms:
                    for (quantity, i), value in equation:
                        rows.append(row)
                        cols.append(self.index(axis, quantity, i))
                        vals.append(value)
                    row += 1
        self.a_eq = sparse.csr_matrix((vals, (rows, cols)), shape=(row, self.size))
        self.b_eq = np.zeros(row)

    def _diagonals(self):
        """|c_x +- c_y| <= sqrt(2) L for acceleration, velocity and jerk: the octagons' slanted sides
        (their straight sides are variable bounds)."""
        n = self.n
        rows, cols, vals, bound = [], [], [], []
        row = 0
        for quantity, limit, count in (("a", self.a_max, n + 1), ("v", self.feed, n + 1), ("j", self.j_max, n)):
            for k in range(count):
                for sx, sy in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                    rows += [row, row]
                    cols += [self.index(0, quantity, k), self.index(1, quantity, k)]
                    vals += [sx, sy]
                    bound.append(math.sqrt(2) * limit)
                    row += 1
        self.a_ub = sparse.csr_matrix((vals, (rows, cols)), shape=(row, self.size))
        self.b_ub = np.array(bound)

    def _tube(self, p, p_a, p_b):
        """The tube that check point p lies in, as (x_low, x_high, y_low, y_high)."""
        tol, step = self.tol, self.step
        if p <= p_a:  # row 1
            return -np.inf, tol, -tol, tol
        if p < p_b:  # the step
            return -tol, tol, -tol, step + tol
        return -np.inf, tol, step - tol, step + tol  # row 2

    def _between_samples(self, p_a, p_b):
        """The tubes checked between the samples, at checks - 1 points in every interval: the position
        there is linear in the interval's start state and jerk."""
        if self.checks == 1:
            return self.a_ub, self.b_ub
        rows, cols, vals, bound = [], [], [], []
        for k in range(self.n):
            for m in range(1, self.checks):
                tau = self.dt * m / self.checks
                x_low, x_high, y_low, y_high = self._tube(k * self.checks + m, p_a, p_b)
                terms = (("s", 1.0), ("v", tau), ("a", tau * tau / 2), ("j", tau ** 3 / 6))
                for axis, low, high in ((0, x_low, x_high), (1, y_low, y_high)):
                    for sign, value in ((1.0, high), (-1.0, -low)):
                        if not math.isfinite(value):
                            continue
                        row = len(bound)
                        for quantity, c in terms:
                            rows.append(row)
                            cols.append(self.index(axis, quantity, k))
                            vals.append(sign * c)
                        bound.append(value)
        extra = sparse.csr_matrix((vals, (rows, cols)), shape=(len(bound), self.size))
        return sparse.vstack([self.a_ub, extra]).tocsr(), np.concatenate([self.b_ub, np.array(bound)])

    def solve(self, p_a, p_b):
        """Largest distance back along row 2 at the horizon, for the phase switches p_a < p_b (check
        points: the samples times `checks`; the tool is in the step's tube after check point p_a and in
        row 2's from p_b on); None if infeasible."""
        n, tol, step = self.n, self.tol, self.step
        lo = np.full(self.size, -np.inf)
        hi = np.full(self.size, np.inf)

        def box(axis, quantity, k, low, high):
            i = self.index(axis, quantity, k)
            lo[i], hi[i] = max(lo[i], low), min(hi[i], high)

        for axis in (0, 1):
            for k in range(n):
                box(axis, "j", k, -self.j_max, self.j_max)
            for k in range(n + 1):
                box(axis, "a", k, -self.a_max, self.a_max)
                box(axis, "v", k, -self.feed, self.feed)
        for k in range(n + 1):
            x_low, x_high, y_low, y_high = self._tube(k * self.checks, p_a, p_b)
            box(0, "s", k, x_low, x_high)
            box(1, "s", k, y_low, y_high)
        # Start: along +x at the feed, lead_mm before the corner; end: along -x at the feed, at rest in y.
        for axis, s0, v0 in ((0, -self.lead, self.feed), (1, 0.0, 0.0)):
            box(axis, "s", 0, s0, s0)
            box(axis, "v", 0, v0, v0)
            box(axis, "a", 0, 0.0, 0.0)
        box(0, "v", n, -self.feed, -self.feed)
        box(0, "a", n, 0.0, 0.0)
        box(1, "v", n, 0.0, 0.0)
        box(1, "a", n, 0.0, 0.0)
        if np.any(lo > hi):
            return None
        cost = np.zeros(self.size)
        cost[self.index(0, "s", n)] = 1.0  # maximise the distance back: minimise x_n
        a_ub, b_ub = self._between_samples(p_a, p_b)
        result = linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=self.a_eq, b_eq=self.b_eq,
                         bounds=list(zip(lo, hi)), method="highs")
        if result.status != 0:
            return None
        return -result.fun

    def lost_time(self, back_mm):
        covered = self.lead + self.step + back_mm
        return self.n * self.dt - covered / self.feed

    def least_lost_time(self, coarse, seed=None):
        """Search the phase switches: a coarse grid of samples (around `seed`, the switch times of a
        coarser search, when given), then every check point around the best pair."""
        best = None
        n, m = self.n, self.checks
        if seed is None:
            pairs = [(k_a, k_b) for k_a in range(0, n, coarse) for k_b in range(k_a + coarse, n, coarse)]
        else:
            centre_a, centre_b = (int(round(t / self.dt)) for t in seed)
            window = range(-3 * coarse, 3 * coarse + 1, coarse)
            pairs = [(centre_a + i, centre_b + k) for i in window for k in window
                     if 0 <= centre_a + i < centre_b + k < n]
        for k_a, k_b in pairs:
            back = self.solve(k_a * m, k_b * m)
            if back is not None and (best is None or back > best[0]):
                best = (back, k_a * m, k_b * m)
        if best is None:
            return None
        last = n * m
        reach = coarse * m
        improved = True
        while improved:
            improved = False
            _, p_a0, p_b0 = best
            for p_a in range(max(0, p_a0 - reach), min(last, p_a0 + reach + 1)):
                for p_b in range(p_b0 - m, p_b0 + m + 1):
                    if p_b <= p_a or p_b >= last or (p_a, p_b) == (p_a0, p_b0):
                        continue
                    back = self.solve(p_a, p_b)
                    if back is not None and back > best[0] + 1e-12:
                        best, improved = (back, p_a, p_b), True
            reach = m
        back, p_a, p_b = best
        check_dt = self.dt / m
        return {"lost_s": round(self.lost_time(back), 5), "step_tube_from_s": round(p_a * check_dt, 5),
                "row2_tube_from_s": round(p_b * check_dt, 5), "samples": n, "dt_s": self.dt,
                "checks_per_sample": m}


def grbl_lost_time(a_max, feed, step, deviation, lead_mm=5.0):
    """grbl's model on the same turnaround (unbounded buffer, ends at rest far enough away)."""
    machine = {"v_max": 1e9, "a_max": a_max, "axes": {}}
    tail = 50.0
    moves = [((-lead_mm, 0.0, 0.0), (0.0, 0.0, 0.0), "feed", feed), ((0.0, 0.0, 0.0), (0.0, step, 0.0), "feed", feed),
             ((0.0, step, 0.0), (-tail, step, 0.0), "feed", feed)]
    # The same job without the turnaround's two corners: the lead and the tail at feed. Both start and end
    # at rest, so the difference is the turnaround's lost time.
    blocks = grbl_model.blocks_from_moves(moves, machine)
    total = grbl_model.job_time(blocks, deviation, None)
    straight = grbl_model.job_time(grbl_model.blocks_from_moves(
        [((0.0, 0.0, 0.0), (lead_mm + step + tail, 0.0, 0.0), "feed", feed)], machine), deviation, None)
    corner_speed = grbl_model.junction_speed(blocks[0], blocks[1], deviation)
    radius = deviation * math.cos(math.pi / 4) / (1 - math.cos(math.pi / 4))
    return {"junction_deviation_mm": deviation, "lost_s": round(total - straight, 5),
            "corner_speed_mm_per_s": round(corner_speed, 4),
            "equivalent_circle_radius_mm": round(radius, 5),
            "path_deviation_of_the_model_mm": 0.0,
            "equivalent_circle_deviation_mm": deviation}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--a", type=float, default=2000.0)
    parser.add_argument("--j", type=float, default=50000.0)
    parser.add_argument("--feed", type=float, default=50.0)
    parser.add_argument("--step", type=float, default=0.5)
    parser.add_argument("--tol", type=float, default=0.01)
    parser.add_argument("--dt", type=float, nargs="+", default=[0.005, 0.0025, 0.00125])
    parser.add_argument("--deviation", type=float, nargs="+", default=[0.02, 0.01])
    parser.add_argument("--horizon", type=float, default=0.26)
    parser.add_argument("--lead", type=float, default=2.2)
    parser.add_argument("--checks", type=int, default=4, help="tube checks per sample interval")
    args = parser.parse_args()
    bounds = []
    seed = None
    for dt in sorted(args.dt, reverse=True):
        problem = Turnaround(args.a, args.j, args.feed, args.step, args.tol, dt, args.horizon, args.lead, args.checks)
        found = problem.least_lost_time(max(1, int(round((0.01 if seed is None else 0.005) / dt))), seed)
        bounds.append(found)
        if found:
            seed = (found["step_tube_from_s"], found["row2_tube_from_s"])
    report = {"benchmark": "turnaround_bound", "a_max": args.a, "j_max": args.j, "feed": args.feed, "step_mm": args.step,
              "tolerance_mm": args.tol, "jerk_limited_least_lost_time": bounds,
              "grbl_model": [grbl_lost_time(args.a, args.feed, args.step, d) for d in args.deviation]}
    print(json.dumps(report, indent=2))


if __name__ == "__main__":
    main()
