"""A seventh lab inherits every check: proved on a throwaway lab, in a temporary copy (issue 47).

In a temporary copy of the repository (HEAD's files, `git archive`; with --worktree the work
tree's tracked and untracked files instead), never the real tree, this adds the lab "drag"
(tools/newlab.d/, whose README.md says what a new lab adds: one task, D1 Heun's step, its
solution, its graded tests with a held-out one, its handout with the points block and a figure,
a default scene, its driver) and one wb_lab(drag) line, then
shows that every per-lab check sees it:

  1. the copy builds the lab alone (-DWB_LABS=drag, -Werror): its skeleton, its solution and
     their tests (build/bin/drag, drag-solution, drag-tests, drag-solution-tests);
  2. its graded tests pass against the solution (ctest -L solution); the bad-input cases
     that run on every lab refuse its bad input with one line and exit 2, and its default
     scene runs within the cost model's estimate (ctest -L badinput);
  3. tools/pattern's per-lab stages, restricted to it (--lab drag): stubs (the skeleton warns
     it is a stub, the solution does not), stubfigs, periods, asserts, nanfree, testnames,
     points, claims, answers, docrefs;
  4. the same text stages fail, each naming the lab, once the lab breaks their rule (a bare
     assertion, a NaN-blind maximum, a misnamed test file, a points list off by one, an
     unmarked statement about a run): they read the new lab, not only the six;
  5. the grader: the skeleton scores 0, the solution 100 (tools/grade --lab drag);
  6. the student pack of that lab alone works on its own (tools/pack --lab drag --verify: its
     links and paths resolve, it builds, its README's commands run, the skeleton scores 0) and
     holds the lab's student files, tests, scene, handout and figure, and no solution;
  7. docs/report.md names the figures the pack's report drew of it (tools/pattern reportdoc).

It fails if a step fails, naming the step; the temporary folder is removed in every case.
About 160 s of CPU (2026-12-07, /usr/bin/time on the shared 2-core machine), most of it
compiling: the framework twice (the copy's build, the pack's prebuilt framework), the lab's
tests three times (the copy's build, the grader's, the pack's), the pack's student build.
Exit status: 0 all passed, 1 a step failed, 2 bad input."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FIXTURE = os.path.join("tools", "newlab.d")  # the throwaway lab, laid out as in the repository
LAB, TASK = "drag", "D1"
# What a lab adds beside its one CMake line: the pack's README table reads the instructor
# README's row (tools/wbtools/pack.py, lab_rows).
README_ROW = ("| `drag` | a throwaway lab: Heun's step under linear drag | D1 "
              "| [handouts/drag.md](handouts/drag.md) | complete |")
GIT_ENV = {"GIT_AUTHOR_NAME": "newlab-check", "GIT_AUTHOR_EMAIL": "newlab-check@localhost",
           "GIT_COMMITTER_NAME": "newlab-check", "GIT_COMMITTER_EMAIL": "newlab-check@localhost",
           "GIT_CONFIG_NOSYSTEM": "1"}


class StepFailed(Exception):
    pass


RUNNING = []  # the step's process, while it runs


def stop_step():
    """Ends the running step's whole process group (on a stop, before the folder goes)."""
    for p in RUNNING:
        try:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(timeout=20)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


# Steps that stop at the first failure: each needs the one before (a build, then its
# grading). Not clang_check.Steps, which goes on to list every failure and has no group of
# processes to stop (docs/contributor.md, "Repeated code").
class Steps:
    def __init__(self):
        self.t0 = time.monotonic()

    def run(self, what, cmd, cwd, env=None, capture=False):
        """Runs one step's command; raises StepFailed naming the step when it fails."""
        t0 = time.monotonic()
        print(f"newlab-check: {what}\n+ {' '.join(cmd)}", flush=True)
        # In a process group of its own, so that a stop ends the whole step (a build's
        # compilers too) before the folder is removed (stop_step).
        p = subprocess.Popen(cmd, cwd=cwd, env=dict(os.environ, **(env or {})),
                             stdout=subprocess.PIPE if capture else None,
                             stderr=subprocess.STDOUT if capture else None, text=True,
                             start_new_session=True)
        RUNNING.append(p)
        stdout, _ = p.communicate()
        RUNNING.remove(p)
        if p.returncode != 0:
            if capture:
                print(stdout, end="", flush=True)
            raise StepFailed(f"{what} (exit {p.returncode})")
        print(f"newlab-check: ok: {what} ({time.monotonic() - t0:.0f} s)", flush=True)
        return stdout if capture else ""

    def check(self, what, problems):
        for p in problems:
            print(f"newlab-check: {p}", flush=True)
        if problems:
            raise StepFailed(what)
        print(f"newlab-check: ok: {what}", flush=True)


