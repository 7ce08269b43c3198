#!/usr/bin/python3
"""The results map (results/README.md) is current and every headline comes from data: `results_map.py --check` passes
on the committed tree, a stale map fails it, a headline key missing from a study's data is an error naming the study
and the key, and every headline template has placeholders (no hand-typed finding). Run by ctest (label results);
Python 3.11 stdlib only."""
import contextlib
import io
import os
import re
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import results_map  # noqa: E402


class ResultsMapTest(unittest.TestCase):
    def test_committed_map_is_current(self):
        run = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "results_map.py"), "--check"],
                             capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, "results/README.md is stale or a headline key is missing:\n" + run.stderr)

    def test_stale_map_fails_the_check(self):
        with tempfile.TemporaryDirectory() as tmp:
            stale = os.path.join(tmp, "README.md")
            with open(stale, "w", encoding="utf-8") as f:
                f.write(results_map.render().replace("| full |", "| no |", 1))
            saved = results_map.OUT
            results_map.OUT = stale
            try:
                with contextlib.redirect_stderr(io.StringIO()) as err:
                    self.assertEqual(results_map.main(["results_map.py", "--check"]), 1)
                self.assertIn("stale", err.getvalue())
                os.remove(stale)  # a missing map is stale too
                with contextlib.redirect_stderr(io.StringIO()):
                    self.assertEqual(results_map.main(["results_map.py", "--check"]), 1)
            finally:
                results_map.OUT = saved

    def test_missing_key_names_study_and_key(self):
        index = results_map.load_index()
        for name in ("critical-tension", "gms-speed"):  # one from summary.json, one through an extractor
            entry = dict(index[name])
            entry["headline"] += " {no_such_key_xyz}"
            with self.assertRaises(results_map.MapError) as ctx:
                results_map.headline(name, entry)
            self.assertIn(f"'{name}'", str(ctx.exception))
            self.assertIn("no_such_key_xyz", str(ctx.exception))

    def test_missing_key_fails_the_script(self):
        index = results_map.load_index()
        saved = results_map.load_index
        broken = {k: dict(v) for k, v in index.items()}
        broken["swegle"]["headline"] += " {no_such_key_xyz}"
        results_map.load_index = lambda: broken
        try:
            with contextlib.redirect_stderr(io.StringIO()) as err:
                self.assertEqual(results_map.main(["results_map.py", "--check"]), 1)
            self.assertIn("swegle", err.getvalue())
            self.assertIn("no_such_key_xyz", err.getvalue())
        finally:
            results_map.load_index = saved

    def test_every_headline_is_a_template(self):
        for name, entry in results_map.load_index().items():
            self.assertRegex(entry["headline"], r"\{[^{}]+\}", f"[{name}] headline has no placeholder")
            if not os.path.exists(os.path.join(ROOT, "results", name, "summary.json")):
                self.assertIn("extract", entry, f"[{name}] has no summary.json and no extractor")

    def test_one_row_per_study_in_its_family(self):
        text = results_map.render()
        index = results_map.load_index()
        rows = re.findall(r"(?m)^\| `([^`]+)` \|", text)
        self.assertEqual(rows, [n for f in results_map.FAMILIES for n, e in index.items() if e["family"] == f])


if __name__ == "__main__":
    unittest.main()
