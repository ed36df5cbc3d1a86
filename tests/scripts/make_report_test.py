"""Tests of scripts/make_report.py: the order a reviewer reads (verdict, headline numbers,
failures, plots, then the folded gate table), alt texts, well-formed HTML and a Markdown
twin with the same sections. Run: /usr/bin/python3 -m unittest tests/scripts/make_report_test.py"""
import html.parser
import importlib.util
import io
import re
import sys
import tempfile
import unittest
from contextlib import redirect_stdout
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from report_fixture import make_fixture  # noqa: E402

spec = importlib.util.spec_from_file_location("make_report", HERE.parent.parent / "scripts" / "make_report.py")
make_report = importlib.util.module_from_spec(spec)
spec.loader.exec_module(make_report)


class Images(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.images = []

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.images.append(dict(attrs))


def run(out):
    with redirect_stdout(io.StringIO()):
        rc = make_report.main(["make_report.py", str(out)])
    return rc, (out / "report.html").read_text(), (out / "report.md").read_text()


class MakeReportTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.out = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_a_passing_run_opens_with_the_verdict_and_folds_the_gates(self):
        n = make_fixture(self.out)
        rc, page, md = run(self.out)
        self.assertEqual(rc, 0)
        self.assertEqual(make_report.html_problems(page), [])
        body = page[page.index("<body>"):]
        verdict = body.index('id="verdict"')
        self.assertIn("tcasim validation: PASS", body[verdict:verdict + 300])
        self.assertIn(f"all {n} gates of 2 programs passed", body)
        # Verdict, then the headline numbers, then plots, and the gate table last, folded.
        dashboard, first_img, gates = body.index('id="dashboard"'), body.index("<img"), body.index('id="gate-table"')
        self.assertLess(verdict, dashboard)
        self.assertLess(dashboard, first_img)
        self.assertLess(first_img, gates)
        self.assertLess(body.rindex("<details", 0, gates), gates)
        self.assertNotIn("<details open", body[body.index('id="all-gates"'):])
        self.assertEqual(body.count('<tr class="gate"'), n)
        self.assertNotIn('id="failed-gates"', body)
        # The headline cards of the tables present (Fig. 5 onset span, the imbalance order, speed).
        self.assertIn("31.0 to 37.8 degC", body)
        self.assertIn("RK4: 4.00 to 4.00", body)
        self.assertIn("18 s in total", body)

    def test_every_image_has_alt_text_and_a_relative_link(self):
        make_fixture(self.out)
        _, page, md = run(self.out)
        parser = Images()
        parser.feed(page)
        self.assertEqual(len(parser.images), 4)
        for img in parser.images:
            self.assertTrue(img.get("alt", "").strip(), img)
            self.assertTrue((self.out / img["src"]).is_file(), img)
        self.assertTrue(any("Fig. 5" in img["alt"] for img in parser.images))
        self.assertTrue(any(img["alt"].startswith("Deformed shape of the a scenario") for img in parser.images))
        self.assertEqual(len(re.findall(r"!\[[^\]]+\]\(", md)), 4)

    def test_a_failed_gate_is_shown_above_the_plots_and_the_filter_starts_on_failures(self):
        make_fixture(self.out, failing_gate=True)
        rc, page, md = run(self.out)
        self.assertEqual(rc, 1)
        body = page[page.index("<body>"):]
        self.assertIn("tcasim validation: FAIL", body)
        self.assertIn("1 of 61 gates failed; 1 program-level problems", body)
        failed = body.index('id="failed-gates"')
        self.assertLess(failed, body.index("<img"))
        self.assertIn("curve 7: elongation non-decreasing", body[failed:body.index("</section>", failed)])
        self.assertIn("validate_fig5_tca: exit code 1", body)
        self.assertEqual(body.count('<tr class="gate failed"'), 1)
        self.assertIn('id="gate-only-failed" checked', body)
        self.assertIn("<details open", body[body.index('id="all-gates"'):])
        # The Markdown twin: the same verdict and failures, in the same place.
        self.assertTrue(md.startswith("# tcasim validation: FAIL\n"))
        self.assertLess(md.index("## Failed gates (1)"), md.index("## validate_fig5_tca"))
        self.assertIn("**FAIL**", md[md.index("## All gates"):])

    def test_the_markdown_twin_has_the_html_sections_in_the_same_order(self):
        make_fixture(self.out, failing_gate=True)
        _, page, md = run(self.out)
        html_order = [page.index(marker) for marker in
                      ('id="verdict"', 'id="dashboard"', 'id="failed-gates"', 'id="programs"',
                       'id="validate_fig5_tca"', 'id="validate_shapes"', 'id="all-gates"', 'id="about"')]
        md_order = [md.index(marker) for marker in
                    ("# tcasim validation", "## Headline numbers", "## Failed gates", "## Programs",
                     "## validate_fig5_tca", "## validate_shapes", "## All gates", "## About this run")]
        self.assertEqual(html_order, sorted(html_order))
        self.assertEqual(md_order, sorted(md_order))

    def test_a_program_without_gates_fails_the_report_by_name(self):
        make_fixture(self.out)
        (self.out / "validate_shapes" / "gates.csv").unlink()
        rc, page, _ = run(self.out)
        self.assertEqual(rc, 1)
        self.assertIn("validate_shapes: exited 0 but wrote no gates.csv", page)

    def test_tables_scroll_inside_their_box_and_the_page_has_a_width_limit(self):
        make_fixture(self.out)
        _, page, _ = run(self.out)
        self.assertIn("max-width: 1180px", page)
        tables = page.count("<table")
        self.assertEqual(page.count('<div class="scroll"><table'), tables)

    def test_the_table1_card_sets_calibrated_against_uncalibrated_paper_differences(self):
        d = self.out / "validate_table1_grasp"
        d.mkdir()
        (d / "table1_grasp.csv").write_text(
            "material,f12_form,calibration,mass_g,temperature_degC,measured_degC,paper_degC\n"
            "m,paper,none,1,40.0,95,93.7\nm,paper,none,2,48.0,120,114.8\n"
            "m,castigliano,expansion_scale=0.05,1,92.5,95,93.7\nm,castigliano,expansion_scale=0.05,2,120.0,120,114.8\n")
        title, headline, _, table, anchor = make_report.card_table1(self.out)
        self.assertEqual(anchor, "validate_table1_grasp")
        # Worst over the masses: |48 - 114.8| = 66.8 uncalibrated, |120 - 114.8| = 5.2 calibrated.
        self.assertEqual(headline, "5.2 degC calibrated, 66.8 to 66.8 degC uncalibrated")
        self.assertEqual(table[1], [["m, f12 paper", "66.8", "72.0"],
                                    ["m, f12 castigliano, expansion_scale=0.05", "5.2", "2.5"]])

    def test_the_dynamic_crosscheck_card_takes_the_worst_gated_case_and_lists_pending_ones(self):
        d = self.out / "validate_dynamic_crosscheck"
        d.mkdir()
        (d / "dynamic_crosscheck_summary.csv").write_text(
            "case,status,reason,finest_dt_s,shooting_steps,fe_elements,difference_over_L,"
            "extrapolated_difference_over_L,bound_over_L\n"
            "pulse,run,,1.25e-04,48,32,7.7e-07,2.5e-08,1e-06\n"
            "release,run,,1.25e-04,40,32,9.1e-05,4.0e-05,\n"
            "tendon,run,,3.125e-05,80,64,3.3e-07,1.0e-07,1e-06\n"
            "tca,pending,\"TCA drives in the FE dynamics\",,,,,,\n")
        title, headline, _, table, anchor = make_report.card_dynamic_crosscheck(self.out)
        self.assertEqual(anchor, "validate_dynamic_crosscheck")
        # The released case has no agreement bound: the headline is the worst bounded case.
        self.assertEqual(headline, "worst 7.7e-07 L (pulse)")
        self.assertEqual(table[1][1], ["release", "1.25e-04", "9.1e-05", "4.0e-05"])
        self.assertEqual(table[1][3], ["tca", "pending: TCA drives in the FE dynamics", "", ""])


if __name__ == "__main__":
    unittest.main()