def copy_repository(dest, worktree):
    """HEAD's files (or the work tree's, tracked and untracked) into dest, committed there:
    tools/pack reads the tree of HEAD."""
    os.makedirs(dest)
    if worktree:
        names = subprocess.run(["git", "-C", ROOT, "ls-files", "-z", "--cached", "--others",
                                "--exclude-standard"], check=True, capture_output=True
                               ).stdout.decode().split("\0")
        for name in filter(None, names):
            src = os.path.join(ROOT, name)
            if os.path.isfile(src):
                os.makedirs(os.path.dirname(os.path.join(dest, name)), exist_ok=True)
                shutil.copy2(src, os.path.join(dest, name))
    else:
        archive = subprocess.Popen(["git", "-C", ROOT, "archive", "HEAD"], stdout=subprocess.PIPE)
        subprocess.run(["tar", "-x", "-C", dest], stdin=archive.stdout, check=True)
        archive.stdout.close()
        if archive.wait() != 0:
            raise StepFailed("copy HEAD (git archive HEAD)")
    commit(dest, "the repository as it was")


def commit(repo, message):
    env = dict(os.environ, **GIT_ENV)
    if not os.path.isdir(os.path.join(repo, ".git")):
        subprocess.run(["git", "init", "-q", repo], check=True, env=env)
    subprocess.run(["git", "-C", repo, "add", "-A"], check=True, env=env)
    subprocess.run(["git", "-C", repo, "commit", "-q", "--no-verify", "-m", message], check=True,
                   env=env)


def add_lab(repo):
    """The new lab's files (tools/newlab.d/, *.in without the suffix), its wb_lab line and its
    README row: everything a new lab adds. Returns the files added."""
    src = os.path.join(repo, FIXTURE)
    added = []
    for d, _, names in os.walk(src):
        for name in names:
            rel = os.path.relpath(os.path.join(d, name), src)
            if rel == "README.md":
                continue  # the folder's own: what a new lab adds
            out = os.path.join(repo, rel[:-3] if rel.endswith(".in") else rel)
            if os.path.exists(out):
                raise StepFailed(f"add the lab: {os.path.relpath(out, repo)} exists already")
            os.makedirs(os.path.dirname(out), exist_ok=True)
            shutil.copy2(os.path.join(d, name), out)
            added.append(os.path.relpath(out, repo))
    insert_after_last(os.path.join(repo, "CMakeLists.txt"), re.compile(r"^wb_lab\("),
                      f"wb_lab({LAB})", "a wb_lab(...) line")
    insert_after_last(os.path.join(repo, "README.md"), re.compile(r"^\| `[a-z0-9_-]+` \|"),
                      README_ROW, "the labs' table (rows | `<lab>` | ...)")
    commit(repo, f"a seventh lab, {LAB}")
    return sorted(added)


def insert_after_last(path, pattern, line, what):
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    last = max((i for i, ln in enumerate(lines) if pattern.match(ln)), default=None)
    if last is None:
        raise StepFailed(f"add the lab: {os.path.basename(path)} has no {what} to add one after")
    lines.insert(last + 1, line)
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


# Each text stage of tools/pattern, and how to break its rule in the new lab: (stage, file,
# old text, new text). Each must then report a finding that names the lab's folder or file.
BREAKS = [
    ("asserts", "tests/drag/test_D1_heun_drag.cpp", "    REQUIRE(dyn.evals() == 2);\n  }\n",
     "    REQUIRE(dyn.evals() == 2);\n  }\n  REQUIRE(dyn.evals() > 0);\n"),
    ("nanfree", "tests/drag/test_D1_heun_drag.cpp", "  Mat2X x = x0, v = v0;\n  step(dyn, h, x, v);\n",
     "  Mat2X x = x0, v = v0;\n  step(dyn, h, x, v);\n  const bool bounded = x.maxCoeff() < 1e9;\n"
     "  (void)bounded;\n"),
    ("points", "handouts/drag.md", "(45)", "(44)"),
    ("claims", "handouts/drag.md", "Everything you edit",
     "In `coast` the balls lose 87 % of their speed by t = 4 s.\n\nEverything you edit"),
]


