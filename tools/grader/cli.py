"""tools/grade's command line: arguments, exit status, signals.

Trust: the trusted side (never runs student code itself)."""
import argparse
import json
import os
import signal
import sys

from . import common
from .build import Grader
from .common import BadInput, Defect, log
from . import heldout
from .procs import kill_all
from .project import repo_root
from .results import wrap, layers_data, layers_text, print_table, results_json, write_atomic
from .submission import resolve_submission

# --------------------------------------------------------------------- main

RESULTS_PATH = None  # --results, known as soon as the arguments are parsed


class Stopped(Exception):
    """The grader received SIGTERM, SIGHUP or SIGINT: clean up and give no score."""


def _stop(signum, frame):
    raise Stopped(signal.Signals(signum).name)


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="tools/grade",
        description="Grades a student submission against the pristine graded tests: screens and "
                    "copies in only the labs/<lab>/*.cpp files, builds them in a scratch build, "
                    "runs every test case in its own sandboxed process with a time limit, prints "
                    "a table of points.",
        epilog="Examples: tools/grade labs --lab forces (your score); tools/grade solutions; "
               "tools/grade submission/ --results results.json. Exit status: 0 graded, "
               "1 internal error or --require-score not met, 2 bad input.")
    p.add_argument("submission", help="a folder laid out like labs/ (forces/, euler/, ...) or one lab's folder")
    p.add_argument("--lab", action="append", default=[], metavar="L",
                   help="grade only this lab (repeatable); required for one lab's folder if ambiguous")
    p.add_argument("--results", metavar="FILE", help="write Gradescope's results.json here")
    p.add_argument("--timeout", type=float, default=60.0, metavar="S",
                   help="CPU time limit of each test case (its two processes together), seconds "
                        "(default 60)")
    p.add_argument("--build-timeout", type=float, default=common.BUILD_TIMEOUT, metavar="S",
                   help=f"time limit of building one lab in seconds (default {common.BUILD_TIMEOUT})")
    p.add_argument("--lab-budget", type=float, default=common.LAB_BUDGET, metavar="S",
                   help="CPU time all of one lab's tests may use together, seconds "
                        f"(default {common.LAB_BUDGET}); tests not started by then score 0")
    p.add_argument("--budget", type=float, default=common.SUBMISSION_BUDGET, metavar="S",
                   help="CPU time all of a submission's tests may use together, and wall-clock time "
                        "for its builds (not the one-time pristine build of the test list), seconds "
                        f"(default {common.SUBMISSION_BUDGET}); tests not started by then score 0")
    p.add_argument("--build-dir", metavar="DIR", default=os.environ.get("WB_GRADE_BUILD_DIR") or None,
                   help="keep the scratch copy and build here to reuse across runs (default: "
                        "$WB_GRADE_BUILD_DIR if set, else build/grade in this checkout, which also "
                        "remembers the last results: a lab whose files did not change is not "
                        "built or run again)")
    p.add_argument("--fresh", action="store_true",
                   help="a temporary scratch build, deleted at the end (no reuse of any kind)")
    p.add_argument("--require-score", type=int, metavar="N",
                   help="exit 1 unless every graded lab scores exactly N")
    p.add_argument("--jobs", type=int, default=2, metavar="J",
                   help="test cases run at once, and build jobs (default 2)")
    p.add_argument("--seed", metavar="N",
                   help="the seed of the held-out inputs (decimal or 0x hex): replays a grading's "
                        "held-out checks (default: a random one, printed)")
    p.add_argument("--seed-key", metavar="FILE",
                   help="derive the seed from this secret and the submission's files (the "
                        "autograder's: the student cannot know it in advance)")
    p.add_argument("--no-screen", action="store_true",
                   help="skip the screening of student files (only to test the sandbox alone; "
                        "the output and results.json say so)")
    p.add_argument("-v", "--verbose", action="store_true",
                   help="also print the details of every failed test")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    global RESULTS_PATH
    RESULTS_PATH = args.results
    repo = repo_root()
    if args.timeout <= 0:
        raise BadInput(f"--timeout {args.timeout:g}: expected a positive number of seconds")
    if args.build_timeout <= 0:
        raise BadInput(f"--build-timeout {args.build_timeout:g}: expected a positive number of seconds")
    if args.jobs < 1:
        raise BadInput(f"--jobs {args.jobs}: expected at least 1")
    if args.results and not os.path.isdir(os.path.dirname(os.path.abspath(args.results))):
        raise BadInput(f"--results {args.results}: the folder does not exist")
    common.BUILD_TIMEOUT = args.build_timeout
    labs, overlays, notes, refused = resolve_submission(repo, args.submission, args.lab)
    log(f"grade: {args.submission}: grading {', '.join(labs)}")
    for flag, value in (("--lab-budget", args.lab_budget), ("--budget", args.budget)):
        if value <= 0:
            raise BadInput(f"{flag} {value:g}: expected a positive number of seconds")
    if args.seed is not None and args.seed_key:
        raise BadInput("--seed and --seed-key: give one of them")
    seed = (heldout.parse_seed(args.seed) if args.seed is not None else
            heldout.seed_from_key(args.seed_key, overlays) if args.seed_key else
            heldout.random_seed())
    build_dir, own = args.build_dir, False
    if build_dir is None and not args.fresh:
        build_dir, own = default_build_dir(repo), True
    grader = Grader(repo, build_dir, args.jobs, args.timeout, screen=not args.no_screen,
                    lab_budget=args.lab_budget, submission_budget=args.budget, seed=seed)
    grader.reuse_results = own  # the student's loop: an unchanged lab is not graded again
    # A seed asked for (--seed, --seed-key) is part of what a reused report must have been
    # graded with; a random one is not (any seed will do for files graded before).
    grader.seed_chosen = args.seed is not None or bool(args.seed_key)
    try:
        reports = grader.grade(overlays, labs, {l: r for l, r in refused.items() if r})
    finally:
        grader.close()
    print_table(reports, notes, seed=grader.seed)  # the one line that names the seed
    layers = layers_text(grader)  # how the tests and the build ran: for TAs (grade-log.txt, -v)
    where = ta_log(grader, layers, args.verbose)
    if not grader.screen:
        print("\nscreening: OFF (--no-screen: for testing the sandbox only)")
    if args.verbose:
        print("\n" + layers + (f"\n(also in {where})" if where else ""))
        for rep in reports.values():
            for r in rep.results:
                if r.status == "failed" and rep.gradable:
                    print()
                    for l in f"--- {r.test.lab}: {r.test.name}\n{r.output}".split("\n"):
                        print("\n".join(wrap(l)))
    sys.stdout.flush()
    if args.results:  # last, atomically: nothing after this can change the verdict
        write_atomic(args.results, json.dumps(results_json(reports, notes, layers,
                                                          layers_data(grader), grader.seed),
                                             indent=2) + "\n")
        log(f"grade: wrote {args.results}")
    if args.require_score is not None:
        wrong = [f"{lab} scored {rep.score}" for lab, rep in reports.items() if rep.score != args.require_score]
        if wrong:
            log(f"grade: --require-score {args.require_score}: {', '.join(wrong)}")
            return 1
    return 0


