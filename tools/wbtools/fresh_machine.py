"""Tries the workbook as a newcomer would, on brand-new Debian 12 machines that have only git."""
# The fresh-machine stage of tools/check (docs/grading.md, "On a fresh machine").
# mmdebstrap makes a minimal Debian 12 root (--variant=minbase, git and
# ca-certificates: no Python, no compiler); the checkout's commit is cloned into
# it, and three copies of that root play three people:
#   1. the instructor: `tools/pack --gradescope LAB` makes the zip (and installs
#      what the instructor needs), then `tools/report` (builds, draws) must
#      write build/report/index.html with every lab's figures (its claims
#      checked), then `tools/pack --out` makes the pack (with --verify:
#      docs/report.md checked against the report,
#      tools/check's stages that need the full build run on the report's build,
#      and the pack verified without building it, each lab's alone too, each
#      lab's closure read from the report's build; then the report's viewer
#      pages are opened in headless Chromium, tools/view-check);
#   2. Gradescope: the zip unpacked in /autograder/source of a pristine root,
#      its setup.sh run there, a submission in /autograder/submission and
#      /autograder/run_autograder run: results.json must be valid and score the
#      skeleton 0 and the solution 100 (the closest we come to Gradescope itself);
#   3. a student: the pack (all labs) unpacked in a pristine root, then every
#      command of its README's sh blocks run in order: tools/setup, the build,
#      a run, the plots, the tests, the grader (with --verify, then what the
#      instructor's tools/pack --verify --no-build leaves to the pack's one build,
#      this one: the build used prebuilt/, every skeleton scores 0, each lab's
#      own README commands run).
# Each root runs in its own mount and PID namespaces, entered with pivot_root
# (as a container is), not chroot: in a chroot the kernel refuses the user
# namespaces the grader's sandbox makes. apt in the roots uses this machine's
# Debian mirror and proxy. Needs root, mmdebstrap and the network.
import argparse
import hashlib
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SUITE = "bookworm"
INCLUDE = "git,ca-certificates"
CACHE_DAYS = 7  # a cached root older than this is made again (security updates)
# The root tarball is cached for the machine, not the checkout: a clean clone (as CI
# and tools/check from a new clone are) then reuses the root the last run made, instead
# of three minutes of mmdebstrap. The runs' work folders stay in the checkout's build/.
CACHE = "/var/cache/sim-workbook/fresh-machine"
ROOT_ENV = {"HOME": "/root", "PATH": "/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"}

# Enters root $1 and runs $2 with bash as root's login would: new mount and PID
# namespaces (unshare), /proc, /sys and /dev mounted, then pivot_root so that the
# root is the namespace's own (not a chroot), the old root unmounted. $3, when
# given, is bind-mounted on the root's apt archive (the instructor's downloads,
# hard-linked into the others': each package is downloaded once).
ENTER = r"""
set -e
r=$1 cmd=$2 debs=$3
mount --rbind "$r" "$r"
mount -t proc proc "$r/proc"
mount -t sysfs -o ro sysfs "$r/sys"
mount --rbind /dev "$r/dev"
[ -z "$debs" ] || mount --bind "$debs" "$r/var/cache/apt/archives"
cd "$r"
mkdir -p .host
pivot_root . .host
umount -l /.host
rmdir /.host
cd /root
exec /usr/bin/env -i HOME="$WB_HOME" PATH="$WB_PATH" /bin/bash -c "$cmd"
"""


RUNNING = set()  # the unshare processes running now, killed if this tool is stopped


def stop(signum, frame):
    """SIGTERM or SIGINT: SIGKILL to every unshare (its --kill-child ends the machine's
    processes with it), then exit."""
    for p in list(RUNNING):
        p.kill()
    print(f"tools/fresh-machine: stopped by signal {signum}", file=sys.stderr, flush=True)
    os._exit(128 + signum)


def call(cmd):
    """Runs a short host command (tar, git) that stop() can end; a failure raises StageError."""
    p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL)
    RUNNING.add(p)
    try:
        if p.wait() != 0:
            raise StageError(f"`{' '.join(cmd)}` exited with status {p.returncode}")
    finally:
        RUNNING.discard(p)