def break_each(repo, steps):
    """Step 4: each text stage fails on the lab once its rule is broken there."""
    problems = []
    for stage, rel, old, new in BREAKS + [("testnames", None, None, None)]:
        saved = {}
        if rel is None:  # a graded test file named against the rule
            bad = os.path.join(repo, "tests", LAB, "heun_extra_test.cpp")
            with open(bad, "w", encoding="utf-8") as f:
                f.write('#include "test_helpers.h"\n')
            saved[bad] = None
        else:
            path = os.path.join(repo, rel)
            with open(path, encoding="utf-8") as f:
                text = f.read()
            if old not in text:
                problems.append(f"{stage}: cannot break it: {rel} lacks {old!r} (update BREAKS)")
                continue
            saved[path] = text
            with open(path, "w", encoding="utf-8") as f:
                f.write(text.replace(old, new, 1))
        try:
            p = subprocess.run([os.path.join(repo, "tools", "pattern"), stage, "--lab", LAB],
                               cwd=repo, capture_output=True, text=True)
        finally:
            for path, text in saved.items():
                if text is None:
                    os.remove(path)
                else:
                    with open(path, "w", encoding="utf-8") as f:
                        f.write(text)
        named = [ln for ln in p.stdout.splitlines()
                 if ln.startswith(f"{stage}:") and re.search(rf"\b{LAB}\b|/{LAB}[/.]", ln)]
        if p.returncode != 1 or not named:
            problems.append(f"tools/pattern {stage} did not report the broken lab (exit "
                            f"{p.returncode}): {(p.stdout + p.stderr).strip()[-300:]}")
        else:
            print(f"newlab-check: {stage} caught it: {named[0][:150]}", flush=True)
    return problems


def pack_contents(pack):
    """Problems with the lab's pack: what it must hold, and what it must not."""
    must = [f"labs/{LAB}/heun_drag.cpp", f"labs/{LAB}/heun_drag.h",
            f"tests/{LAB}/test_D1_heun_drag.cpp", f"scenes/{LAB}/coast.json",
            f"handouts/{LAB}.md", f"framework/drivers/{LAB}/main.cpp",
            f"handouts/figures/{LAB}/coast-trajectory.png"]
    problems = [f"the pack lacks {m}" for m in must if not os.path.isfile(os.path.join(pack, m))]
    for d, _, names in os.walk(pack):
        if os.path.relpath(d, pack).split(os.sep)[0] == "solutions":
            problems.append(f"the pack holds {os.path.relpath(d, pack)}")
    with open(os.path.join(pack, "README.md"), encoding="utf-8") as f:
        if f"`{LAB}`" not in f.read():
            problems.append(f"the pack's README does not list the lab {LAB}")
    return problems


