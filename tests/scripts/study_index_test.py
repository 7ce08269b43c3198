#!/usr/bin/python3
"""studies/index.toml lists every study exactly once: every folder under studies/ (except common/) and every
results/<name>/ folder has one [name] table, and every table names an existing studies/<name>/ and results/<name>/.
Every main = "full" study has headline claims (studies/<name>/claims.py with a claim_* function; docs/claims.md).
Its fields are the ones scripts/run_studies.py accepts. Run by ctest (label results); Python 3.11 stdlib only."""
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


if __name__ == "__main__":
    unittest.main()