class StageError(Exception):
    """What went wrong, in one line (the logs say more)."""


def log(msg):
    print(f"fresh-machine: {msg}", flush=True)


def host_apt():
    """This machine's Debian mirror, security mirror and apt proxy, for the roots."""
    mirror, security = "http://deb.debian.org/debian", "http://deb.debian.org/debian-security"
    uris = []
    for d, names in (("/etc/apt", ["sources.list"]),
                     ("/etc/apt/sources.list.d", sorted(os.listdir("/etc/apt/sources.list.d"))
                      if os.path.isdir("/etc/apt/sources.list.d") else [])):
        for n in names:
            if not n.endswith((".list", ".sources")):
                continue
            try:
                with open(os.path.join(d, n), encoding="utf-8") as f:
                    text = f.read()
            except OSError:
                continue
            uris += re.findall(r"^\s*URIs:\s*(\S+)", text, re.M)
            uris += re.findall(r"^\s*deb\s+(?:\[[^\]]*\]\s+)?(\S+)", text, re.M)
    for u in uris:
        u = u.rstrip("/")
        if u.endswith("/debian-security"):
            security = u
        elif u.endswith("/debian"):
            mirror = u
    proxies = []
    p = subprocess.run(["apt-config", "dump"], stdout=subprocess.PIPE, text=True)
    for m in re.finditer(r'^(Acquire::(?:http|https)::Proxy(?:::[^ ]+)?) "([^"]*)";', p.stdout,
                         re.M):
        proxies.append(f'{m.group(1)} "{m.group(2)}"')
    return mirror, security, proxies


def mmdebstrap_options():
    """mmdebstrap's options and sources.list for a minimal Debian 12 root, and a short key
    of them that names the cached tarball (another mirror or option: another root)."""
    mirror, security, proxies = host_apt()
    sources = (f"deb {mirror} {SUITE} main\ndeb {mirror} {SUITE}-updates main\n"
               f"deb {security} {SUITE}-security main\n")
    opts = ["--variant=minbase", f"--include={INCLUDE}",
            "--dpkgopt=force-unsafe-io"]  # dpkg without fsync, as Debian's container images have
    opts += [f"--aptopt={p}" for p in proxies]
    key = hashlib.sha256("\n".join(opts + [sources]).encode()).hexdigest()[:10]
    return opts, sources, key, f"mirror {mirror}" + (f", {len(proxies)} apt proxy setting(s)"
                                                     if proxies else ", no apt proxy")


def make_root_tar(path, work):
    """A minimal Debian 12 root as a tarball (mmdebstrap), written atomically to path."""
    opts, text, _, where = mmdebstrap_options()
    sources = os.path.join(work, "sources.list")
    with open(sources, "w", encoding="utf-8") as f:
        f.write(text)
    tmp = path + ".tmp.tar"
    cmd = ["mmdebstrap"] + opts + [SUITE, tmp, sources]
    log(f"mmdebstrap: a minimal {SUITE} root ({where})")
    run_logged(cmd, os.path.join(work, "logs", "mmdebstrap.log"), "mmdebstrap")
    os.replace(tmp, path)


def wait_running(p, timeout, late):
    """p's exit status; p is in RUNNING (ended on a signal) while it runs, and killed past
    timeout, which raises StageError(late)."""
    RUNNING.add(p)
    try:
        return p.wait(timeout)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
        raise StageError(late)
    finally:
        RUNNING.discard(p)


def run_logged(cmd, logfile, what, env=None, timeout=None):
    """Runs cmd with its output in logfile; a failure raises StageError with the last lines."""
    with open(logfile, "ab") as f:
        f.write(("\n$ " + " ".join(cmd[:4]) + (" ..." if len(cmd) > 4 else "") + "\n").encode())
        f.flush()
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                             env=env)
        status = wait_running(p, timeout,
                              f"{what}: did not finish in {timeout} s (log: {rel(logfile)})")
    if status != 0:
        raise StageError(f"{what}: exit status {status}\n{tail(logfile)}\n"
                         f"(whole log: {rel(logfile)})")


def tail(logfile, n=25):
    with open(logfile, "rb") as f:
        lines = f.read().decode("utf-8", "replace").splitlines()
    return "\n".join("  | " + x for x in lines[-n:])


