"""tools/gradescope/hostile: grades the hostile submissions of tests/hostile/ with the
autograder zip that `tools/pack --gradescope` builds, and fails if any scores more
than its honest maximum, leaves a process or a file behind, leaks a planted
secret, or changes anything outside its scratch build.

Each case (tests/hostile/<case>/case.json) is the solution of a lab with one
student file replaced by a hostile one, or ("generate") every file of the lab made for the
case, for each lab it names ("labs"). Its honest maximum is the lab's 100
points less those of the tests tagged with the tasks the hostile file touches
("touches"). Every case runs through Gradescope's run_autograder as
submitted (screening on); a case with "no_screen": true runs a second time
with --no-screen, so that the sandbox alone must hold it.
Exit status: 0 every case held, 1 some case got through, 2 bad usage.
"""
import argparse
import hashlib
import json
import re
import os
import secrets
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = os.path.join(REPO, "tests", "hostile")
TEST_UIDS = range(1 << 20, 1 << 30)  # tools/grade's test users (grader/sandbox.py TEST_UID_RANGE)
GRADE_ARGS = "--timeout 3 --build-timeout 120"  # bounds the infinite loop and the slow compile
# A case's "grade_args" (case.json) go after these: the slow compile's own, shorter build
# limit (an honest build of its lab takes seconds) spares the suite minutes of a busy core.
RESULTS_CAP = 8 * 1024 * 1024  # bytes: no results.json may be larger (tools/grader/common.py)
CASE_TIMEOUT = 600  # s, one run of run_autograder


def log(msg):
    print(msg, flush=True)


def tree_digest(root, skip=()):
    """{relative path: sha256} of every file under root (symbolic links by target)."""
    out = {}
    for d, dirs, files in os.walk(root):
        rel_d = os.path.relpath(d, root)
        dirs[:] = sorted(x for x in dirs if os.path.normpath(os.path.join(rel_d, x)) not in skip)
        for f in files:
            p = os.path.join(d, f)
            rel = os.path.normpath(os.path.join(rel_d, f))
            if rel in skip:
                continue
            if os.path.islink(p):
                out[rel] = "link:" + os.readlink(p)
                continue
            try:
                with open(p, "rb") as fh:
                    out[rel] = hashlib.sha256(fh.read()).hexdigest()
            except OSError as e:
                out[rel] = f"unreadable: {e}"
    return out


def checkout_files():
    """The checkout's own files (tracked and untracked, not ignored): what no case may change."""
    out = subprocess.run(["git", "-C", REPO, "ls-files", "-co", "--exclude-standard", "-z"],
                         stdout=subprocess.PIPE, check=True).stdout.decode()
    digests = {}
    for rel in sorted(p for p in out.split("\0") if p):
        p = os.path.join(REPO, rel)
        try:
            with open(p, "rb") as f:
                digests[rel] = hashlib.sha256(f.read()).hexdigest()
        except OSError:
            digests[rel] = "missing"
    return digests


def processes():
    """{pid: (uid, command line)} of every process."""
    out = {}
    for e in os.listdir("/proc"):
        if not e.isdigit():
            continue
        try:
            with open(f"/proc/{e}/status") as f:
                uid = next(int(l.split()[1]) for l in f if l.startswith("Uid:"))
            with open(f"/proc/{e}/cmdline", "rb") as f:
                cmd = f.read().replace(b"\0", b" ").decode("utf-8", "replace").strip()
        except (OSError, StopIteration, ValueError):
            continue
        out[int(e)] = (uid, cmd)
    return out


def tmp_entries():
    found = set()
    for d in ("/tmp", "/var/tmp", "/dev/shm"):
        try:
            found |= {os.path.join(d, e) for e in os.listdir(d)}
        except OSError:
            pass
    return found


def owner(path):
    try:
        return os.lstat(path).st_uid
    except OSError:
        return -1


def diff(before, after):
    changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
    return changed


