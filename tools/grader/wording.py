"""What a student reads of a failed test: the test's own words, in the order of what failed, and
nothing of the machinery (docs/grading.md, "The output").

A test's report holds the messages in scope when a check failed (INFO, CAPTURE, a helper's
"expected ... got ..."), the check itself (file:line, the expression, Catch's expansion), and
what the lab's code threw or how its process ended. A student acts on the first and on what
their code did, so:
  - the failed check's own message comes first (the innermost message in scope), then the
    context around it (the step, the particle, the held-out inputs);
  - a capture "name := value" reads "name = value";
  - the file:line of the test helpers, the expression and its expansion go to the TAs' text
    only (TestResult.check: tools/mutants measures its margins from it);
  - an exception or a crash in the lab's code says, in one line, what the code did (an index
    out of range, std::clamp called with hi < lo), not the library's assertion or the pipe;
  - the held-out seed is printed once per grade (the header): a reason refers to it.

Trust: formats text only; never decides a score."""
import re

# ---------------------------------------------------------------- messages

_CAPTURE = re.compile(r"^(.*?) := (.*)$", re.S)
_WRAPPED = re.compile(r"^(?:[A-Za-z_]\w*::)*(?:str|to_string)\((.*)\)$")


def capture(text):
    """A capture as a student writes it: "k := 0" -> "k = 0", "wbtest::str(x) := (1, 2)" ->
    "x = (1, 2)", a string's quotes dropped ('wbtest::str(x) := "(1, 2)"' -> "x = (1, 2)").
    Anything else unchanged."""
    m = _CAPTURE.match(text)
    if not m:
        return text
    name, value = m.group(1).strip(), m.group(2).strip()
    w = _WRAPPED.match(name)
    if w:
        name = w.group(1).strip()
    if len(value) >= 2 and value[0] == value[-1] == '"' and '"' not in value[1:-1]:
        value = value[1:-1]
    return f"{name} = {value}"


# "held-out inputs of E1 from seed 0x6f10c224dfd6e475 (replay: tools/grade ... --seed 0x...,
# or WB_HELDOUT_SEED=0x... when running the tests)" (tests/common/heldout.h)
_REPLAY = re.compile(r"held-out inputs of (\w+) from seed (0x[0-9a-fA-F]+|\d+)"
                     r"(?: \(replay: [^()]*\))?")


def seed_reference(text, seed):
    """The held-out replay hint of a message, when it names this grade's seed, as a reference
    to the one seed line of the grade (a reason never repeats, nor cuts, the seed)."""
    if seed is None:
        return text

    def one(m):
        try:
            same = int(m.group(2), 0) == seed
        except ValueError:
            same = False
        return f"held-out inputs of {m.group(1)} (the grade's seed, above)" if same else m.group(0)
    return _REPLAY.sub(one, text)


_EIGEN = re.compile(r"Eigen: an index out of range, or sizes that do not match \(\S+:\d+ checks "
                    r"(.*)\)\s*$", re.S)


def library_words(text):
    """A library's check in a student's words, without its file and line."""
    m = _EIGEN.search(text)
    if m:
        cond = m.group(1).strip()
        what = ("an index out of range of an Eigen vector or matrix"
                if re.search(r"\bindex\b|<\s*(?:size|rows|cols)\(\)|\b(?:row|col)\b", cond) else
                "Eigen matrices or vectors whose sizes do not match")
        return text[:m.start()] + f"{what} ({cond})"
    return text


# "the lab's code stopped answering during solve_contact (the other side closed the pipe): its
# process crashed, called exit() or hit a limit" (tools/grader/cpp/client.cpp)
_GONE = re.compile(r"the lab's code stopped answering(?: during (\w+))?(?: \([^()]*\))?(?:: [^\n]*)?")
# "your prepare_contact threw: ..." (tools/grader/cpp/client.h)
_THREW = re.compile(r"^your (\w+) threw: (.*)$", re.S)


def exception(text):
    """What an exception out of a test says: the lab's function and what it did, in words."""
    m = _THREW.match(text.strip())
    if m:
        return f"your {m.group(1)} threw an exception: {library_words(m.group(2).strip())}"
    g = _GONE.search(text)
    if g:
        return (f"your {g.group(1)}" if g.group(1) else "the lab's code") + \
            " stopped answering (its process crashed, ended or hit a limit)"
    return f"the test stopped on an exception: {library_words(text.strip())}"