def default_build_dir(repo):
    """The checkout's own scratch build (build/grade): kept from one grade to the next, so that
    a re-grade compiles only what changed."""
    return os.path.join(repo, "build", "grade")


def ta_log(grader, layers, verbose):
    """Writes what the grader's defences were (for TAs: a student never needs it) beside the
    scratch build, when that build is kept; returns the file's path or ""."""
    if grader.temporary:
        return ""
    path = os.path.join(grader.root, "grade-log.txt")
    try:
        write_atomic(path, layers + "\n")
    except OSError:
        return ""
    return path


def run(argv=None):
    """The entry point: runs main() and turns every outcome into tools/grade's exit status."""
    for _sig in (signal.SIGTERM, signal.SIGHUP, signal.SIGINT):
        signal.signal(_sig, _stop)
    try:
        sys.exit(main(sys.argv[1:] if argv is None else argv))
    except BadInput as e:
        log(f"grade: {e}")
        if RESULTS_PATH and os.path.isdir(os.path.dirname(os.path.abspath(RESULTS_PATH))):
            # Graded, with 0 and the reason (the same message as on the command line).
            write_atomic(RESULTS_PATH, json.dumps({
                "score": 0, "output_format": "text",
                "output": f"The submission could not be graded:\n{e}\nUpload the .cpp files of "
                          "the lab (the files in labs/<lab>/), or the lab's folder."}, indent=2))
        sys.exit(2)
    except Defect as e:
        kill_all()
        log(f"grade: internal error (a defect in the grader, the tests or the skeletons, not in the submission):\n{e}")
        sys.exit(1)
    except (KeyboardInterrupt, Stopped) as e:
        kill_all()
        log(f"grade: stopped ({e or 'interrupted'}): no results were written")
        sys.exit(130)
    except Exception as e:  # an autograder error: a clear line, not a traceback
        kill_all()
        log(f"grade: autograder error (not the submission's fault): {type(e).__name__}: {e}")
        if os.environ.get("WB_GRADE_TRACEBACK"):
            import traceback
            traceback.print_exc()
        sys.exit(1)
