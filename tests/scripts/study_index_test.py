#!/usr/bin/python3
"""studies/index.toml lists every study exactly once: every folder under studies/ (except common/) and every
results/<name>/ folder has one [name] table, and every table names an existing studies/<name>/ and results/<name>/.
Every main = "full" study has headline claims (studies/<name>/claims.py with a claim_* function; docs/claims.md).
Its fields are the ones scripts/run_studies.py accepts. Every stored --quick reference (tests/study_quick/<name>/, the
ctest label "study") belongs to a study with a --quick case, and the comparison it runs catches a changed value.
Run by ctest (label results); Python 3.11 stdlib only."""
import os
import re
import sys
import tomllib
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))


def folders(parent, skip=()):
    path = os.path.join(ROOT, parent)
    return {d for d in os.listdir(path) if os.path.isdir(os.path.join(path, d)) and d not in skip}


class StudyIndexTest(unittest.TestCase):
    def setUp(self):
        with open(os.path.join(ROOT, "studies", "index.toml"), "rb") as f:
            self.text = f.read().decode("utf-8")
            self.index = tomllib.loads(self.text)

    def test_each_table_once(self):
        # tomllib already refuses a repeated table; count the headers too so the message names the study.
        headers = re.findall(r"(?m)^\[([^\]]+)\]\s*$", self.text)
        repeated = sorted({h for h in headers if headers.count(h) > 1})
        self.assertEqual(repeated, [], "studies/index.toml lists these studies more than once")

    def test_every_study_folder_listed(self):
        missing = sorted(folders("studies", skip=("common",)) - set(self.index))
        self.assertEqual(missing, [], "study folders not in studies/index.toml")

    def test_every_results_folder_listed(self):
        missing = sorted(folders("results") - set(self.index))
        self.assertEqual(missing, [], "results/ folders not in studies/index.toml")

    def test_every_listed_study_exists(self):
        studies, results = folders("studies"), folders("results")
        self.assertEqual(sorted(set(self.index) - studies), [], "listed studies without a studies/<name>/ folder")
        self.assertEqual(sorted(set(self.index) - results), [], "listed studies without a results/<name>/ folder")

    def test_run_studies_accepts_the_index(self):
        import run_studies
        self.assertEqual(list(run_studies.load_index()), list(self.index))

    def test_full_studies_have_claims(self):
        # Every study of the default main job keeps its headline statements as checks on its committed CSVs
        # (studies/<name>/claims.py, run by tests/scripts/claims_test.py; docs/claims.md).
        import claims
        lacking = []
        for name, entry in self.index.items():
            if entry.get("main") != "full":
                continue
            module = claims.load_claims(name, ROOT)
            if module is None or not claims.claims_of(module):
                lacking.append(name)
        self.assertEqual(lacking, [], 'main = "full" studies without a studies/<name>/claims.py with a claim_*')

    def test_map_fields_present(self):
        for name, entry in self.index.items():
            for field in ("family", "question", "sources", "headline"):
                self.assertIn(field, entry, f"[{name}] lacks {field}")
                self.assertTrue(str(entry[field]).strip(), f"[{name}] has an empty {field}")

    def test_quick_references_belong_to_quick_studies(self):
        base = os.path.join(ROOT, "tests", "study_quick")
        for name in sorted(folders(os.path.relpath(base, ROOT))):
            driver = os.path.join(ROOT, "studies", name, "main.cpp")
            self.assertTrue(os.path.isfile(driver), f"tests/study_quick/{name}: no studies/{name}/main.cpp")
            # The flag is declared in the driver or in a header it includes (its own, or studies/common/).
            with open(driver, encoding="utf-8") as f:
                text = f.read()
            for header in re.findall(r'#include "([^"]+\.hpp)"', text):
                for path in (os.path.join(ROOT, "studies", name, header), os.path.join(ROOT, "studies", header)):
                    if os.path.isfile(path):
                        with open(path, encoding="utf-8") as f:
                            text += f.read()
            self.assertIn('"--quick"', text, f"studies/{name} has no --quick case")
            csvs = [c for c in os.listdir(os.path.join(base, name)) if c.endswith(".csv")]
            self.assertTrue(csvs, f"tests/study_quick/{name} holds no CSV")

    def test_physical_times_are_compared_and_measured_times_are_not(self):
        import compare_results
        for column in ("dt_ns", "dt", "t", "dt_limit", "t_stop", "growth_rate"):  # simulated quantities
            self.assertFalse(compare_results.is_timing_column("tl-time-step/runs.csv", column), column)
        for column in ("cpu_s", "wall_seconds", "rate_ns", "us_per_particle_step", "peak_rss_MB"):  # measurements
            self.assertTrue(compare_results.is_timing_column("gms-speed/runs.csv", column), column)

    def test_quick_comparison_catches_a_changed_value(self):
        # compare_results --subset (what tests/scripts/study_quick_test.py runs): equal to itself, and one value moved
        # by 1e-5 relative (above the tests' 1e-6) fails, as does a missing file.
        import contextlib
        import io
        import shutil
        import tempfile
        import compare_results
        reference = os.path.join(ROOT, "tests", "study_quick", "forms")
        quiet = contextlib.redirect_stdout(io.StringIO())
        with tempfile.TemporaryDirectory() as tmp, quiet:
            run = os.path.join(tmp, "run")
            shutil.copytree(reference, run)
            with open(os.path.join(run, "extra.csv"), "w") as f:
                f.write("a\n1\n")
            self.assertEqual(compare_results.main([reference, run, "--subset", "--rtol", "1e-6"]), 0)
            path = os.path.join(run, "crosscheck.csv")
            with open(path) as f:
                rows = f.read().splitlines()
            cells = rows[1].split(",")
            k = next(i for i, c in enumerate(cells) if re.fullmatch(r"-?[0-9.]+(e[-+]?[0-9]+)?", c) and float(c) != 0)
            cells[k] = repr(float(cells[k]) * (1 + 1e-5))
            rows[1] = ",".join(cells)
            with open(path, "w") as f:
                f.write("\n".join(rows) + "\n")
            self.assertEqual(compare_results.main([reference, run, "--subset", "--rtol", "1e-6"]), 1)
            os.remove(path)
            self.assertEqual(compare_results.main([reference, run, "--subset", "--rtol", "1e-6"]), 1)


if __name__ == "__main__":
    unittest.main()
