"""What the catalogue keeps of a failed test (tools/diagnosis/hints.py, failure_text): tools/mutants
compares it between runs. The hint matching these tests once covered (a lab's failed tests
matched against the stored signatures) was replaced by the diagnosis by execution, which
test_diagnosis.py covers (issue 30)."""
from diagnosis import hints


def test_failure_text_blanks_numbers_and_keeps_the_first_paragraph():
    """Defect: a signature that keeps the values a wrong program prints (they differ from run
    to run, so the stored signature goes stale at random) or the captured output after the
    reason."""
    a = hints.failure_text("step 3: expected 1.25e-3 got -7\n\noutput of the test process:\nx 42")
    assert a == "step #: expected # got #"
    assert hints.failure_text("  a   b\n c ") == "a b c"
    assert len(hints.failure_text("x" * 1000)) == hints.FAILURE_CHARS
