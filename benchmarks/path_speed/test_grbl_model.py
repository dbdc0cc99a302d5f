# SPDX-License-Identifier: MIT
"""Hand-computed checks of the grbl planner model (run by CTest)."""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import grbl_model as g  # noqa: E402

FAST = [1e9, 1e9, 1e9]


def line(start, end, feed=50.0, a=2000.0):
    return g.Block(start, end, feed, FAST, FAST, a)


class GrblModelTest(unittest.TestCase):
    def test_straight_line_takes_length_over_speed_plus_speed_over_acceleration(self):
        # 100 mm at 50 mm/s, a = 2000: accelerate 0.025 s over 0.625 mm, decelerate the same,
        # cruise 98.75 mm in 1.975 s: 2.025 s = L/v + v/a.
        self.assertAlmostEqual(g.job_time([line((0, 0, 0), (100, 0, 0))], 0.02), 100 / 50 + 50 / 2000, places=12)

    def test_collinear_lines_run_as_one(self):
        blocks = [line((10 * i, 0, 0), (10 * (i + 1), 0, 0)) for i in range(10)]
        self.assertAlmostEqual(g.job_time(blocks, 0.02, None), 100 / 50 + 50 / 2000, places=9)

    def test_junction_speed_of_a_right_angle(self):
        # phi = 90 degrees: sin 45 = 0.70711, r = 0.02 * 0.70711 / 0.29289 = 0.048284 mm,
        # v = sqrt(2000 * 0.048284) = 9.82693 mm/s.
        v = g.junction_speed(line((0, 0, 0), (10, 0, 0)), line((10, 0, 0), (10, 10, 0)), 0.02)
        self.assertAlmostEqual(v, 9.82693, places=4)

    def test_right_angle_corner_time_by_hand(self):
        # Two 10 mm lines at 90 degrees, corner at v_j = 9.82693 mm/s (unbounded buffer):
        # each line: 0 -> 50 -> v_j (or back), trapezoid times summed.
        vj = math.sqrt(2000 * 0.02 * math.sqrt(0.5) / (1 - math.sqrt(0.5)))
        one = (50 / 2000) + (50 - vj) / 2000 + (10 - 50 ** 2 / 4000 - (50 ** 2 - vj ** 2) / 4000) / 50
        blocks = [line((0, 0, 0), (10, 0, 0)), line((10, 0, 0), (10, 10, 0))]
        self.assertAlmostEqual(g.job_time(blocks, 0.02, None), 2 * one, places=9)

    def test_reversal_stops(self):
        self.assertEqual(g.junction_speed(line((0, 0, 0), (10, 0, 0)), line((10, 0, 0), (0, 0, 0)), 0.02), 0.0)

    def test_a_short_buffer_is_slower_on_short_lines(self):
        blocks = [line((0.1 * i, 0, 0), (0.1 * (i + 1), 0, 0)) for i in range(500)]
        self.assertGreater(g.job_time(blocks, 0.02, 4), g.job_time(blocks, 0.02, None) * 1.05)

    def test_axis_limits_lower_speed_and_acceleration(self):
        # A 45-degree XZ move with z limited to 20 mm/s and 500 mm/s^2: |u_z| = 0.7071, so
        # v = 20 / 0.7071 = 28.28 mm/s and a = 500 / 0.7071 = 707.1 mm/s^2.
        b = g.Block((0, 0, 0), (10, 0, 10), 50, [200, 200, 20], [2000, 2000, 500], 2000)
        self.assertAlmostEqual(b.nominal, 20 / math.sqrt(0.5), places=9)
        self.assertAlmostEqual(b.acceleration, 500 / math.sqrt(0.5), places=9)


if __name__ == "__main__":
    unittest.main()
