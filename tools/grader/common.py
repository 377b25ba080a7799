"""Shared by every layer of the grader: limits, errors, and the records a run produces.

Trust: no student bytes are handled here."""
import re
import sys
from dataclasses import dataclass, field

PRISTINE_ENTRIES = ["CMakeLists.txt", "CMakePresets.json", "cmake", "framework", "labs",
                    "tests", "scenes"]
SKIPPED_DIRS = {"tests/mutants", "tests/hostile", "tests/badinput"}  # instructor material
OUTPUT_CAP = 8 * 1024  # bytes of a test's stdout/stderr kept
COMPILE_TAIL = 60  # lines of compiler output kept
MAX_STUDENT_FILE = 4 * 1024 * 1024  # larger files keep the skeleton
BUILD_TIMEOUT = 900  # s, one lab's build (a template bomb must not hang the grader)
LIST_TIMEOUT = 60  # s, each listing of the pristine test binary
REPORT_FSIZE = 64 * 1024 * 1024  # largest file a test process may write (RLIMIT_FSIZE)
REPORT_CAP = 8 * 1024 * 1024  # bytes of report read from a test process (more: no report)
TEST_ADDRESS_SPACE = 4 * 1024 * 1024 * 1024  # RLIMIT_AS of a test process
TEST_CPU = 300  # s, RLIMIT_CPU of a process that has no limit of its own (the probes)
IDLE_LIMIT = 5  # s: a test whose processes, over the last IDLE_LIMIT s of wall-clock time, ran or
IDLE_SHARE = 0.01  # waited for a core less than IDLE_SHARE of it is blocked: stopped (worker.py)
# The wall-clock safety net (wall_limit): a test still running after WALL_FACTOR times its CPU
# time limit plus WALL_SLACK s is stopped; if it ran or waited for a core WALL_BUSY_SHARE of
# that time the machine is to blame and the lab is not scored (verdict.py), else it failed.
WALL_FACTOR, WALL_SLACK, WALL_BUSY_SHARE = 10, 300, 0.5
WORKER_OUTPUT_CAP = 8 * 1024  # bytes of the worker's own output kept (each stream)
MESSAGE_CAP = 2 * 1024  # characters of one message of a test's report kept
TEST_OUTPUT_CAP = 16 * 1024  # characters of one test's details kept (table -v, results.json)
RESULTS_CAP = 8 * 1024 * 1024  # bytes: results.json is never larger
LAB_BUDGET = 600  # s of CPU time for one lab's test processes together
SUBMISSION_BUDGET = 1800  # s: CPU time of all a submission's tests, wall clock of its builds
REASON_WIDTH = 100  # characters of the short reason in the table
CACHE_VERSION = 2
FORBIDDEN_NAME_CHARS = set(';,[]*~"\\')
POINTS_TAG = re.compile(r"^\[(\d+)pts\]$", re.IGNORECASE)


def wall_limit(cpu_limit):
    """The wall-clock time after which a test with this CPU time limit is stopped (a safety net:
    the CPU limit and the idle rule end every test long before on any sane machine)."""
    return WALL_FACTOR * cpu_limit + WALL_SLACK


class BadInput(Exception):
    """A problem with what the user gave us: exit 2."""


class Defect(Exception):
    """A problem on our side (tests, skeletons, build): exit 1."""


def log(msg):
    print(msg, file=sys.stderr, flush=True)


@dataclass
class TestCase:
    lab: str
    name: str
    points: int
    tags: list


@dataclass
class TestResult:
    test: TestCase
    score: int
    status: str  # "passed" or "failed"
    reason: str  # the first failure in a student's words: the check's message, then its context
    output: str  # the details (failure text, captured output, compile error)
    check: str = ""  # the failed checks in the harness's words (file:line, expansion): TAs' tools
    settled: bool = True  # False: a limit decided it (time, idle, a crash): never reused as is
    cpu: float = 0.0  # s of CPU time its processes used (the budgets count it)


@dataclass
class LabReport:
    lab: str
    results: list
    notes: list = field(default_factory=list)
    compile_error: str = ""
    refused: str = ""  # why screening refused a submitted file ("" = accepted)
    diagnosis: dict = field(default_factory=dict)  # {task: diagnosis.hints.Diagnosis}

    @property
    def gradable(self):
        return not self.compile_error and not self.refused

    @property
    def score(self):
        return sum(r.score for r in self.results)

    @property
    def max_score(self):
        return sum(r.test.points for r in self.results)

_UNSAFE = re.compile(r"[^\x20-\x7e\n\t\u00a0-\u00ff\u0370-\u03ff\u2190-\u22ff]")


def printable(s, keep_newlines=True):
    """Text from a test or a submission made safe to print: control characters (escape
    sequences, carriage returns) and look-alike letters outside Latin-1, Greek and the math
    symbols become \\xNN / \\uNNNN, so nothing can draw fake lines or fake names."""
    s = _UNSAFE.sub(lambda m: f"\\x{ord(m.group()):02x}" if ord(m.group()) < 256
                    else f"\\u{ord(m.group()):04x}", s)
    return s if keep_newlines else s.replace("\n", "\\n").replace("\t", "\\t")


def capped(s, cap):
    """s cut to `cap` characters, saying how many were left out."""
    return s if len(s) <= cap else s[:cap] + f"\n[... {len(s) - cap} more characters not shown]"


def short(s, width=REASON_WIDTH):
    s = printable(" ".join(s.split()), keep_newlines=False)
    return s if len(s) <= width else s[:width - 3] + "..."


