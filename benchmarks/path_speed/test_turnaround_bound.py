# SPDX-License-Identifier: MIT
"""Hand-computed checks of the turnaround bound (turnaround_bound.py; run by CTest, skipped with exit
77 where SciPy is missing)."""
import math
import os
import sys
import unittest

try:
    import scipy  # noqa: F401
except ImportError:
    print("turnaround bound: SciPy (python3-scipy) not found, skipped")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import turnaround_bound as t  # noqa: E402

A, J, V = 2000.0, 50000.0, 50.0


class TurnaroundBoundTest(unittest.TestCase):
    def test_a_reversal_in_place_loses_the_s_curve_time_by_hand(self):
        # No step (and a negligible tolerance): x reverses from +V to -V without passing x = 0.
        # Fastest reversal: jerk -J for A/J = 0.04 s (dv 40), -A for 20/A = 0.01 s, jerk +J 0.04 s: 0.09 s,
        # v = 0 at its middle. Distance to the peak: 50*0.04 - J*0.04^3/6 = 1.466667 over the ramp (v 10
        # left), then 10*0.005 - A*0.005^2/2 = 0.025: d = 1.491667. Lost: 0.09 - 2d/V = 0.0303333 s.
        # The tube alone does not make the tool reach the corner: one sample (k + 1) must lie in the step's
        # tube, |x| <= tol, as the step of a real turnaround forces.
        # The lead is d + 0.75 mm, so the reversal starts on a sample (0.015 s in) and the jerk switches
        # fall on samples too: the sampled problem holds the continuous optimum.
        d = 50 * 0.04 - J * 0.04 ** 3 / 6 + 10 * 0.005 - A * 0.005 ** 2 / 2
        problem = t.Turnaround(A, J, V, 0.0, 1e-7, 0.005, 0.22, d + 0.75)
        back = max(b for b in (problem.solve(k, k + 2) for k in range(problem.n - 2)) if b is not None)
        expected = 0.09 - 2 * d / V
        self.assertAlmostEqual(problem.lost_time(back), expected, delta=1e-6)

    def test_checks_between_samples_keep_the_hand_computed_reversal(self):
        # The same reversal with the tube checked at 4 points per interval (check point 4 (k + 1) is
        # sample k + 1, the one in the step's tube): the continuous optimum never leaves x <= tol (its
        # peak is on a sample), so the bound must not rise above it.
        d = 50 * 0.04 - J * 0.04 ** 3 / 6 + 10 * 0.005 - A * 0.005 ** 2 / 2
        problem = t.Turnaround(A, J, V, 0.0, 1e-7, 0.005, 0.22, d + 0.75, checks=4)
        back = max(b for b in (problem.solve(4 * k + 3, 4 * k + 5) for k in range(problem.n - 2)) if b is not None)
        self.assertAlmostEqual(problem.lost_time(back), 0.09 - 2 * d / V, delta=1e-6)

    def test_checks_between_samples_raise_the_bound_below_a_feasible_turnaround(self):
        # Checked only at samples 5 ms apart, the tool may cut a corner between two samples; checked
        # between them too, the bound rises. It stays below the loss of a turnaround every machine with
        # these limits can run, worked by hand: stop at the corner (jerk-only S-curve: V < A^2/J, so
        # T = 2 sqrt(V/J), d = V T/2, lost T - d/V = sqrt(V/J)), the step of 0.5 mm rest to rest
        # (jerk-only: 0.5 = J T^3/32, peak a = J T/4 = 855 <= A), start again.
        feasible = 2 * math.sqrt(V / J) + (32 * 0.5 / J) ** (1 / 3) - 0.5 / V
        samples = t.Turnaround(A, J, V, 0.5, 0.01, 0.005, 0.26, 2.2).least_lost_time(2)["lost_s"]
        between = t.Turnaround(A, J, V, 0.5, 0.01, 0.005, 0.26, 2.2, checks=4).least_lost_time(2)["lost_s"]
        self.assertGreater(between, samples)
        self.assertLess(between, feasible)

    def test_a_step_costs_more_than_a_reversal_and_a_looser_tolerance_less(self):
        tight = t.Turnaround(A, J, V, 0.5, 0.005, 0.005, 0.26, 2.2).least_lost_time(2)
        loose = t.Turnaround(A, J, V, 0.5, 0.05, 0.005, 0.26, 2.2).least_lost_time(2)
        self.assertGreater(tight["lost_s"], 0.0303)
        self.assertLess(loose["lost_s"], tight["lost_s"])

    def test_grbl_turnaround_by_hand(self):
        # Junction speed at 90 degrees, delta 0.02: v = sqrt(2000 * 0.02 * s / (1 - s)), s = sin 45.
        # Braking 50 -> v and back loses (50 - v)^2 / (2 A V) each; the 0.5 mm step from v to v peaks at
        # sqrt(A * 0.5 + v^2) and takes 2 (peak - v) / A against 0.5 / V.
        s = math.sqrt(0.5)
        v = math.sqrt(A * 0.02 * s / (1 - s))
        peak = math.sqrt(A * 0.5 + v * v)
        expected = 2 * (V - v) ** 2 / (2 * A * V) + 2 * (peak - v) / A - 0.5 / V
        self.assertAlmostEqual(t.grbl_lost_time(A, V, 0.5, 0.02)["lost_s"], expected, delta=1e-5)


if __name__ == "__main__":
    unittest.main()