def rel(path):
    p = os.path.relpath(path, ROOT)
    return path if p.startswith("..") else p


class Machine:
    """One fresh root: the tarball unpacked in its own folder."""

    def __init__(self, name, tarball, work, debs):
        self.name, self.debs, self.logs = name, debs, os.path.join(work, "logs")
        self.path = os.path.join(work, name)
        os.makedirs(self.path)
        call(["tar", "-C", self.path, "--numeric-owner", "-xpf", tarball])
        shutil.copy("/etc/resolv.conf", os.path.join(self.path, "etc", "resolv.conf"))

    def host(self, path):
        """The host's path of the machine's path."""
        return os.path.join(self.path, path.lstrip("/"))

    def run(self, what, cmd, timeout=None, check=True):
        """Runs cmd (bash) inside as root; logs to logs/<machine>.log; returns the exit status."""
        logfile = os.path.join(self.logs, f"{self.name}.log")
        env = dict(os.environ, WB_HOME=ROOT_ENV["HOME"], WB_PATH=ROOT_ENV["PATH"])
        full = ["unshare", "--mount", "--pid", "--fork", "--kill-child", "--propagation", "private",
                "sh", "-c", ENTER, "sh", self.path, cmd, self.debs or ""]
        t0 = time.monotonic()
        log(f"[{self.name}] $ {cmd}")
        with open(logfile, "ab") as f:
            f.write(f"\n### {what}\n$ {cmd}\n".encode())
            f.flush()
            p = subprocess.Popen(full, stdout=f, stderr=subprocess.STDOUT,
                                 stdin=subprocess.DEVNULL, env=env)
            status = wait_running(p, timeout, f"{self.name}: {what}: `{cmd}` did not finish in "
                                              f"{timeout} s (log: {rel(logfile)})")
        log(f"[{self.name}]   exit {status} in {time.monotonic() - t0:.0f} s")
        if check and status != 0:
            raise StageError(f"{self.name}: {what}: `{cmd}` exited with status {status}\n"
                             f"{tail(logfile)}\n(whole log: {rel(logfile)})")
        return status


def check_report(m, clone):
    """build/report/index.html exists and shows figures of every lab that has a solution."""
    report = m.host(f"{clone}/build/report")
    index = os.path.join(report, "index.html")
    if not os.path.isfile(index):
        raise StageError("instructor: tools/report exited 0 but wrote no build/report/index.html")
    with open(index, encoding="utf-8") as f:
        html = f.read()
    imgs = re.findall(r'<img src="([^"]+)"', html)
    missing = [i for i in imgs if not os.path.isfile(os.path.join(report, i))]
    if missing:
        raise StageError(f"instructor: index.html shows {len(missing)} figure(s) that are not "
                         f"there, e.g. {missing[0]}")
    labs = sorted(d for d in os.listdir(m.host(f"{clone}/solutions"))
                  if os.path.isdir(m.host(f"{clone}/solutions/{d}")))
    without = [lab for lab in labs if not any(i.startswith(f"{lab}/") for i in imgs)]
    if without:
        raise StageError(f"instructor: the report has no figure of the lab(s) {', '.join(without)}")
    log(f"[{m.name}]   report: {len(imgs)} figures, every lab's ({', '.join(labs)})")


def unzip_as_gradescope(zip_path, m):
    """Unpacks the autograder zip in /autograder/source (modes kept, as unzip does) and
    puts run_autograder in /autograder, as Gradescope does."""
    src = m.host("/autograder/source")
    os.makedirs(src)
    with zipfile.ZipFile(zip_path) as z:
        for info in z.infolist():
            dest = os.path.join(src, info.filename)
            if not os.path.realpath(dest).startswith(os.path.realpath(src) + os.sep):
                raise StageError(f"gradescope: the zip holds a path outside its folder: "
                                 f"{info.filename}")
            z.extract(info, src)
            mode = (info.external_attr >> 16) & 0o777
            if mode:
                os.chmod(dest, mode)
    shutil.copy2(os.path.join(src, "run_autograder"), m.host("/autograder/run_autograder"))
    os.makedirs(m.host("/autograder/submission"))
    os.makedirs(m.host("/autograder/results"), exist_ok=True)


