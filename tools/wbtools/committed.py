"""What was committed: the tree of HEAD exported, and the files that differ from it.

The student pack and the Gradescope zip are made from HEAD, never from the work tree (issue
44: an instructor's try of an exercise in labs/ must not ship); the report records the commit
it drew its figures from, so that tools/pack can tell whether they are current for HEAD.

Trust: reads the checkout through git; writes only the folder it is given."""
import os
import subprocess
import tarfile

# The files a figure of tools/report depends on (git pathspecs): the solutions it runs, what
# they are compiled with, the scenes, and the tools that draw. Not the handouts (the report only
# checks their claims), the tests or the skeletons' .cpp files (the report runs no skeleton).
REPORT_INPUTS = ["CMakeLists.txt", "CMakePresets.json", "cmake", "framework", "solutions",
                 "scenes", ":(glob)labs/*/*.h", "tools/report", "tools/lib",
                 "tools/wbtools/report.py", "tools/wbtools/committed.py", "tools/wbplot",
                 "tools/wbview"]


class NotCommitted(Exception):
    """No git checkout, or no commit: one line."""


def _git_cmd(root):
    # safe.directory: the checkout is the one this tool belongs to, owned by whoever cloned it
    # (git refuses a repository of another owner, e.g. under sudo, unless told it is safe).
    return ["git", "-c", f"safe.directory={os.path.abspath(root)}", "-C", root]


def _git(root, *args, check=True):
    p = subprocess.run(_git_cmd(root) + list(args), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE)
    if check and p.returncode != 0:
        raise NotCommitted(f"git {' '.join(args)}: "
                           + (p.stderr.decode("utf-8", "replace").strip().splitlines() or ["failed"])[-1])
    return p


def head(root):
    """The commit HEAD names (40 hex digits); NotCommitted outside a git checkout."""
    try:
        return _git(root, "rev-parse", "--verify", "HEAD^{commit}").stdout.decode().strip()
    except OSError as e:  # no git at all
        raise NotCommitted(f"git: {e}")


def export_head(root, dest):
    """Writes the tree of HEAD into dest (new or empty), as `git archive` gives it (modes and
    symbolic links kept). Returns dest."""
    os.makedirs(dest, exist_ok=True)
    tar = os.path.join(dest, ".head.tar")
    with open(tar, "wb") as f:
        p = subprocess.run(_git_cmd(root) + ["archive", "--format=tar", "HEAD"], stdout=f,
                           stderr=subprocess.PIPE)
    if p.returncode != 0:
        os.remove(tar)
        raise NotCommitted("git archive HEAD: " + p.stderr.decode("utf-8", "replace").strip())
    with tarfile.open(tar) as t:
        for m in t.getmembers():  # git's own archive: relative paths, no devices
            if m.name.startswith("/") or ".." in m.name.split("/") or not (
                    m.isfile() or m.isdir() or m.issym()):
                raise NotCommitted(f"git archive HEAD: unexpected member {m.name!r}")
        t.extractall(dest)
    os.remove(tar)
    return dest


def uncommitted(root, pathspecs=()):
    """Paths (relative to root) whose work-tree state differs from HEAD: modified, added,
    deleted, renamed or untracked (ignored files are not), limited to pathspecs when given.
    Sorted; [] for a clean tree."""
    args = ["status", "--porcelain=v1", "-z", "--untracked-files=all", "--no-renames"]
    out = _git(root, *args, "--", *pathspecs).stdout.decode("utf-8", "replace")
    return sorted({entry[3:] for entry in out.split("\0") if len(entry) > 3})


def changed_between(root, commit, pathspecs):
    """The paths of pathspecs that differ between `commit` and HEAD (sorted), ["?"] when
    commit is not a commit of this repository; [] when none differ."""
    p = _git(root, "diff", "--name-only", commit, "HEAD", "--", *pathspecs, check=False)
    if p.returncode != 0:
        return ["?"]
    return sorted(line for line in p.stdout.decode("utf-8", "replace").splitlines() if line)


def source_stamp(root, pathspecs=REPORT_INPUTS):
    """What a product was made from: {"commit": HEAD, "uncommitted": [paths of pathspecs that
    differ from it]}, or {"commit": None, ...} outside a git checkout."""
    try:
        return {"commit": head(root), "uncommitted": uncommitted(root, pathspecs)}
    except NotCommitted:
        return {"commit": None, "uncommitted": []}


def current_for_head(root, stamp, pathspecs=REPORT_INPUTS):
    """"" when a product stamped with `stamp` (source_stamp) is what HEAD would make, else why
    not (one phrase)."""
    if not isinstance(stamp, dict) or not stamp.get("commit"):
        return "it records no commit (drawn before tools/report recorded one, or outside git)"
    if stamp.get("uncommitted"):
        files = stamp["uncommitted"]
        return (f"it was drawn with uncommitted edits ({', '.join(files[:3])}"
                + (f" and {len(files) - 3} more" if len(files) > 3 else "") + ")")
    changed = changed_between(root, stamp["commit"], pathspecs)
    if changed == ["?"]:
        return f"it was drawn from commit {stamp['commit'][:10]}, which this repository lacks"
    if changed:
        return (f"its inputs changed since commit {stamp['commit'][:10]}, which it was drawn from "
                f"({', '.join(changed[:3])}" + (f" and {len(changed) - 3} more" if len(changed) > 3
                                                else "") + ")")
    return ""
