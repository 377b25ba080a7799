"""The hint hook of the results layer: names the likely known mistake behind a lab's failed
tests, from the failure signatures of the mutant catalogue (tools/wbgrade_hints.py,
tests/mutants/<lab>/signatures.json; docs/grading.md, "Failure signatures and hints").

Trust: reads only the verdict's results (test names, pass/fail, the capped failure texts) and
the pristine signatures; never student code."""
import os
import sys

_TOOLS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if _TOOLS not in sys.path:
    sys.path.insert(0, _TOOLS)
import wbgrade_hints  # noqa: E402  (the one matcher, shared with tools/mutants)

_REPO = os.path.dirname(_TOOLS)


def hints_for(lab, results):
    """results: [(test name, passed?, output)] of one graded lab; returns the hint lines
    ([] when nothing is close, or the lab has no signatures)."""
    return wbgrade_hints.hints_for_results(_REPO, lab, results)
