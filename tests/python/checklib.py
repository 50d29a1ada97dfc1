"""moraine: the pass/fail tally of the Python checks.

    from checklib import Checks
    check = Checks("check_thing")
    check(value == expected, "what was compared")   # prints FAIL: ... when false
    sys.exit(check.report())                        # "check_thing: N passed, M failed"; 1 if any failed
"""

import sys


class Checks:
    def __init__(self, name):
        self.name = name
        self.passed = 0
        self.failed = 0

    def __call__(self, cond, what):
        if cond:
            self.passed += 1
        else:
            self.failed += 1
            print(f"FAIL: {what}", file=sys.stderr)
        return bool(cond)

    def report(self):
        print(f"{self.name}: {self.passed} passed, {self.failed} failed")
        return 1 if self.failed else 0
