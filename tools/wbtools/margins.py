"""How widely a failed graded test misses: the factor by which its failing check exceeds its tolerance.

tools/mutants reads it from the grader's failure text of each test a mutant fails (docs/grading.md,
"Margins"). A mistake caught only within a factor WEAK of a tolerance is a weak catch: move the
tolerance by that factor (or find an implementation whose rounding differs) and it passes.

The failure text is what tools/grade prints for a test: the messages in scope (INFO) and then the
failed assertion, "file:line: REQUIRE( ... ) failed, with expansion: ...". Two forms are measured:

- a helper's message "expected E ... got G ... tolerance A [+ R * |value|]" (tests/common and the
  labs' helpers; E and G numbers or vectors "(x, y[, z])"): max over components of
  |G - E| / (A + R max(|E|, |G|));
- an expansion comparing two numbers, "a <= b" (or <, >, >=): the larger of |a|, |b| over the
  smaller (a tolerance 1e-12 missed by 0.5 is 5e11).

Anything else that fails (an exception, a crash, a flag, a count, a NaN where a number belongs)
is categorical: no tolerance can hide it (margin inf). When the printed numbers are too short to
show the difference (a scalar printed to 6 digits), the margin is unknown (None)."""
import math
import re

WEAK = 10.0  # a catch within this factor of its tolerance is weak
EPS = 2.220446049250313e-16

_NUM = r"[-+]?(?:nan|inf|(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
_VAL = rf"(?:\(\s*{_NUM}(?:\s*,\s*{_NUM})*\s*\)|{_NUM})"
_HELPER = re.compile(rf"expected\s+({_VAL})\s+got\s+({_VAL})\s+tolerance\s+({_NUM})"
                     rf"(?:\s*\+\s*({_NUM})\s*\*\s*\|value\|)?", re.IGNORECASE)
_COMPARE = re.compile(rf"with expansion:\s*({_NUM})\s*(<=|>=|<|>)\s*({_NUM})\s*$", re.IGNORECASE)


def _numbers(text):
    return [float(t) for t in re.findall(_NUM, text, re.IGNORECASE)]


def margin(output):
    """The margin of one failed test from its failure text: a float > 0 (inf: categorical), or
    None when the text shows no measurable difference."""
    lines = (output or "").splitlines()
    fail = next((k for k, l in enumerate(lines) if ") failed, with expansion:" in l), None)
    if fail is None:
        return math.inf  # an exception, a crash, a time-out: nothing a tolerance hides
    # The helper's message just before the assertion (the innermost one in scope).
    helper = list(_HELPER.finditer("\n".join(lines[:fail])))
    if helper:
        m = helper[-1]
        expected, got = _numbers(m.group(1)), _numbers(m.group(2))
        abs_tol, rel_tol = float(m.group(3)), float(m.group(4) or 0.0)
        if len(expected) != len(got):
            return math.inf
        best, shown = 0.0, False
        for e, g in zip(expected, got):
            if not (math.isfinite(e) and math.isfinite(g)):
                return math.inf
            if e == g:
                continue
            shown = True
            scale = max(abs(e), abs(g))
            tol = abs_tol + rel_tol * scale
            best = max(best, math.inf if tol <= 0 else abs(g - e) / tol)
        return best if shown else None
    m = _COMPARE.search(lines[fail])
    if m:
        a, b = float(m.group(1)), float(m.group(3))
        if not (math.isfinite(a) and math.isfinite(b)) or a * b < 0:
            return math.inf
        lo, hi = sorted((abs(a), abs(b)))
        if hi == lo:
            return None  # printed alike: the difference is below what was printed
        return math.inf if lo == 0 else hi / lo
    return math.inf  # a bool, a flag, a size, an exact comparison of values


def best(outputs):
    """A mutant's margin: the widest of its failed tests' (None when none is measurable)."""
    known = [m for m in (margin(o) for o in outputs) if m is not None]
    return max(known) if known else None


def describe(value):
    if value is None:
        return "?"
    return "inf" if math.isinf(value) else f"{value:.3g}"