def check_results(m, expected, what):
    path = m.host("/autograder/results/results.json")
    try:
        with open(path, encoding="utf-8") as f:
            res = json.load(f)
    except (OSError, ValueError) as e:
        raise StageError(f"gradescope: {what}: no valid /autograder/results/results.json ({e})")
    tests = res.get("tests")
    if not isinstance(res.get("score"), (int, float)) or not isinstance(tests, list) or not tests:
        raise StageError(f"gradescope: {what}: results.json has no numeric score or no tests")
    for t in tests:
        if not (isinstance(t, dict) and isinstance(t.get("name"), str)
                and isinstance(t.get("score"), (int, float))
                and isinstance(t.get("max_score"), (int, float))):
            raise StageError(f"gradescope: {what}: a test entry lacks name, score or max_score: "
                             f"{str(t)[:200]}")
    total = sum(t["max_score"] for t in tests)
    if res["score"] != expected or total != 100:
        raise StageError(f"gradescope: {what}: scored {res['score']} of {total}, expected "
                         f"{expected} of 100\n  " + str(res.get("output", ""))[:800])
    log(f"[{m.name}]   results.json: {what} scored {res['score']} of {total} "
        f"({len(tests)} tests)")


def readme_commands(readme):
    """The command lines of a README's ```sh blocks, in order: tools/pack's own reading
    (what its --verify runs), so that the two never run different lists."""
    from wbtools import pack
    return pack.readme_commands(os.path.dirname(readme))


# tools/check's stages that need the full build, run with --verify on the instructor's (the
# report's) instead of a second build on the host: (what, command).
BUILD_CHECKS = [
    ("every skeleton run on every default scene warns it is a stub, no solution run does",
     "tools/pattern stubs"),
    ("no scene lets a do-nothing step score zero error", "tools/pattern periods"),
    ("a figure of a stub run says so", "tools/pattern stubfigs"),
    ("graded tests against the solutions", "ctest --preset default -L solution --no-tests=error"),
    ("bad input gets one line and exit 2", "ctest --preset default -L badinput --no-tests=error"),
]

# The viewer's browser test, on the report's pages and build (it installs chromium itself).
VIEW_CHECK = ("the report's viewer pages work in a browser (tools/view-check)", "tools/view-check")


class Handoff:
    """What the instructor hands to the others, each as soon as it exists: the solution's
    files and the zip (right after the clone), the pack (with --verify: its draft, written
    before the verification starts; compared with the verified pack at the end, and with it
    each lab's README commands that the pack's README lacks, tools/pack --lab-commands)."""

    def __init__(self, work):
        self.solution = os.path.join(work, "solution-files")
        self.zip = os.path.join(work, "autograder.zip")
        self.pack = os.path.join(work, "sim-workbook.tar.gz")
        self.lab_commands = os.path.join(work, "lab-commands.json")
        self.zip_ready, self.pack_ready, self.failed = (threading.Event(), threading.Event(),
                                                        threading.Event())

    def wait(self, event, what):
        while not event.wait(1.0):
            if self.failed.is_set():
                raise StageError(f"not run: the instructor failed before making {what}")


