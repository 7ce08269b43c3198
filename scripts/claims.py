#!/usr/bin/python3
"""Helpers for the headline claims of the studies (docs/claims.md).

Each studies/<name>/claims.py defines functions `claim_<what>(r)` in the order they should run. `r` is a `Results`
for results/<name>/: `r.csv(file)` reads a committed CSV into `Row`s (dicts with numbers converted, each remembering
its file and line), `r.summary` is summary.json, `r.md` the rendered summary.md, `r.template` summary.md.in and
`r.readme` the study's README.md. A claim asserts one headline statement of the study against that committed data and
raises `ClaimError` (via `check`, `approx`, `one`, ...) with a message naming the file, row and values when it does
not hold; it returns a one-line description of what it found, which tests/scripts/claims_test.py prints after PASS.

A claim must be able to fail: exact values or explicit tolerances, signs, orderings, verdict classes, counts. Timing
claims are ratios within one run, never absolute seconds. Python 3.11 standard library only.
"""
import csv
import importlib.util
import json
import math
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class ClaimError(AssertionError):
    """A claim that does not hold on the committed data; the message says where and by how much."""


class Row(dict):
    """One CSV row: values converted by `number`, plus the file (relative to the repository) and line it came from."""

    def __init__(self, values, file, line):
        super().__init__(values)
        self.file = file
        self.line = line

    def where(self):
        return f"{self.file}:{self.line}"

    def __getitem__(self, key):
        try:
            return super().__getitem__(key)
        except KeyError:
            raise ClaimError(f"{self.where()}: no column '{key}' (columns: {', '.join(self)})") from None


def number(text):
    """A CSV cell as int, float (nan, inf included) or the stripped string when it is not a number."""
    s = text.strip()
    if re.fullmatch(r"[+-]?\d+", s):
        return int(s)
    try:
        return float(s)
    except ValueError:
        return s


def verdict_class(gamma_j, gamma_m, floor):
    """The class of growth/stability_verdict.hpp's classify_verdict, written again independently: S (both rates at
    or below the floor), U (the semi-discrete growth above it), I (only the one-step map's), B (both, the map by more
    than the floor)."""
    if not gamma_j > floor:
        return "I" if gamma_m > floor else "S"
    return "B" if gamma_m - max(gamma_j, 0.0) > floor else "U"


def check(condition, message):
    if not condition:
        raise ClaimError(message)


def close(actual, expected, rel=0.0, abs_=0.0):
    """|actual - expected| <= max(rel |expected|, abs_); nan is never close."""
    if isinstance(actual, str) or isinstance(expected, str):
        return actual == expected
    if math.isnan(actual) or math.isnan(expected):
        return False
    if math.isinf(actual) or math.isinf(expected):
        return actual == expected
    return abs(actual - expected) <= max(rel * abs(expected), abs_)


def approx(actual, expected, what, rel=0.0, abs_=0.0):
    """Assert close(actual, expected, rel, abs_); `what` names the quantity and where it came from."""
    check(close(actual, expected, rel, abs_),
          f"{what}: {actual!r}, expected {expected!r} (rel {rel:g}, abs {abs_:g})")
    return actual


def matches(row, filters):
    for key, want in filters.items():
        have = row.get(key)
        if callable(want):
            if not want(have):
                return False
        elif isinstance(want, float) and isinstance(have, (int, float)):
            if not close(have, want, rel=1e-9, abs_=1e-12):
                return False
        elif have != want:
            return False
    return True


def select(rows, **filters):
    """The rows whose columns equal the filters (floats to 1e-9 relative; a callable filter is a predicate)."""
    return [row for row in rows if matches(row, filters)]


def one(rows, **filters):
    """Exactly one row matching the filters, or a ClaimError naming the file and the filters."""
    found = select(rows, **filters)
    if len(found) != 1:
        source = rows[0].file if rows else "(empty table)"
        shown = ", ".join(f"{k}={v!r}" for k, v in filters.items() if not callable(v))
        raise ClaimError(f"{source}: {len(found)} rows with {shown}, expected exactly one")
    return found[0]


def fmt(x, digits=4):
    return f"{x:.{digits}g}" if isinstance(x, float) else str(x)


