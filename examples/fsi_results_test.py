#!/usr/bin/python3
"""Unit tests of the analysis helpers the examples share (examples/fsi_results.py), on made-up
signals with known answers. Run: /usr/bin/python3 examples/fsi_results_test.py"""
import math
import os
import sys
import tempfile
import contextlib
import io
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fsi_results import (Checks, damped_fit, interpolate_clamped, judge_runs, read_reference_points,  # noqa: E402
                         zero_crossings)


def damped_signal(period_natural, zeta, offset, amplitude=0.025, end=4.0, dt=0.005):
    """c + A exp(-s t) cos(w t) with natural period T_n and damping ratio zeta."""
    omega_n = 2.0 * math.pi / period_natural
    sigma = zeta * omega_n
    omega = omega_n * math.sqrt(1.0 - zeta ** 2)
    time = [i * dt for i in range(int(end / dt) + 1)]
    return time, [offset + amplitude * math.exp(-sigma * t) * math.cos(omega * t) for t in time]


class DampedFit(unittest.TestCase):
    def test_recovers_natural_period_and_damping(self):
        for zeta in (0.0, 0.06, 0.1, 0.2):
            time, values = damped_signal(1.02, zeta, 0.0)
            fit = damped_fit(time, values, 2.0 * math.pi / 1.0424)
            self.assertAlmostEqual(fit["natural_period"], 1.02, delta=2e-4, msg=f"zeta {zeta}")
            self.assertAlmostEqual(fit["damping_ratio"], zeta, delta=2e-3, msg=f"zeta {zeta}")
            self.assertLess(fit["rms_residual"], 1e-3 * 0.025)  # 0.1 % of the amplitude: the grid's step

    def test_an_offset_does_not_move_the_period(self):
        # A mean level 3 % of the amplitude off zero: the zero crossings over an odd number of
        # half periods are biased by it (asserted, so that the test shows what the fit is for),
        # the fit is not.
        time, values = damped_signal(1.02, 0.08, 0.03 * 0.025)
        crossings = zero_crossings(time, values)
        odd = len(crossings) - 1 if (len(crossings) - 1) % 2 else len(crossings) - 2
        damped = 1.02 / math.sqrt(1.0 - 0.08 ** 2)
        from_crossings = 2.0 * (crossings[odd] - crossings[0]) / odd
        self.assertGreater(abs(from_crossings / damped - 1.0), 2e-3)
        fit = damped_fit(time, values, 2.0 * math.pi / 1.0424)
        self.assertAlmostEqual(fit["natural_period"], 1.02, delta=2e-4)

    def test_noise_costs_little(self):
        time, values = damped_signal(1.6, 0.03, 0.0, end=8.0)
        noisy = [v + 0.001 * math.sin(37.0 * t) * math.cos(91.0 * t) for t, v in zip(time, values)]
        fit = damped_fit(time, noisy, 2.0 * math.pi / 1.6678)
        self.assertAlmostEqual(fit["natural_period"], 1.6, delta=2e-3)

    def test_a_signal_far_from_the_guess_is_refused(self):
        time, values = damped_signal(0.3, 0.05, 0.0)
        with self.assertRaises(SystemExit) as raised:
            damped_fit(time, values, 2.0 * math.pi / 1.0424)
        self.assertIn("edge of the searched range", str(raised.exception))


class ZeroCrossings(unittest.TestCase):
    def test_interpolates_between_samples(self):
        self.assertEqual(zero_crossings([0.0, 1.0, 2.0, 3.0], [1.0, -1.0, -3.0, 1.0]), [0.5, 2.75])


class InterpolateClamped(unittest.TestCase):
    def test_linear_inside_and_the_end_values_outside(self):
        xs, ys = [0.0, 1.0, 3.0], [2.0, 4.0, 0.0]
        self.assertEqual(interpolate_clamped(xs, ys, 0.5), 3.0)
        self.assertEqual(interpolate_clamped(xs, ys, 2.0), 2.0)
        self.assertEqual(interpolate_clamped(xs, ys, 1.0), 4.0)
        self.assertEqual(interpolate_clamped(xs, ys, -1.0), 2.0)
        self.assertEqual(interpolate_clamped(xs, ys, 5.0), 0.0)


class ChecksVerdict(unittest.TestCase):
    def test_a_figure_outside_its_tolerance_fails_the_analysis(self):
        checks = Checks(digits=".4f", against="benchmark")
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            checks.check("inside", 1.005, 1.0, 0.01)
            checks.check("outside", 1.02, 1.0, 0.01)
        self.assertEqual(out.getvalue().splitlines(),
                         ["ok   inside: 1.0050 (benchmark 1.0000 +- 0.01)",
                          "FAIL outside: 1.0200 (benchmark 1.0000 +- 0.01)"])
        with self.assertRaises(SystemExit) as leaving, contextlib.redirect_stdout(io.StringIO()):
            checks.exit()
        self.assertEqual(leaving.exception.code, 1)
        passing = Checks()
        with contextlib.redirect_stdout(io.StringIO()):
            passing.check("inside", 0.0, 0.0, 0.0)
        with self.assertRaises(SystemExit) as leaving:
            passing.exit()
        self.assertEqual(leaving.exception.code, 0)


class JudgeRuns(unittest.TestCase):
    def test_reports_each_run_writes_its_figures_and_fails_on_any_failure(self):
        with tempfile.TemporaryDirectory() as first, tempfile.TemporaryDirectory() as second:
            results = [{"run_dir": first, "peak": 1.0, "time": [0, 1]},
                       {"run_dir": second, "peak": 3.0, "time": [0, 1]}]
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                status = judge_runs(results, lambda r: print(f"peak {r['peak']}"),
                                    lambda r: [] if r["peak"] < 2 else [f"peak {r['peak']} above 2"],
                                    curves=("time",))
            self.assertEqual(status, 1)
            self.assertEqual(out.getvalue().splitlines(), ["peak 1.0", "peak 3.0", "FAIL: peak 3.0 above 2"])
            with open(os.path.join(first, "analysis.json")) as handle:
                self.assertEqual(handle.read().replace(" ", "").replace("\n", ""),
                                 '{"run_dir":"' + first + '","peak":1.0}')
            with contextlib.redirect_stdout(io.StringIO()):
                self.assertEqual(judge_runs(results[:1], lambda r: None, lambda r: []), 0)


class ReadReferencePoints(unittest.TestCase):
    def write(self, text):
        handle = tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False)
        handle.write(text)
        handle.close()
        self.addCleanup(os.remove, handle.name)
        return handle.name

    def test_commas_blanks_comments_and_extra_columns(self):
        path = self.write("# t, value\n0.04, 0.0125\n\n0.08 0.034 7\n  # note\n-0.001,\t2e-5\n")
        self.assertEqual(read_reference_points(path, "give --reference FILE"),
                         [(0.04, 0.0125), (0.08, 0.034), (-0.001, 2e-5)])

    def test_a_bad_line_names_its_file_and_number(self):
        path = self.write("0.04, 0.0125\n0.08, n/a\n")
        with self.assertRaises(SystemExit) as caught:
            read_reference_points(path, "give --reference FILE")
        self.assertIn(f"{path}:2", str(caught.exception))

    def test_a_missing_file_says_how_to_give_it(self):
        with self.assertRaises(SystemExit) as caught:
            read_reference_points("/nonexistent/reference.csv", "give --reference FILE")
        self.assertIn("/nonexistent/reference.csv is missing; give --reference FILE", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
