"""Held-out checks (docs/grading.md, "Held-out checks"): the seed of a grading run's held-out
inputs, and the gate that makes a task's public points count only when its held-out tests pass.

Every task (a tag [F5], [E1], ...) has at least one test tagged [held-out], which checks the
student's function on inputs drawn from a seed the student could not know in advance: on the
autograder HMAC(secret, the submission's files), locally a random one, printed; `--seed`
replays one. The seed goes to the test process only (WB_HELDOUT_SEED), never to the worker.

Trust: decides scores (the gate); reads the submission's bytes only to hash them."""
import hashlib
import hmac
import os
import re
import secrets

from .common import BadInput, Defect

HELD_OUT_TAG = "[held-out]"
TASK_TAG = re.compile(r"^\[([A-Z]\d+)\]$")


def task_of(test):
    """The task id of a test ("F5"), from its one task tag; None when it has none or several."""
    tasks = [m.group(1) for m in (TASK_TAG.match(t) for t in test.tags) if m]
    return tasks[0] if len(tasks) == 1 else None


def is_held_out(test):
    return any(t.lower() == HELD_OUT_TAG for t in test.tags)


def list_problems(lab, tests):
    """What makes a lab's test list ungradable as far as held-out checks go: every test has
    exactly one task tag, and every task has a held-out test (so that no task's public points
    can be earned by replaying the public tests' answers)."""
    problems = []
    tasks, held = set(), set()
    for t in tests:
        task = task_of(t)
        if task is None:
            problems.append(f"'{t.name}': expected exactly one task tag ([F5], [E1], ...)")
            continue
        tasks.add(task)
        if is_held_out(t):
            held.add(task)
    for task in sorted(tasks - held):
        problems.append(f"task {task} has no test tagged {HELD_OUT_TAG}: its points could be "
                        "earned by replaying the public tests' answers (tests/common/heldout.h)")
    return problems


def gate(results):
    """The held-out gate, in place on one lab's [TestResult]: a public test of a task whose
    held-out tests did not all pass scores 0 (it stays "passed", saying why it counts for
    nothing)."""
    failed = {task_of(r.test) for r in results if is_held_out(r.test) and r.status != "passed"}
    for r in results:
        if r.status == "passed" and not is_held_out(r.test) and task_of(r.test) in failed:
            r.score = 0
            r.reason = (f"this test passed; its points count once {task_of(r.test)}'s held-out "
                        "test passes too")
            r.output = (r.reason + "\n\n" + r.output).strip()


def parse_seed(text):
    """--seed's value: decimal or 0x hex, 0 to 2^64 - 1."""
    try:
        seed = int(text, 0)
    except ValueError:
        seed = -1
    if not 0 <= seed < 1 << 64:
        raise BadInput(f"--seed {text}: expected a number from 0 to 2^64 - 1 (decimal or 0x hex)")
    return seed


def submission_digest(overlays):
    """A hash of exactly the bytes that are graded: every lab's submitted student files."""
    h = hashlib.sha256()
    for lab in sorted(overlays):
        for name in sorted(overlays[lab]):
            data = overlays[lab][name]
            h.update(f"{lab}\0{name}\0{len(data)}\0".encode() + data)
    return h.digest()


def seed_from_key(path, overlays):
    """The autograder's seed: HMAC-SHA256(the secret in `path`, the submission's files), so it
    differs for every change of the code and cannot be computed without the secret (which only
    the grader's user can read). A TA replays it with --seed (it is printed with the results).
    A missing or short secret is the autograder's defect (exit 1), never the submission's."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW)
        with os.fdopen(fd, "rb") as f:
            key = f.read(4096)
    except OSError as e:  # the autograder's own set-up, never the submission's fault
        raise Defect(f"--seed-key {path}: cannot read the held-out secret ({e.strerror}): "
                     "setup.sh makes it")
    if len(key) < 16:
        raise Defect(f"--seed-key {path}: expected a secret of at least 16 bytes, got {len(key)}")
    mac = hmac.new(key, submission_digest(overlays), hashlib.sha256).digest()
    return int.from_bytes(mac[:8], "big")


def random_seed():
    return secrets.randbits(64)