def probe_error(text):
    """A probe's error as the catalogue keeps it and a counterexample shows it (the call is
    shown beside it): the same words whether the probe ran through the worker ("your f
    threw: ...") or linked directly."""
    m = _THREW.match(text.strip())
    return library_words((m.group(2) if m else text).strip())


def function_gone(text):
    """None when the lab's process did not go away during the test, else the lab function that
    was running ("" when not named). Never read from what the lab's code threw: its words are
    the student's."""
    for line in (text or "").splitlines():
        g = _GONE.search(line)
        if g and not re.search(r"\bthrew\b", line[:g.start()]):
            return g.group(1) or ""
    return None


# ----------------------------------------------------------------- crashes

# libstdc++ (_GLIBCXX_ASSERTIONS): "/usr/include/c++/12/bits/stl_algo.h:3625: constexpr const
# _Tp& std::clamp(const _Tp&, const _Tp&, const _Tp&) [with _Tp = double]: Assertion
# '!(__hi < __lo)' failed."
_GLIBCXX = re.compile(r"^.*?\b(std::[\w:]*?)(?:<.*?>)?(?:::operator\[\]|::at|::\w+)?"
                      r"\(.*?: Assertion '(.*)' failed\.?\s*$")
_ASSERT = re.compile(r"^.*?: ([^:]*?): Assertion [`'](.*)' failed\.?\s*$")
_KNOWN = [  # (a piece of the assertion, what the code did)
    ("__hi < __lo", "called std::clamp with hi < lo (clamp(v, lo, hi) needs lo <= hi)"),
    ("__n < this->size()", "an index out of range of a std::vector (operator[])"),
    ("__n < _Nm", "an index out of range of a std::array (operator[])"),
    ("!this->empty()", "front(), back() or pop_back() of an empty container"),
    ("__p != nullptr", "a null pointer dereferenced"),
]
_SIGNALS = {
    "SIGSEGV": "an invalid memory access (an index past the end of an array, a null or dangling "
               "pointer?)",
    "SIGBUS": "an invalid memory access",
    "SIGFPE": "an integer division by zero",
    "SIGABRT": "it aborted (abort(), or a failed check of the standard library)",
    "SIGILL": "an illegal instruction (a function that returns nothing where a value is due?)",
    "SIGKILL": "it was stopped by a limit (memory or time)",
    "SIGXCPU": "it used up its CPU time (an infinite loop?)",
    "SIGXFSZ": "it wrote more than the output limit",
}


def crash(signal_name, output):
    """(what the lab's code did, its output without the library's assertion lines) for a lab
    process that ended on `signal_name` ("SIGABRT") after writing `output`."""
    output = output or ""
    what = ""
    # Only short lines that say "Assertion" are read (the output is the student's: a long line
    # must not cost the patterns time).
    asserts = [l for l in output.splitlines() if ": Assertion " in l and len(l) <= 2000]
    for line in asserts:
        m = _GLIBCXX.match(line) or _ASSERT.match(line)
        if m:
            known = next((w for piece, w in _KNOWN if piece in m.group(2)), None)
            what = known or f"a failed check of the standard library in {m.group(1)}"
            break
    kept = "\n".join(l for l in output.splitlines() if l not in asserts)
    if not what:
        what = _SIGNALS.get((signal_name or "").split(" ")[0], f"it crashed ({signal_name})")
    return what, kept.strip()


# ----------------------------------------------------------------- numbers

# A number, written so that a string of digits has one way to match (no backtracking blow-up
# on hostile values: these patterns run on text that holds numbers from the student's code;
# tests/test_wording.py times a long line of them).
NUMBER = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?"
_NUM = re.compile(rf"(?<![\w.]){NUMBER}(?![\w.])")


def _digits(a, b):
    """The significant digits that show a and b apart (at least 6, at most 17)."""
    if a == b:
        return 0
    for p in range(6, 18):
        if f"{a:.{p}g}" != f"{b:.{p}g}":
            return p
    return 17