def load_cases(names):
    cases = []
    for name in sorted(os.listdir(CASES)):
        path = os.path.join(CASES, name, "case.json")
        if not os.path.isfile(path) or (names and name not in names):
            continue
        with open(path, encoding="utf-8") as f:
            c = json.load(f)
        c["name"] = name
        # A case of every lab ("labs"): one run per lab, the submission made for each.
        for lab in c.pop("labs", None) or [c["lab"]]:
            cases.append(dict(c, lab=lab))
    missing = set(names) - {c["name"] for c in cases}
    if missing:
        raise SystemExit(f"hostile: unknown case {', '.join(sorted(missing))} (tests/hostile/)")
    return cases


class Run:
    def __init__(self, scratch, labs):
        self.scratch, self.labs = scratch, labs
        self.ag = os.path.join(scratch, "autograder")
        self.token = secrets.token_hex(8)  # what a leak must not show, in any part
        self.secret = "wb-secret-" + self.token

    def setup(self):
        """The zip `tools/pack --gradescope LAB` builds (tools/gradescope/make_zip.py), of every
        lab the cases need (one set-up for all: each lab's zip alone set up its own build),
        unpacked and set up as on Gradescope."""
        zip_path = os.path.join(self.scratch, "autograder.zip")
        sys.path.insert(0, os.path.join(REPO, "tools", "gradescope"))
        import make_zip
        make_zip.build(self.labs, zip_path, REPO)
        src = os.path.join(self.ag, "source")
        if os.path.isdir(src):
            shutil.rmtree(src)
        os.makedirs(src)
        with zipfile.ZipFile(zip_path) as z:
            for info in z.infolist():
                z.extract(info, src)
                mode = info.external_attr >> 16
                if mode:
                    os.chmod(os.path.join(src, info.filename), mode & 0o777)
        # "Other students' files": a secret beside the autograder that no test may read.
        others = os.path.join(self.scratch, "others")
        os.makedirs(others, exist_ok=True)
        os.chmod(others, 0o700)
        with open(os.path.join(others, "secret.txt"), "w") as f:
            f.write(self.secret + "\n")
        env = dict(os.environ, AUTOGRADER_ROOT=self.ag)
        t0 = time.monotonic()
        r = subprocess.run(["bash", os.path.join(src, "setup.sh")], env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        if r.returncode != 0:
            sys.stdout.write(r.stdout.decode("utf-8", "replace")[-4000:])
            raise SystemExit("hostile: setup.sh of the autograder zip failed")
        log(f"hostile: autograder zip built and set up in {time.monotonic() - t0:.0f} s")

    def honest_max(self, lab, touches):
        with open(os.path.join(self.ag, "grade-build", "tests.json"), encoding="utf-8") as f:
            tests = json.load(f)["labs"][lab]
        return sum(t["points"] for t in tests
                   if not any(f"[{task}]".lower() == tag.lower() for task in touches
                              for tag in t["tags"]))

    def submission(self, case):
        sub = os.path.join(self.ag, "submission")
        if os.path.lexists(sub):
            shutil.rmtree(sub)
        os.makedirs(sub)
        if case.get("generate"):  # every file of the lab made for the case (nonfinite.py)
            from wbtools import nonfinite
            for name, text in nonfinite.submission(REPO, case["lab"], case["generate"]).items():
                with open(os.path.join(sub, name), "w", encoding="utf-8") as f:
                    f.write(text)
            return
        sol = os.path.join(REPO, "solutions", case["lab"])
        for f in sorted(os.listdir(sol)):
            shutil.copy(os.path.join(sol, f), os.path.join(sub, f))
        target = os.path.join(sub, case["file"])
        os.remove(target)
        if "symlink" in case:
            os.symlink(os.path.join(REPO, case["symlink"]), target)
        else:
            shutil.copy(os.path.join(CASES, case["name"], case["file"]), target)
        for name, text in case.get("extra_files", {}).items():  # odd names, made here
            with open(os.path.join(sub, name), "w", encoding="utf-8") as f:
                f.write(text)

    def run_case(self, case, no_screen):
        """Returns (score or None, reasons, problems)."""
        self.submission(case)
        build = os.path.join(self.ag, "grade-build")
        # What the grader itself rewrites on every grading (grade-log.txt: its TA log of the
        # defences, tools/grader/cli.py ta_log) is not the submission's doing.
        keep = {"build", os.path.join("src", "labs"), "screened.json", ".lock", "cwd", "run",
                "view", "wb-hostile-view.txt", "grade-log.txt"}
        probe = os.path.join(self.ag, "grade-build", "wb-hostile-view.txt")
        if case.get("plant_view_probe"):  # world-readable, beside the build: the worker's view
            with open(probe, "w") as f:       # must not hold it
                f.write(self.secret + "\n")
            os.chmod(probe, 0o644)
        source = os.path.join(self.ag, "source")  # the project as Gradescope holds it
        before = dict(procs=processes(), tmp=tmp_entries(), checkout=checkout_files(),
                      build=tree_digest(build, keep), source=tree_digest(source))
        results = os.path.join(self.ag, "results", "results.json")
        env = dict(os.environ, AUTOGRADER_ROOT=self.ag, WB_HOSTILE_SECRET=self.secret,
                   WB_GRADE_ARGS=" ".join([GRADE_ARGS, case.get("grade_args", "")]
                                          + (["--no-screen"] if no_screen else [])))
        problems = []
        # "load": busy processes on every core meanwhile (a verdict must not depend on it).
        load = [subprocess.Popen([sys.executable, "-c", "while True: pass"],
                                 stdin=subprocess.DEVNULL) for _ in range(case.get("load", 0))]
        try:
            started = time.monotonic()
            r = subprocess.run(["bash", os.path.join(self.ag, "source", "run_autograder")],
                               env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               timeout=CASE_TIMEOUT)
            out = r.stdout.decode("utf-8", "replace")
            if r.returncode != 0:
                problems.append(f"run_autograder failed (status {r.returncode}): {out[-600:]}")
            took = time.monotonic() - started
            if case.get("max_seconds") and took > case["max_seconds"]:
                problems.append(f"run_autograder took {took:.0f} s, more than the "
                                f"{case['max_seconds']} s an idle test may make it take")
        except subprocess.TimeoutExpired:
            problems.append(f"run_autograder did not finish in {CASE_TIMEOUT} s")
            out = ""
        finally:
            for p in load:
                p.kill()
                p.wait()
        score, reasons = None, []
        try:
            with open(results, encoding="utf-8") as f:
                text = f.read()
            data = json.loads(text)
            cap = case.get("results_cap", RESULTS_CAP)
            if len(text.encode("utf-8")) > cap:
                problems.append(f"results.json is {len(text.encode())} bytes, more than {cap}")
            if re.search(r"^\S*euler: REFUSED: nothing, every test passed$", out, re.M) and \
                    case.get("extra_files"):
                problems.append("a file name printed a fake line into the table")
            score = data["score"]
            if score < case.get("min_score", 0):
                problems.append(f"scored {score}, less than the {case['min_score']} this honest "
                                "submission must get")
            if self.token in text or self.token in out:
                problems.append("a planted secret (another student's file, the grader's "
                                "environment, a file beside the build) appears in the results "
                                "or the log")
            for word in case.get("forbidden_in_results", []):
                word = word.replace("{scratch}", self.scratch)
                if word in text:
                    problems.append(f"the results show '{word}': the lab's code saw what it "
                                    "must not (another process, the tests, the build)")
            for t in data.get("tests", []):
                if t["status"] == "failed":
                    lines = t["output"].strip().splitlines()
                    if lines and lines[0].startswith("A submitted file was refused"):
                        lines = ["refused: " + (lines[1] if len(lines) > 1 else "")]
                    elif lines and lines[0].startswith("The lab does not compile"):
                        lines = ["does not compile: " + lines[-1]]
                    reasons.append(lines[0] if lines else "")
            if not data.get("tests"):
                reasons += str(data.get("output") or "").splitlines()[:1]
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
            problems.append(f"no valid results.json: {e}")
        time.sleep(0.3)
        after = processes()
        # Ours only: the machine may be shared with other graders whose tests run as the same
        # test users (their command lines name their own folders, never this scratch).
        stray = {p: v for p, v in after.items() if p not in before["procs"] and
                 self.scratch in v[1] or (v[0] in TEST_UIDS and self.scratch in v[1])}
        for p in stray:
            try:
                os.kill(p, 9)
            except OSError:
                pass
        if stray:
            problems.append(f"processes left behind: {sorted(v[1][:60] for v in stray.values())}")
        # New files of the test users, or named like the grader's or the cases' own (other
        # programs on the machine may create files in /tmp meanwhile: not ours to judge).
        new_tmp = {p for p in tmp_entries() - before["tmp"]
                   if owner(p) in TEST_UIDS or
                   os.path.basename(p).startswith("wb-hostile")}
        new_tmp = {p for p in new_tmp if not p.startswith(self.scratch)}
        if new_tmp:
            problems.append(f"files left behind: {sorted(new_tmp)}")
            for p in new_tmp:
                shutil.rmtree(p, ignore_errors=True) if os.path.isdir(p) else os.remove(p)
        if os.path.exists(probe):
            os.remove(probe)
        changed = diff(before["checkout"], checkout_files())
        if changed:
            problems.append(f"the checkout changed: {changed[:5]}")
        changed = diff(before["source"], tree_digest(source))
        if changed:
            problems.append(f"the autograder's project changed: {changed[:5]}")
        changed = diff(before["build"], tree_digest(build, keep))
        if changed:
            problems.append(f"the grader's scratch files changed: {changed[:5]}")
        return score, reasons, problems


def kill_grader(run, case):
    """SIGKILLs tools/grade while `case`'s tests are running: run_autograder must report
    an autograder failure (exit status not 0, no results.json) and nothing may be left."""
    run.submission(case)
    results = os.path.join(run.ag, "results", "results.json")
    before_tmp = tmp_entries()
    env = dict(os.environ, AUTOGRADER_ROOT=run.ag, WB_GRADE_ARGS="--timeout 60")
    proc = subprocess.Popen(["bash", os.path.join(run.ag, "source", "run_autograder")], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            start_new_session=True)
    problems, deadline = [], time.monotonic() + 300
    grader = None
    while time.monotonic() < deadline and proc.poll() is None:
        procs = processes()
        if any(uid in TEST_UIDS for uid, _ in procs.values()):
            grader = next((p for p, (uid, cmd) in procs.items()
                           if "tools/grade" in cmd and run.ag in cmd and "python" in cmd), None)
            if grader:
                break
        time.sleep(0.2)
    if grader is None:
        problems.append("no test process was seen running: nothing was killed")
        proc.kill()
    else:
        os.kill(grader, 9)
    out = proc.communicate(timeout=120)[0].decode("utf-8", "replace")
    if proc.returncode == 0:
        problems.append("run_autograder exited 0 although tools/grade was killed")
    if os.path.exists(results):
        problems.append("a results.json was left although tools/grade was killed")
    if "autograder error" not in out:
        problems.append("run_autograder did not say it failed")
    time.sleep(1)
    stray = [cmd for uid, cmd in processes().values() if uid in TEST_UIDS and run.scratch in cmd]
    if stray:
        problems.append(f"test processes outlived the killed grader: {stray[:3]}")
    new_tmp = {p for p in tmp_entries() - before_tmp if owner(p) in TEST_UIDS or
               os.path.basename(p).startswith("wb-hostile")}
    if new_tmp:
        problems.append(f"files left behind: {sorted(new_tmp)}")
    return problems


def main(argv):
    ap = argparse.ArgumentParser(prog="tools/gradescope/hostile", description=__doc__.split("\n")[0])
    ap.add_argument("--case", action="append", default=[], help="run only this case (repeatable)")
    ap.add_argument("--screen-only", action="store_true",
                    help="skip the second, --no-screen run of the cases that have one")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder (printed)")
    ap.add_argument("--scratch", metavar="DIR",
                    help="use (and keep) this scratch folder: a kept one is reused, so only what "
                         "changed is rebuilt")
    args = ap.parse_args(argv)
    cases = load_cases(args.case)
    labs = sorted({c["lab"] for c in cases})
    t0 = time.monotonic()
    rows, bad = [], 0
    if args.scratch:
        scratch = os.path.abspath(args.scratch)
        os.makedirs(scratch, mode=0o700, exist_ok=True)
        args.keep = True
    else:
        scratch = tempfile.mkdtemp(prefix="wb-hostile-")
    # Other users may pass through (the build runs as another user, like the tests), not list
    # it; the planted secret's folder stays private.
    os.chmod(scratch, 0o711)
    try:
        run = Run(scratch, labs)
        run.setup()
        for lab in labs:
            for case in (c for c in cases if c["lab"] == lab):
                modes = [False] + ([True] if case.get("no_screen") and not args.screen_only else [])
                for no_screen in modes:
                    t1 = time.monotonic()
                    score, reasons, problems = run.run_case(case, no_screen)
                    limit = min(run.honest_max(lab, case["touches"]), case.get("honest_max", 100))
                    if score is not None and score > limit:
                        problems.append(f"scored {score}, more than the honest {limit}")
                    how = reasons[0] if reasons else ""
                    mode = "sandbox only" if no_screen else "as submitted"
                    ok = not problems
                    bad += not ok
                    layer = case.get("stopped_by", "").split(" | ")
                    layer = layer[-1] if no_screen else layer[0]
                    rows.append((case["name"] if case["lab"] == "euler" else
                                 f"{case['name']} ({lab})", mode, score, limit,
                                 "held" if ok else "GOT THROUGH",
                                 layer, problems))
                    log(f"hostile: {case['name']} ({lab}, {mode}): {score}/{limit} "
                        f"{'held' if ok else 'GOT THROUGH'} in {time.monotonic() - t1:.0f} s: "
                        f"{how[:110]}")
                    for p in problems:
                        log(f"    problem: {p}")
            loop = [c for c in cases if c["name"] == "infinite-loop" and c["lab"] == lab]
            if not args.case and loop:
                t1 = time.monotonic()
                problems = kill_grader(run, loop[0])
                bad += bool(problems)
                rows.append(("(grader SIGKILLed)", "as submitted", None, 0,
                             "GOT THROUGH" if problems else "held",
                             "run_autograder: no results.json, exit 1; the launcher dies with the "
                             "grader", problems))
                log(f"hostile: tools/grade killed mid-run: {'held' if not problems else 'GOT THROUGH'} "
                    f"in {time.monotonic() - t1:.0f} s")
                for p in problems:
                    log(f"    problem: {p}")
    finally:
        if args.keep:
            log(f"hostile: kept {scratch}")
        else:
            shutil.rmtree(scratch, ignore_errors=True)
    print()
    print(f"{'case':<30} {'run':<13} {'score':>5} {'max':>4}  verdict      designed to be stopped by")
    for name, mode, score, limit, verdict, how, _ in rows:
        print(f"{name:<30} {mode:<13} {score if score is not None else '-':>5} {limit:>4}  "
              f"{verdict:<12} {how[:90]}")
    print(f"\nhostile: {len(rows) - bad} of {len(rows)} runs held, in {time.monotonic() - t0:.0f} s")
    return 1 if bad else 0


def run():
    """The entry tools/gradescope/hostile calls: main() with the command line, its exit status."""
    sys.exit(main(sys.argv[1:]))