def instructor(args, work, tarball, debs, hand):
    """The README's main job in a clone, and the two packs, handed over as they are made."""
    clone, lab = "/root/workbook", args.lab
    a = Machine("instructor", tarball, work, debs)
    call(["git", "clone", "-q", "--no-hardlinks", ROOT, a.host(clone)])
    call(["git", "-C", a.host(clone), "checkout", "-q", "--detach", args.rev])
    shutil.copytree(a.host(f"{clone}/solutions/{lab}"), hand.solution)
    # The zip needs nothing built: Gradescope's root starts on it as soon as this first
    # Python tool has installed the packages.
    a.run("the Gradescope zip", f"cd {clone} && tools/pack --gradescope {lab} --out /root/ag.zip")
    shutil.copy(a.host("/root/ag.zip"), hand.zip)
    hand.zip_ready.set()
    a.run("the README's main job", f"cd {clone} && tools/report")
    check_report(a, clone)
    failed = []
    if args.verify:  # what tools/check would otherwise check on this machine's own build
        a.run("docs/report.md against the report", f"cd {clone} && tools/pattern reportdoc")
        for what, cmd in BUILD_CHECKS:
            if a.run(what, f"cd {clone} && {cmd}", check=False) != 0:
                failed.append(f"instructor: {what}: `{cmd}` failed\n"
                              f"{tail(os.path.join(work, 'logs', 'instructor.log'))}")
    try:
        make_pack(args, a, clone, hand)
    except StageError as e:
        raise StageError("\n".join(failed + [str(e)])) from None
    if args.verify:  # after the pack, beside the student's build of it (docs/view.md)
        what, cmd = VIEW_CHECK
        if a.run(what, f"cd {clone} && {cmd}", check=False) != 0:
            failed.append(f"instructor: {what}: `{cmd}` failed\n"
                          f"{tail(os.path.join(work, 'logs', 'instructor.log'))}")
        shots, kept = a.host(f"{clone}/build/view-check"), os.path.join(os.path.dirname(work),
                                                                        "view-check")
        if os.path.isdir(shots):  # kept after the work folder goes: build/fresh-machine/
            shutil.rmtree(kept, ignore_errors=True)
            shutil.copytree(shots, kept)
    if not args.keep:
        remove_root(a)
    if failed:
        raise StageError("\n".join(failed))


def make_pack(args, a, clone, hand):
    """The student pack, handed over as soon as it exists (with --verify: its draft, and the
    commands of each lab's README that the student's root runs)."""
    draft, cmds = a.host("/root/draft.tar.gz"), a.host("/root/lab-commands.json")
    if args.verify:
        # The student starts on the draft (the same files, written before the verification
        # starts) while the pack is verified here. The verification does not build the pack
        # (--no-build: each lab's closure is read from the report's build): the student's
        # root builds it anyway, and checks there what a build is needed for (student()).
        def hand_draft():
            while not (os.path.isfile(draft) and os.path.isfile(cmds)) and not done.is_set():
                time.sleep(1.0)
            if os.path.isfile(draft) and os.path.isfile(cmds):
                shutil.copy(cmds, hand.lab_commands)
                shutil.copy(draft, hand.pack)
                hand.pack_ready.set()
        done = threading.Event()
        watcher = threading.Thread(target=hand_draft)
        watcher.start()
        try:
            a.run("the student pack", f"cd {clone} && tools/pack --out /root/sim-workbook.tar.gz "
                  "--draft /root/draft.tar.gz --lab-commands /root/lab-commands.json "
                  "--verify --no-build --each-lab")
        finally:
            done.set()
            watcher.join()
        same_pack(draft, a.host("/root/sim-workbook.tar.gz"))
    else:
        a.run("the student pack", f"cd {clone} && tools/pack --out /root/sim-workbook.tar.gz")
        shutil.copy(a.host("/root/sim-workbook.tar.gz"), hand.pack)
        hand.pack_ready.set()


def same_pack(draft, final):
    """The verified pack holds exactly the draft's files (the student tried the draft)."""
    import tarfile

    def files(path):
        out = {}
        with tarfile.open(path) as t:
            for m in t.getmembers():
                data = t.extractfile(m).read() if m.isfile() else m.linkname.encode()
                out[m.name] = (m.type, m.mode, hashlib.sha256(data).hexdigest())
        return out
    a, b = files(draft), files(final)
    if a != b:
        diff = sorted(set(a) ^ set(b)) + sorted(n for n in set(a) & set(b) if a[n] != b[n])
        raise StageError("instructor: the verified pack differs from the draft the student "
                         f"tried: {', '.join(diff[:5])}")


def gradescope(args, work, tarball, debs, zip_path, solution):
    """The zip on a pristine root, as Gradescope runs it: the skeleton scores 0, the solution 100."""
    lab = args.lab
    g = Machine("gradescope", tarball, work, debs)
    unzip_as_gradescope(zip_path, g)
    g.run("the zip's setup.sh", "cd /autograder/source && bash ./setup.sh")
    sub = g.host("/autograder/submission")
    for side, folder, expected in (("skeleton", g.host(f"/autograder/source/labs/{lab}"), 0),
                                   ("solution", solution, 100)):
        for name in os.listdir(sub):
            os.remove(os.path.join(sub, name))
        for name in sorted(os.listdir(folder)):
            if name.endswith(".cpp"):
                shutil.copy(os.path.join(folder, name), sub)
        g.run(f"run_autograder on the {side}", "cd /autograder && /autograder/run_autograder")
        check_results(g, expected, f"the {lab} {side}")
    if not args.keep:
        remove_root(g)