def digits(text):
    """Each "expected ..." line and the "got ..." line after it, with every pair of numbers
    printed to the digits that tell them apart: 4.94760000001 against 4.94760000002 (the tests
    print every digit; 6 would show 4.9476 twice)."""
    lines = text.split("\n")
    for k in range(len(lines) - 1):
        e = re.match(r"^(\s*expected\b)(.*)$", lines[k])
        g = re.match(r"^(\s*got\b)(.*)$", lines[k + 1])
        if not (e and g):
            continue
        en, gn = list(_NUM.finditer(e.group(2))), list(_NUM.finditer(g.group(2)))
        if len(en) != len(gn) or not en:
            continue
        vals = [(float(a.group()), float(b.group())) for a, b in zip(en, gn)]

        def put(s, found, which):
            out, last = [], 0
            for m, pair in zip(found, vals):
                p = _digits(*pair)
                v = pair[which]
                short = m.group() if p == 0 or v == int(v) and abs(v) < 1e15 else f"{v:.{p}g}"
                out += [s[last:m.start()], short if len(short) < len(m.group()) else m.group()]
                last = m.end()
            return "".join(out) + s[last:]
        lines[k] = e.group(1) + put(e.group(2), en, 0)
        lines[k + 1] = g.group(1) + put(g.group(2), gn, 1)
    return "\n".join(lines)


_ROW = rf"{NUMBER}(?:[ ]+{NUMBER})*"
ROW_LINE = 2000  # a longer line is left as it is


def one_line_matrices(text):
    """A matrix a test printed with Eigen's operator<< (one row per line, numbers apart by
    spaces), inside a sentence, as [a, b; c, d] on the sentence's line."""
    lines = text.split("\n")
    out, k = [], 0
    while k < len(lines):
        m = re.match(rf"^(.*?(?:= |: |^)\s*)({_ROW})\s*$", lines[k]) \
            if len(lines[k]) <= ROW_LINE else None
        rows = []
        if m:
            j = k + 1
            width = len(m.group(2).split())
            while j < len(lines):
                r = re.match(rf"^\s*({_ROW})(.*)$", lines[j])
                if not r or len(r.group(1).split()) != width:
                    break
                rows.append(r.group(1).split())
                j += 1
                if r.group(2):
                    break
        if rows:
            tail = re.match(rf"^\s*({_ROW})(.*)$", lines[k + len(rows)]).group(2)
            allrows = [m.group(2).split()] + rows
            head = m.group(1).rstrip()
            out.append(head + (" " if head else "") + "[" +
                       "; ".join(", ".join(r) for r in allrows) + "]" + tail)
            k += len(rows) + 1
        else:
            out.append(lines[k])
            k += 1
    return "\n".join(out)


VALUE_CHARS = 160  # an expected or got longer than this shows the numbers that differ


def differing(text, limit=VALUE_CHARS):
    """An "expected ..." and "got ..." pair too long to read whole: the numbers that differ,
    each with its place (the n-th number of the value), and how many agree."""
    lines = text.split("\n")
    for k in range(len(lines) - 1):
        e = re.match(r"^(\s*expected\s+)(.*)$", lines[k])
        g = re.match(r"^(\s*got\s+)(.*)$", lines[k + 1])
        if not (e and g) or max(len(e.group(2)), len(g.group(2))) <= limit:
            continue
        en, gn = list(_NUM.finditer(e.group(2))), list(_NUM.finditer(g.group(2)))
        if len(en) != len(gn) or not en:
            continue
        bad = [i for i, (a, b) in enumerate(zip(en, gn)) if float(a.group()) != float(b.group())]
        if not bad:
            continue
        rest = f" (the other {len(en) - len(bad)} of {len(en)} numbers agree)" if len(bad) < len(en) else ""
        lines[k] = e.group(1) + ", ".join(f"#{i} = {en[i].group()}" for i in bad) + rest
        lines[k + 1] = g.group(1) + ", ".join(f"#{i} = {gn[i].group()}" for i in bad)
    return "\n".join(lines)


def student(text, seed=None):
    """A test's message as a student reads it: the seed referred to, matrices on one line,
    expected and got to the digits that differ (only the numbers that differ, when too long)."""
    return differing(digits(one_line_matrices(seed_reference(text, seed))))
