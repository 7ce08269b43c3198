#!/usr/bin/python3
"""Run the headline claims of the studies against their committed results (docs/claims.md).

    claims_test.py [NAME ...]     the studies/<NAME>/claims.py given, or every study that has one

Prints one line per claim (PASS/FAIL, study, claim, message) and exits 1 when any claim fails or a named study has no
claims. Run by ctest (label results), one test per study. Python 3.11 standard library only.
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import claims  # noqa: E402


def main(argv):
    names = argv[1:] or claims.studies_with_claims(ROOT)
    failed = 0
    total = 0
    for name in names:
        results = claims.run_claims(name, ROOT)
        if not results:
            print(f"FAIL {name}: no studies/{name}/claims.py with a claim_* function")
            failed += 1
            continue
        for claim, ok, message in results:
            total += 1
            failed += not ok
            print(f"{'PASS' if ok else 'FAIL'} {name}.{claim}" + (f": {message}" if message else ""))
    print(f"{total} claims in {len(names)} studies, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