def command_failed(cmd, status):
    """A README command fails when it is not found, dies of a signal, or (all but the test
    runners, which the skeletons fail) exits non-zero: tools/pack's rule."""
    first = cmd.split()[0]
    tests = first.endswith("-tests") or first == "ctest"
    return status in (126, 127) or status > 128 or (status != 0 and not tests)


# A lab README's command that grades that lab's skeleton alone, as `tools/grade labs
# --require-score 0`, run on the student's root just before with the same scratch build,
# has done: not run a second time when that passed. (The README's comment after it is
# allowed; anything else on the line makes it another command, which is run.)
GRADE_ONE_LAB = re.compile(r"tools/grade labs --lab ([A-Za-z0-9_-]+)(?:\s+#.*)?")


def student(args, work, tarball, debs, hand):
    """The pack on a pristine root: its README's commands in order. With --verify, also what
    the instructor's tools/pack --verify --no-build leaves to whoever builds the pack (the
    one build of the pack in this stage is this one): the build used prebuilt/, every
    lab's skeleton scores 0, and each lab's own README commands run."""
    s = Machine("student", tarball, work, debs)
    call(["tar", "-C", s.host("/root"), "-xzf", hand.pack])
    home = "/root/sim-workbook"
    logfile = os.path.join(work, "logs", "student.log")
    configured = []  # the output of the README's configure command(s)
    for cmd in readme_commands(s.host(f"{home}/README.md")):
        start = os.path.getsize(logfile) if os.path.exists(logfile) else 0
        status = s.run("a command of the pack's README", f"cd {home} && {cmd}", check=False)
        if command_failed(cmd, status):
            raise StageError(f"student: the pack's README command `{cmd}` exited with status "
                             f"{status}\n{tail(logfile)}")
        if cmd.startswith("cmake --preset"):
            with open(logfile, "rb") as f:
                f.seek(start)
                configured.append(f.read().decode("utf-8", "replace"))
    if args.verify:
        problems = student_checks(s, home, hand, "\n".join(configured), logfile)
        if problems:
            raise StageError("\n".join(problems) + f"\n(whole log: {rel(logfile)})")
    if not args.keep:
        remove_root(s)


def student_checks(s, home, hand, configured, logfile):
    """With --verify, after the README's commands: what tools/pack --verify checked in a build
    of its own before tools/pack --no-build left it to the pack's one build, this one.
    Returns the problems (each with the log's last lines)."""
    problems = []
    said = [line.strip() for line in configured.splitlines() if "prebuilt framework" in line]
    if "prebuilt framework: used" not in configured:
        problems.append("student: the pack's build does not use its prebuilt framework: "
                        + (said[0] if said else "cmake said nothing about it"))
    # Every grading here shares one scratch build, as tools/pack --verify's did.
    env = "export WB_GRADE_BUILD_DIR=/root/grade-build && "
    cmd = "tools/grade labs --require-score 0"
    status = s.run("every lab's skeleton scores 0", f"cd {home} && {env}{cmd}", check=False)
    scored = status == 0
    if not scored:
        problems.append(f"student: the pack's skeletons do not score 0 (`{cmd}` exited with "
                        f"status {status})\n{tail(logfile, 12)}")
    with open(hand.lab_commands, encoding="utf-8") as f:
        each = json.load(f)["labs"]
    labs = {d for d in os.listdir(s.host(f"{home}/labs"))
            if os.path.isdir(s.host(f"{home}/labs/{d}"))}
    graded = cmd
    for entry in each:
        lab = entry["lab"]
        for cmd in entry["commands"]:
            m = GRADE_ONE_LAB.fullmatch(cmd)
            if scored and m and m.group(1) in labs:
                why = (f"lab {lab}'s README; not run again: `{graded}` above graded lab "
                       f"{m.group(1)}'s skeleton with the same grader and scratch build")
                log(f"[{s.name}] $ {cmd}  ({why})")
                with open(logfile, "ab") as f:
                    f.write(f"\n### skipped\n$ {cmd}\n({why})\n".encode())
                continue
            status = s.run(f"a command of lab {lab}'s README (its pack alone has it)",
                           f"cd {home} && {env}{cmd}", check=False)
            if command_failed(cmd, status):
                problems.append(f"student: lab {lab}'s README command `{cmd}` exited with status "
                                f"{status}\n{tail(logfile, 12)}")
    return problems


