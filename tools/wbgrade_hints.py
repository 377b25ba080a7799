"""Names the likely mistake behind a set of failed tests, from the catalogue of known mistakes.

Pure standard library, no grader internals: the grader (or any tool) passes in what failed
and the lab's stored signatures (tests/mutants/<lab>/signatures.json, written by
`tools/mutants --signatures`), and gets back zero to three sentences for the student.

    import wbgrade_hints
    sigs = wbgrade_hints.load_signatures(repo, "forces")        # None when the lab has none
    lines = wbgrade_hints.hints_for("forces", failed, all_tests, sigs)

`failed` is the list of failed test case names, or a dict {name: the grader's output for
that test} (its first paragraph, the failure reason, tells apart mistakes that fail the same
tests at different assertions: failure_text()).
`all_tests` is every test case name of the lab (passed or failed).

The closeness rule (docs/grading.md, "Failure signatures and hints"): each known mistake m
has a signature S_m, the tests it fails, each with its failure text (failure_text: the
reason, numbers blanked). With F the submission's failed tests, each test t weighted by
w_t = log(1 + M / (1 + m_t)) (m_t of the M known mistakes fail it: a test every mistake
fails tells little apart),
    names = w(F & S_m) / w(F | S_m)          (weighted Jaccard index over test names)
    pairs = w(tests of F & S_m that failed with the same text) / w(F | S_m)
    score = (1 - ASSERTION_WEIGHT) names + ASSERTION_WEIGHT pairs.
A mistake is close when score >= CLOSE. The closest one is named, with any other whose
score is within TIE of it, up to MAX_HINTS sentences with different text. Nothing is said
when nothing is close, when no test failed, or when every test failed (a skeleton, a build
error, a crash at start: no pattern to match).
"""
import functools
import json
import math
import os
import re

SIGNATURES_VERSION = 1
CLOSE = 0.7          # the least score (below) to name a mistake
TIE = 0.1            # scores within TIE of the best are named together
MAX_HINTS = 3        # at most this many mistakes are named
RARITY_WEIGHTS = True  # weigh each test by how few known mistakes fail it
ASSERTION_WEIGHT = 0.5  # weight of the (test, failure text) Jaccard index in the score

_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


CLASS_CHARS = 300   # characters of a blanked failure text kept in a signature
CLASS_PREFIX = 300  # characters of it compared ("the same assertion")


@functools.lru_cache(maxsize=65536)
def failure_text(output):
    """What a signature keeps of a failed test: the first paragraph of the grader's output for
    it (the whole failure reason: the assertion's message, expected and actual values), every
    number blanked to '#' (values differ from run to run of a wrong program, the assertion
    does not), whitespace collapsed, at most CLASS_CHARS characters."""
    first = (output or "").split("\n\n", 1)[0]
    return " ".join(_NUMBER.sub("#", first).split())[:CLASS_CHARS]


def assertion_class(text):
    """The class compared between a submission's failure and a signature's."""
    return failure_text(text or "")[:CLASS_PREFIX]


def signatures_path(repo, lab):
    return os.path.join(repo, "tests", "mutants", lab, "signatures.json")


def load_signatures(repo, lab):
    """The lab's stored signatures (the parsed JSON), or None when there are none or the file
    cannot be read (then no hints: a missing catalogue must never break grading)."""
    try:
        with open(signatures_path(repo, lab), encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("version") != SIGNATURES_VERSION \
            or not isinstance(data.get("mutants"), dict):
        return None
    return data


def _failed_map(failed):
    if isinstance(failed, dict):
        return {str(k): assertion_class(str(v)) for k, v in failed.items()}
    return {str(k): None for k in failed}


def _weights(signatures, tests):
    """Each test's weight: 1, or with RARITY_WEIGHTS, log(1 + M / (1 + m_t)) for a test that m_t
    of the M known mistakes fail (a test that most mistakes fail tells little apart)."""
    if not RARITY_WEIGHTS:
        return {t: 1.0 for t in tests}
    muts = [m for m in (signatures or {}).get("mutants", {}).values() if isinstance(m, dict)]
    count = {t: 0 for t in tests}
    for m in muts:
        for t in m.get("failed") or {}:
            if t in count:
                count[t] += 1
    return {t: math.log(1 + len(muts) / (1 + count[t])) for t in tests}


def scores(failed, all_tests, signatures, exclude=()):
    """[(score, mutant name, hint)] for every known mistake, best first.
    `exclude`: mutant names to leave out (leave-one-out)."""
    tests = set(all_tests)
    F = {t: c for t, c in _failed_map(failed).items() if t in tests}
    out = []
    mutants = (signatures or {}).get("mutants", {})
    w = _weights(signatures, tests)
    for name in sorted(mutants):
        m = mutants[name]
        if name in exclude or not isinstance(m, dict):
            continue
        S = {t: assertion_class(c) for t, c in (m.get("failed") or {}).items() if t in tests}
        if not S or not F:
            continue
        union = sum(w[t] for t in set(F) | set(S))
        names = sum(w[t] for t in set(F) & set(S)) / union
        same = sum(w[t] for t in set(F) & set(S) if F[t] is not None and F[t] == S[t])
        pairs = same / union  # the same over (test, failure text) pairs
        score = (1 - ASSERTION_WEIGHT) * names + ASSERTION_WEIGHT * pairs
        out.append((score, name, str(m.get("hint", "")).strip()))
    out.sort(key=lambda r: (-r[0], r[1]))
    return out


def matches(failed, all_tests, signatures, exclude=()):
    """The known mistakes whose hints would be shown: [(score, name, hint)]."""
    F = set(_failed_map(failed)) & set(all_tests)
    if not F or F >= set(all_tests):
        return []
    ranked = [r for r in scores(failed, all_tests, signatures, exclude) if r[0] >= CLOSE and r[2]]
    if not ranked:
        return []
    best = ranked[0][0]
    chosen, texts = [], set()
    for r in ranked:
        if r[0] < best - TIE or len(texts) >= MAX_HINTS:
            break
        if r[2] not in texts:
            texts.add(r[2])
            chosen.append(r)
    return chosen


def hints_for(lab, failed, all_tests, signatures):
    """Zero to MAX_HINTS sentences for the student; never certain, never solution code.
    `signatures`: load_signatures(repo, lab) (None: no hints)."""
    if not signatures or signatures.get("lab", lab) != lab:
        return []
    chosen = matches(failed, all_tests, signatures)
    if not chosen:
        return []
    if len(chosen) == 1:
        return [f"These failures match a known mistake: {chosen[0][2]}"]
    return ["These failures match known mistakes; check each of:"] + \
        [f"- {r[2]}" for r in chosen]


def hints_for_results(repo, lab, results):
    """The grader's one call: `results` is [(test name, passed?, output)] of one graded lab
    (its output: the failure text; the first paragraph is enough). Returns hints_for's lines,
    [] when the lab has no stored signatures."""
    failed = {name: output for name, passed, output in results if not passed}
    return hints_for(lab, failed, [r[0] for r in results], load_signatures(repo, lab))
