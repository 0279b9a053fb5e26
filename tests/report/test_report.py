#!/usr/bin/env python3
"""Unit tests of report.py's pure parts: timings, ratios and their noise marks
(report_timing.py), and the Markdown spans of its HTML (report_doc.py). Standard library
only: python3 tests/report/test_report.py"""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_convergence  # noqa: E402
import report_convergence_doc  # noqa: E402
import report_doc  # noqa: E402
import report_timing  # noqa: E402


class FeatureSwitches(unittest.TestCase):
    SCENE = {"Scene": {
        "Cameras": {"Camera": {"NumSamples": "4", "ApertureSize": "0.5", "FocusDistance": "3"}},
        "Lights": {"AreaLight": {"Position": "0 5 0", "Size": "2", "Radiance": "10 20 30"}},
        "Materials": {"Material": [{"_id": "1"}, {"_id": "2", "Roughness": "0.1"}]},
        "Objects": {"Sphere": {"MotionBlur": "1 0 0"}, "Mesh": [{"Faces": {"_plyFile": "ply/a.ply"}}]}}}

    def test_each_feature_found_and_turned_off(self):
        switches = dict(report_convergence.feature_switches(self.SCENE))
        self.assertEqual(sorted(switches), ["area light (as a point light)", "lens", "motion blur", "roughness"])
        import json
        for name, change in switches.items():
            doc = json.loads(json.dumps(self.SCENE))
            change(doc["Scene"])
            self.assertEqual(report_convergence.feature_switches(doc).__len__(), 3, name)
        doc = json.loads(json.dumps(self.SCENE))
        switches["area light (as a point light)"](doc["Scene"])
        # The point light carries the area light's power: radiance times its area (2 x 2).
        self.assertEqual(doc["Scene"]["Lights"]["PointLight"][0]["Intensity"], "40.0 80.0 120.0")

    def test_ply_paths_made_absolute(self):
        import json
        doc = json.loads(json.dumps(self.SCENE))
        report_convergence.absolute_paths(doc, "/x/scenes")
        self.assertEqual(doc["Scene"]["Objects"]["Mesh"][0]["Faces"]["_plyFile"], "/x/scenes/ply/a.ply")

    def test_plot_is_well_formed_svg(self):
        import xml.etree.ElementTree as ET
        run = {"cpu": 1.0, "vs_converged": {"rmse": 4.0, "blocks": 1.0}}
        result = {"scene": "s.json", "spp": [dict(run, n=1), dict(run, n=4, cpu=4.0, vs_converged={"rmse": 2.0})],
                  "samplers": {"random": run, "stratified": run, "sobol": run},
                  "adaptive": [dict(run, target=2, spp=3.0)]}
        root = ET.fromstring(report_convergence_doc.svg_plot([result]))
        self.assertTrue(root.tag.endswith("svg"))


class MonteCarloFigures(unittest.TestCase):
    def test_rmse_from_the_psnr_not_its_two_decimals(self):
        # 69.52 dB: 255 / 10^3.476 = 0.08522, printed as 0.09.
        r = report_convergence.parse_mc_line(
            "vs reference        0.2500      +0.00  +0.01  -0.02  -0.01      0.09   69.52 dB")
        self.assertAlmostEqual(r["rmse"], 0.08522, places=5)
        self.assertEqual(r["blocks"], 0.25)
        self.assertEqual(r["mean"], -0.01)
        # 40.00 dB: 2.55 exactly; identical images: infinite PSNR, no error.
        self.assertAlmostEqual(report_convergence.parse_mc_line(
            "vs reference        0.0000      +0.00  +0.00  +0.00  +0.00      2.55   40.00 dB")["rmse"], 2.55, places=9)
        self.assertEqual(report_convergence.parse_mc_line(
            "vs reference        0.0000      +0.00  +0.00  +0.00  +0.00      0.00   inf")["rmse"], 0.0)


class RatioText(unittest.TestCase):
    def test_apart_spreads_give_a_plain_ratio(self):
        off = report_timing.Timing(2.0, 1.9, 2.1, 3)
        on = report_timing.Timing(1.0, 0.95, 1.05, 3)
        self.assertEqual(report_timing.ratio_text(off, on), "2.00x")

    def test_overlapping_spreads_are_within_noise(self):
        a = report_timing.Timing(1.05, 0.90, 1.20, 3)
        b = report_timing.Timing(1.00, 0.95, 1.10, 3)
        self.assertEqual(report_timing.ratio_text(a, b), "1.05x (within noise)")
        self.assertEqual(report_timing.ratio_text(b, a), "0.95x (within noise)")

    def test_touching_spreads_are_within_noise(self):
        self.assertEqual(report_timing.ratio_text(report_timing.Timing(1.2, 1.1, 1.3, 2), report_timing.Timing(1.0, 0.9, 1.1, 2)),
                         "1.20x (within noise)")

    def test_a_single_render_cannot_be_judged(self):
        self.assertEqual(report_timing.ratio_text(report_timing.Timing(1.5, 1.5, 1.5, 1), report_timing.Timing(1.0, 0.8, 1.2, 5)),
                         "1.50x (one run)")

    def test_missing_or_zero_time(self):
        self.assertEqual(report_timing.ratio_text(None, report_timing.Timing(1, 1, 1, 3)), "—")
        self.assertEqual(report_timing.ratio_text(report_timing.Timing(1, 1, 1, 3), report_timing.Timing(0, 0, 0, 3)), "—")

    def test_totals_sum_medians_and_extremes(self):
        t = report_timing.Timing.total([report_timing.Timing(1, 0.5, 2, 3), report_timing.Timing(3, 2, 4, 5)])
        self.assertEqual((t.median, t.lo, t.hi, t.n), (4, 2.5, 6, 3))
        self.assertIsNone(report_timing.Timing.total([report_timing.Timing(1, 1, 1, 1), None]))
        self.assertIsNone(report_timing.Timing.total([]))


class HtmlInline(unittest.TestCase):
    def test_bold_and_code_spans(self):
        self.assertEqual(report_doc.html_inline("**all**"), "<strong>all</strong>")
        self.assertEqual(report_doc.html_inline("`a<b` and **x & y**"), "<code>a&lt;b</code> and <strong>x &amp; y</strong>")

    def test_asterisks_inside_code_stay(self):
        self.assertEqual(report_doc.html_inline("`**not bold**`"), "<code>**not bold**</code>")

    def test_the_culling_table_total_row_is_bold_in_html(self):
        doc = report_doc.Doc()
        doc.table(["scene", "time"], [["**all**", "1.0"]])
        page = doc.html("t")
        self.assertIn("<strong>all</strong>", page)
        self.assertNotIn("**", page)


if __name__ == "__main__":
    unittest.main()