class Results:
    """The committed output of one study: results/<name>/ and studies/<name>/."""

    def __init__(self, name, root=ROOT):
        self.name = name
        self.root = root
        self.dir = os.path.join(root, "results", name)
        self.study_dir = os.path.join(root, "studies", name)
        self._csv = {}
        self._summary = None

    def other(self, name):
        """The committed results of another study (a claim about a mechanism another study computes)."""
        return Results(name, self.root)

    def path(self, file):
        return os.path.join(self.dir, file)

    def rel(self, file):
        return f"results/{self.name}/{file}"

    def text(self, file, study=False):
        path = os.path.join(self.study_dir if study else self.dir, file)
        if not os.path.exists(path):
            where = f"studies/{self.name}/{file}" if study else self.rel(file)
            raise ClaimError(f"{where} does not exist")
        with open(path, encoding="utf-8") as f:
            return f.read()

    def csv(self, file):
        """The rows of results/<name>/<file> as Row dicts (cached)."""
        if file not in self._csv:
            text = self.text(file)
            reader = csv.reader(text.splitlines())
            header = next(reader)
            rows = []
            for line, cells in enumerate(reader, start=2):
                if not cells:
                    continue
                rows.append(Row(zip(header, (number(c) for c in cells)), self.rel(file), line))
            self._csv[file] = rows
        return self._csv[file]

    def column(self, file, name, **filters):
        return [row[name] for row in select(self.csv(file), **filters)]

    @property
    def summary(self):
        if self._summary is None:
            self._summary = json.loads(self.text("summary.json"))
        return self._summary

    def key(self, key):
        """summary.json[key] as a string, or a ClaimError."""
        if key not in self.summary:
            raise ClaimError(f"{self.rel('summary.json')}: no key '{key}'")
        return self.summary[key]

    def num(self, key):
        """summary.json[key] as a number (the driver writes strings)."""
        value = number(self.key(key))
        check(isinstance(value, (int, float)), f"{self.rel('summary.json')}: '{key}' = {value!r} is not a number")
        return value

    @property
    def md(self):
        return self.text("summary.md")

    @property
    def template(self):
        return self.text("summary.md.in", study=True)

    @property
    def readme(self):
        return self.text("README.md", study=True)

    def stated(self, pattern, text=None, where="summary.md", group=1, convert=True):
        """The value a regular expression captures in summary.md (or `text`), whitespace runs read as one space: the
        number or word the prose states. A ClaimError when the sentence is not there (the text changed: the claim
        must be revisited)."""
        source = re.sub(r"\s+", " ", self.md if text is None else text)  # a sentence may wrap across lines
        m = re.search(pattern, source)
        check(m is not None, f"{self.rel(where) if where == 'summary.md' else where}: no sentence matching /{pattern}/")
        return number(m.group(group)) if convert else m.group(group)


def summary_md_is_rendered(r):
    """Run before every study's own claims: results/<name>/summary.md is exactly summary.md.in rendered with
    summary.json (scripts/render_summary.py), so the claims on summary.md are claims on what the driver wrote."""
    if not os.path.exists(os.path.join(r.study_dir, "summary.md.in")):
        return "no summary.md.in"
    import render_summary
    try:
        expected = render_summary.render(r.template, r.summary)
    except KeyError as e:
        raise ClaimError(f"studies/{r.name}/summary.md.in: {e.args[0]}") from None
    check(expected == r.md, f"{r.rel('summary.md')} is not summary.md.in rendered with summary.json "
                            f"(rerun scripts/render_summary.py)")
    return f"summary.md = render(summary.md.in, summary.json), {len(r.summary)} keys"


def md_table(text, header=False):
    """The rows of a Markdown table as lists of stripped cells: the body only (the row above the |---| rule is the
    header, returned first when header=True)."""
    rows, head = [], None
    for line in text.strip().splitlines():
        line = line.strip()
        if not line.startswith("|"):
            continue
        if re.fullmatch(r"\|[\s|:-]*\|", line):
            if rows and head is None:
                head = rows.pop()
            continue
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return ([head] if header and head else []) + rows


def claims_of(module):
    """The claim_* functions of a study's claims module, in definition order."""
    funcs = [v for k, v in vars(module).items() if k.startswith("claim_") and callable(v)]
    return sorted(funcs, key=lambda f: f.__code__.co_firstlineno)


def load_claims(name, root=ROOT):
    """Import studies/<name>/claims.py (None when the study has none)."""
    path = os.path.join(root, "studies", name, "claims.py")
    if not os.path.exists(path):
        return None
    spec = importlib.util.spec_from_file_location("claims_" + name.replace("-", "_"), path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_claims(name, root=ROOT):
    """[(claim name, passed, message)] for one study; an exception other than ClaimError is a failure too."""
    module = load_claims(name, root)
    if module is None:
        return []
    r = Results(name, root)
    out = []
    for func in [summary_md_is_rendered] + claims_of(module):
        try:
            message = func(r)
            out.append((func.__name__, True, message or ""))
        except ClaimError as e:
            out.append((func.__name__, False, str(e)))
        except Exception as e:  # a claim that crashes is a failing claim, with the reason
            out.append((func.__name__, False, f"{type(e).__name__}: {e}"))
    return out


def studies_with_claims(root=ROOT):
    studies = os.path.join(root, "studies")
    return sorted(d for d in os.listdir(studies) if os.path.exists(os.path.join(studies, d, "claims.py")))