def check(work, worktree):
    s = Steps()
    repo, build = os.path.join(work, "repo"), os.path.join(work, "repo", "build")
    copy_repository(repo, worktree)
    added = add_lab(repo)
    print(f"newlab-check: added in {repo}: {', '.join(added)}, wb_lab({LAB}) in CMakeLists.txt, "
          "a row in README.md", flush=True)
    s.run("configure the lab alone (-DWB_LABS=drag, -Werror)",
          ["cmake", "--preset", "default", f"-DWB_LABS={LAB}", "-DWB_WERROR=ON", "-DWB_BENCH=OFF"],
          repo, capture=True)
    s.run("build its skeleton, its solution and their tests", ["cmake", "--build", build, "-j2"],
          repo, capture=True)
    s.check("the build made the lab's executables",
            [f"build/bin/{x} was not built" for x in
             (LAB, f"{LAB}-solution", f"{LAB}-tests", f"{LAB}-solution-tests")
             if not os.path.isfile(os.path.join(build, "bin", x))])
    s.run("its graded tests pass against the solution (ctest -L solution)",
          ["ctest", "--test-dir", build, "-L", "solution", "--no-tests=error",
           "--output-on-failure"], repo, capture=True)
    out = s.run("bad input gets one line and exit 2, its default scene within the cost model "
                "(ctest -L badinput)", ["ctest", "--test-dir", build, "-L", "badinput",
                                        "--no-tests=error", "--output-on-failure", "-V"],
                repo, capture=True)
    s.check("the bad-input cases of every lab and the cost model's check ran the new lab",
            [f"ctest -L badinput did not run {what}" for what in
             (f"every-lab-scene-missing@{LAB}", f"{LAB}/coast.json") if what not in out])
    out = s.run("tools/pattern's per-lab stages see it and pass (--lab drag)",
                [os.path.join(repo, "tools", "pattern"), "-v", "--lab", LAB, "stubs", "stubfigs",
                 "periods", "asserts", "nanfree", "testnames", "points", "claims", "answers",
                 "docrefs"], repo, capture=True)
    s.check("tools/pattern stubs ran the new lab's skeleton and solution",
            [] if f"scenes/{LAB}/coast.json on the skeleton" in out else
            [f"tools/pattern stubs -v printed no run of scenes/{LAB}/: {out[-400:]}"])
    s.check("each text stage of tools/pattern fails on the lab once it breaks its rule",
            break_each(repo, s))
    grade = os.path.join(work, "grade")
    s.run("the grader: the skeleton scores 0",
          [os.path.join(repo, "tools", "grade"), "labs", "--lab", LAB, "--require-score", "0",
           "--build-dir", grade], repo)
    s.run("the grader: the solution scores 100",
          [os.path.join(repo, "tools", "grade"), "solutions", "--lab", LAB, "--require-score",
           "100", "--build-dir", grade], repo)
    pack = os.path.join(work, "pack")
    s.run("the student pack of the lab alone works on its own: links, paths, its build, its "
          "README's commands, the skeleton scoring 0 (tools/pack --lab drag --verify)",
          [os.path.join(repo, "tools", "pack"), "--lab", LAB, "--out", pack, "--verify"], repo)
    s.check("the pack holds the lab's student files, tests, scene and handout, no solution",
            pack_contents(pack))
    # The pack drew the lab's report (build/report/drag/): its figures are in docs/report.md.
    s.run("docs/report.md names every figure the report drew of it (tools/pattern reportdoc "
          "--lab drag)", [os.path.join(repo, "tools", "pattern"), "reportdoc", "--lab", LAB],
          repo, capture=True)
    print(f"newlab-check: all passed in {time.monotonic() - s.t0:.0f} s", flush=True)


def stopped(*_):
    raise KeyboardInterrupt  # a SIGTERM: stop as on Ctrl-C (the step ended, the folder removed)


def main():
    ap = argparse.ArgumentParser(prog="tools/newlab-check", description=__doc__.split("\n\n")[0],
                                 epilog="\n\n".join(__doc__.split("\n\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--worktree", action="store_true",
                    help="copy the work tree's files (tracked and untracked, not ignored) "
                         "instead of HEAD's: to try uncommitted changes")
    ap.add_argument("--keep", action="store_true",
                    help="keep the temporary folder (its path is printed) to look at")
    try:
        args = ap.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    if not os.path.isdir(os.path.join(ROOT, FIXTURE)):
        print(f"tools/newlab-check: error: {FIXTURE}/ is missing (the throwaway lab)",
              file=sys.stderr)
        return 2
    work = tempfile.mkdtemp(prefix="wb-newlab-")
    # A stop (tools/check stopped, Ctrl-C) still removes the folder.
    signal.signal(signal.SIGTERM, stopped)
    try:
        check(work, args.worktree)
        return 0
    except StepFailed as e:
        print(f"newlab-check: FAILED: {e}", flush=True)
        return 1
    except KeyboardInterrupt:
        print("newlab-check: stopped", flush=True)
        return 130
    except subprocess.CalledProcessError as e:
        print(f"newlab-check: FAILED: making the copy: {e}", flush=True)
        return 1
    finally:
        stop_step()
        if args.keep:
            print(f"newlab-check: kept {work}", flush=True)
        else:
            shutil.rmtree(work, ignore_errors=True)


def run():
    sys.exit(main())