def stage(args, work, tarball):
    """The three at once, each starting as soon as what it needs exists: Gradescope on the
    zip (made right after the clone, so its apt and build overlap the instructor's report),
    the student on the pack (with --verify its draft, while the instructor verifies it)."""
    debs = os.path.join(work, "debs")  # the instructor's downloads, reused by the student
    os.makedirs(os.path.join(debs, "partial"))
    hand = Handoff(work)
    errors = []

    def run(fn, *a):
        try:
            fn(*a)
        except Exception as e:  # noqa: BLE001 (reported below, with the others')
            errors.append(e)
            if fn is instructor:
                hand.failed.set()

    def gradescope_side():
        hand.wait(hand.zip_ready, "the zip")
        # Its own apt archive, empty: the instructor is still downloading into its own.
        own = os.path.join(work, "debs-gradescope")
        os.makedirs(os.path.join(own, "partial"))
        gradescope(args, work, tarball, own, hand.zip, hand.solution)

    def student_side():
        hand.wait(hand.pack_ready, "the pack")
        # One apt archive each (apt locks it: its lock file is not linked), the .deb files
        # hard links of the instructor's (its report installed them).
        own = os.path.join(work, "debs-student")
        os.makedirs(os.path.join(own, "partial"))
        for deb in os.listdir(debs):
            if deb.endswith(".deb"):
                os.link(os.path.join(debs, deb), os.path.join(own, deb))
        student(args, work, tarball, own, hand)

    threads = [threading.Thread(target=run, args=(instructor, args, work, tarball, debs, hand)),
               threading.Thread(target=run, args=(gradescope_side,)),
               threading.Thread(target=run, args=(student_side,))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    if errors:
        raise StageError("\n".join(str(e) for e in errors))


def remove_root(m):
    remove(m.path)


def remove(path):
    """Removes a file or folder, never one with something mounted in it (a root's /dev)."""
    with open("/proc/self/mountinfo", encoding="utf-8") as f:
        if any((line.split()[4] + "/").startswith(path.rstrip("/") + "/") for line in f):
            raise StageError(f"{path} has mounts in it; not removed")
    # rm: faster than shutil.rmtree on a root's hundred thousand files, and it never
    # crosses into another file system.
    subprocess.run(["rm", "-rf", "--one-file-system", path], check=True)


def main(argv):
    ap = argparse.ArgumentParser(
        prog="tools/fresh-machine", description=__doc__,
        epilog="Exit status: 0 every step passed, 1 a step failed (the line says which; logs in "
               "the work folder), 2 bad flags or this machine cannot run it (not root, no "
               "mmdebstrap). See docs/grading.md, \"On a fresh machine\".")
    ap.add_argument("--lab", default="forces",
                    help="the lab whose Gradescope zip is tried (default forces)")
    ap.add_argument("--rev", default="HEAD",
                    help="the commit of this checkout to clone (default HEAD: commit first; "
                         "uncommitted changes are not in the clone)")
    ap.add_argument("--cache", default=CACHE,
                    help=f"folder of the cached root tarball (default {CACHE}: one for the "
                         "machine, shared by every checkout); a tarball older than "
                         f"{CACHE_DAYS} days is made again")
    ap.add_argument("--no-cache", action="store_true",
                    help="make a new root with mmdebstrap, and keep it nowhere")
    ap.add_argument("--verify", action="store_true",
                    help="in the instructor's root, also check docs/report.md against its report "
                         "(tools/pattern reportdoc), run the stages of tools/check that need the "
                         "full build on the report's build (tools/pattern stubs and periods, "
                         "ctest -L solution and -L badinput), verify the pack it makes "
                         "without building it (tools/pack --verify --no-build --each-lab) and "
                         "open the report's viewer pages in headless Chromium "
                         "(tools/view-check); in "
                         "the student's root, which builds the pack, check the rest of "
                         "tools/pack --verify --each-lab: the build used prebuilt/, every "
                         "skeleton scores 0 (tools/grade labs --require-score 0), each lab's "
                         "own README commands run. tools/check's own stages for those, run here "
                         "instead of on this machine")
    ap.add_argument("--keep", action="store_true",
                    help="keep the work folder (the three roots and the logs) for a look")
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    if os.geteuid() != 0:
        print("tools/fresh-machine: needs root (it unpacks Debian roots and mounts in them); "
              "run it as root or with sudo", file=sys.stderr)
        return 2
    if not shutil.which("mmdebstrap"):
        print("tools/fresh-machine: mmdebstrap is missing: tools/setup --fresh-machine installs "
              "it", file=sys.stderr)
        return 2
    labs = os.listdir(os.path.join(ROOT, "tests"))
    if args.lab not in labs or not os.path.isdir(os.path.join(ROOT, "solutions", args.lab)):
        print(f"tools/fresh-machine: --lab: got '{args.lab}', expected a lab with tests and a "
              "solution", file=sys.stderr)
        return 2
    rev = subprocess.run(["git", "-C", ROOT, "rev-parse", "--verify", "-q", args.rev + "^{commit}"],
                         stdout=subprocess.PIPE, text=True)
    if rev.returncode != 0:
        print(f"tools/fresh-machine: --rev: '{args.rev}' is not a commit of this checkout",
              file=sys.stderr)
        return 2
    args.rev = rev.stdout.strip()
    dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                           stdout=subprocess.PIPE, text=True).stdout.strip()

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    t0 = time.monotonic()
    works = os.path.join(ROOT, "build", "fresh-machine")
    try:
        for folder in (args.cache, works):
            os.makedirs(folder, exist_ok=True)
    except OSError as e:
        print(f"tools/fresh-machine: cannot make the folder {e.filename} (--cache, or the "
              f"work folders' build/fresh-machine): {e.strerror}", file=sys.stderr)
        return 2
    work = tempfile.mkdtemp(prefix="run-", dir=works)
    os.makedirs(os.path.join(work, "logs"))
    log(f"cloning commit {args.rev[:12]} into fresh {SUITE} roots; work folder {rel(work)}"
        + (" (uncommitted changes of the checkout are not in it)" if dirty else ""))
    ok = False
    try:
        if args.no_cache:
            tarball = os.path.join(work, "root.tar")
            make_root_tar(tarball, work)
        else:
            tarball = os.path.join(args.cache, f"{SUITE}-minbase-{mmdebstrap_options()[2]}.tar")
            fresh = (os.path.isfile(tarball)
                     and time.time() - os.path.getmtime(tarball) < CACHE_DAYS * 86400)
            if fresh:
                log(f"using the cached root {rel(tarball)} (--no-cache makes a new one)")
            else:
                make_root_tar(tarball, work)
        log(f"root ready after {time.monotonic() - t0:.0f} s")
        stage(args, work, tarball)
        ok = True
    except StageError as e:
        print(f"tools/fresh-machine: FAILED: {e}", file=sys.stderr)
    finally:
        ru = resource.getrusage(resource.RUSAGE_CHILDREN)
        log(f"{'passed' if ok else 'FAILED'} in {time.monotonic() - t0:.0f} s wall, "
            f"{ru.ru_utime + ru.ru_stime:.0f} s of CPU (user and system, every process it ran)")
        if ok and not args.keep:
            remove(work)
        elif args.keep:
            log(f"work folder kept: {rel(work)} (the roots, and the logs in logs/)")
        else:  # keep the logs only: the roots take gigabytes
            for name in os.listdir(work):
                if name != "logs":
                    remove(os.path.join(work, name))
            log(f"logs kept in {rel(work)}/logs")
    return 0 if ok else 1


def run():
    """The entry tools/fresh-machine calls: main() with the command line, its exit status."""
    sys.exit(main(sys.argv[1:]))
