"""Builds the student pack: the workbook without solutions or anything that reveals them."""
# What the pack holds (docs/grading.md, "The student pack"):
#   - the student side of the packed labs (and the labs they depend on: the
#     DEPS of their wb_lab(...) lines), their tests, scenes and glue;
#   - its own README (tools/pack.d/README.md, with the table of packed labs),
#     not the instructor one;
#   - the handouts with their figures copied in (handouts/figures/<lab>/),
#     drawn from the solutions by tools/report, and without the paragraphs
#     fenced by <!-- instructor --> ... <!-- /instructor -->;
#   - only the student docs and tools.
# --verify unpacks nothing new: it checks the staged pack itself: every link
# and image in its markdown resolves inside it, every path a handout or the
# README names exists in it, it builds with the README's command (timed), the
# README's commands run, and the skeletons score 0. --verify --no-build checks
# only what needs no build of the pack (each lab's closure then comes from the
# repository's own build) and leaves the rest to whoever builds the pack anyway
# (tools/fresh-machine's student, with the commands --lab-commands writes).
import argparse
import glob
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time

from . import answers, committed

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# Where the pack's files are read from: the tree of HEAD, exported (main() sets it; issue 44:
# never the work tree, whose uncommitted edits, an instructor's try of an exercise included,
# would ship). The tools' code itself runs from ROOT.
SRC = ROOT

# Shipped (filtered per lab where they hold per-lab folders or files).
SHIPPED = ["CMakeLists.txt", "CMakePresets.json", ".clang-format", ".gitignore", "cmake",
           "framework", "labs", "tests", "scenes", "handouts", "docs", "tools"]
# Never shipped: answers (solutions, known-wrong and known-right variants of
# them), instructor material, CI, build trees.
NEVER = {"solutions", "mutants", "hostile", "badinput", "bench", "gradescope", "pack.d", ".ci",
         ".git", "__pycache__", "fuzz"}
STUDENT_TOOLS = {"setup", "lib", "plot", "view", "grade", "grader", "diagnosis", "wbplot",
                 "wbview"}  # the rest stays home
STUDENT_DOCS = {"run-contract.md", "scenes.md", "sweep.md", "view.md", "live.md"}
INSTRUCTOR_BLOCK = re.compile(r"<!--\s*instructor\s*-->.*?<!--\s*/instructor\s*-->\n?", re.S)
CLAIM_MARKER = re.compile(r" ?<!--\s*(?:not-a-)?claim:.*?-->", re.S)  # claim markers
# The delimiters of the points lists (tools/pattern points): the lists ship, not the markers.
POINTS_MARKER = re.compile(r"^<!-- (?:points [A-Z][0-9]+:[^\n]*|/points) -->\n", re.M)
REPORT_FIGURE = re.compile(r"\.\./build/report/([A-Za-z0-9_-]+)/([^)\s`'\"]+)")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
PATH_REF = re.compile(r"`((?:tools|build/bin|scenes|labs|docs|handouts|tests|framework)/"
                      r"[A-Za-z0-9_./<>-]*)")


def shown(path):
    """A path as printed: relative to the repository when inside it."""
    rel = os.path.relpath(path, ROOT)
    return path if rel.startswith("..") else rel


class PackError(Exception):
    """Bad input or a pack that cannot be made: one line, exit 2."""


def known_labs():
    """{lab: [deps]} from the wb_lab(...) lines of CMakeLists.txt, in teaching order."""
    with open(os.path.join(SRC, "CMakeLists.txt"), encoding="utf-8") as f:
        text = f.read()
    labs = {}
    for m in re.finditer(r"^\s*wb_lab\(\s*([A-Za-z0-9_-]+)([^)]*)\)", text, re.M):
        rest = m.group(2).split()
        deps = rest[rest.index("DEPS") + 1:] if "DEPS" in rest else []
        # DEPS ends at the next keyword (TESTS_USE_GLUE, ...): lab names are lower case.
        labs[m.group(1)] = [d for d in deps[:next((i for i, d in enumerate(deps)
                                                   if d.isupper()), len(deps))]]
    return {lab: deps for lab, deps in labs.items() if os.path.isdir(os.path.join(SRC, "labs", lab))}


def with_deps(wanted, labs):
    out, todo = set(), list(wanted)
    while todo:
        lab = todo.pop()
        if lab not in out:
            out.add(lab)
            todo += labs.get(lab, [])
    return out


def lab_of(rel, labs_all):
    """The lab a path belongs to (labs/L, tests/L, scenes/L, framework/drivers/L,
    handouts/L.md, tools/wbplot/labs/L.py), or None."""
    parts = rel.split(os.sep)
    if len(parts) >= 2 and parts[0] in ("labs", "tests", "scenes") and parts[1] in labs_all:
        return parts[1]
    if len(parts) >= 3 and parts[:2] == ["framework", "drivers"] and parts[2] in labs_all:
        return parts[2]
    if len(parts) == 2 and parts[0] == "handouts" and parts[1].endswith(".md"):
        return parts[1][:-3] if parts[1][:-3] in labs_all else None
    if len(parts) == 4 and parts[:3] == ["tools", "wbplot", "labs"] and parts[3].endswith(".py"):
        return parts[3][:-3] if parts[3][:-3] in labs_all else None
    return None


def shipped(rel, labs, labs_all):
    parts = rel.split(os.sep)
    if parts[:2] == ["tests", "mutants"]:  # the grader's hints' data, never the mutants
        return len(parts) == 2 or parts[2] in labs and parts[3:] in ([], ["signatures.json"])
    # build/, build-asan/ ... are build trees; a file named build.py is not
    if any(p in NEVER for p in parts) or any(p.startswith("build") for p in parts[:-1]):
        return False
    if rel.endswith((".pyc", "~", ".orig", ".rej")):
        return False
    if parts[0] == "tools" and len(parts) >= 2 and parts[1] not in STUDENT_TOOLS:
        return False
    if parts[0] == "tools" and "tests" in parts[1:-1]:  # the tools' own unit tests stay home
        return False
    if parts[0] == "docs" and (len(parts) != 2 or parts[1] not in STUDENT_DOCS):
        return False
    if parts[0] == "tests" and len(parts) >= 2 and parts[1] != "common" and parts[1] not in labs:
        return False
    lab = lab_of(rel, labs_all)
    return lab is None or lab in labs


def lab_rows():
    """{lab: (topic, tasks)} from the instructor README's lab table."""
    rows = {}
    with open(os.path.join(SRC, "README.md"), encoding="utf-8") as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) >= 3 and re.fullmatch(r"`[A-Za-z0-9_-]+`", cells[0]):
                rows[cells[0].strip("`")] = (cells[1], cells[2])
    return rows


def first_scene(lab):
    d = os.path.join(SRC, "scenes", lab)
    names = sorted(f for f in os.listdir(d) if f.endswith(".json")) if os.path.isdir(d) else []
    if not names:
        raise PackError(f"scenes/{lab}/ has no scene: the pack README needs one")
    return f"scenes/{lab}/{names[0]}"


def first_task(lab):
    """The first TODO(<task>) tag of the lab's files."""
    d = os.path.join(SRC, "labs", lab)
    for name in sorted(os.listdir(d)):
        if name.endswith(".h"):
            with open(os.path.join(d, name), encoding="utf-8") as f:
                m = re.search(r"TODO\(([A-Za-z0-9.]+)\)", f.read())
            if m:
                return m.group(1)
    raise PackError(f"labs/{lab}/: no TODO(<task>) tag in a header")


def make_readme(labs, order, featured=None):
    """The pack's README; its example commands are those of `featured` (a lab asked for
    with --lab), else of the first packed lab."""
    rows = lab_rows()
    table = ["| lab | topic | tasks | handout |", "|---|---|---|---|"]
    for lab in order:
        if lab in labs:
            topic, tasks = rows.get(lab, ("", ""))
            table.append(f"| `{lab}` | {topic} | {tasks} | [handouts/{lab}.md](handouts/{lab}.md) |")
    first = featured or next(lab for lab in order if lab in labs)
    with open(os.path.join(SRC, "tools", "pack.d", "README.md"), encoding="utf-8") as f:
        text = f.read()
    return (text.replace("{labs_table}", "\n".join(table))
            .replace("{plot_commands}", plot_commands(first))
            .replace("{first_lab}", first).replace("{first_scene}", first_scene(first))
            .replace("{first_task}", first_task(first)))


# Every lab's run plays in the viewer (tools/view, docs/view.md).
VIEW_COMMAND = ("tools/view out/run.csv --scene {scene}",
                "watch it move: out/run-view.html, open it in a browser")


def plot_commands(lab):
    """The README's plot lines for `lab`'s run of its first scene (out/run.csv, run-stats.csv,
    run-summary.json): tools/wbplot/labs/<lab>.py's PACK_PLOTS when it has them, else the
    particle figures (wbplot.labs.GENERIC_PLOTS; tools/pattern stubfigs draws the same)."""
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    import importlib
    plots = importlib.import_module("wbplot.labs").GENERIC_PLOTS
    plugin = os.path.join(ROOT, "tools", "wbplot", "labs", f"{lab}.py")  # imported from ROOT
    if os.path.exists(plugin):
        plots = getattr(importlib.import_module(f"wbplot.labs.{lab}"), "PACK_PLOTS", plots)
    plots = list(plots) + [VIEW_COMMAND]
    lines = [cmd.replace("{scene}", first_scene(lab)) for cmd, _ in plots]
    width = max(len(c) for c in lines) + 2
    return "\n".join(f"{c}{' ' * (width - len(c))}# {why}" for c, (_, why) in zip(lines, plots))


def pack_handout(text, report_dir):
    """The handout as shipped: instructor blocks dropped, report figures copied
    to handouts/figures/<lab>/. Returns (text, [(source, dest relative to handouts/)])."""
    text = POINTS_MARKER.sub("", CLAIM_MARKER.sub("", INSTRUCTOR_BLOCK.sub("", text)))
    figures = []

    def swap(m):
        rel = os.path.join("figures", m.group(1), m.group(2))
        figures.append((os.path.join(report_dir, m.group(1), m.group(2)), rel))
        return rel
    return REPORT_FIGURE.sub(swap, text), figures


def drop_other_labs(text, labs, labs_all, stand_in=None):
    """A shared doc as a pack of `labs` ships it: without the sections about a lab it does
    not hold (a heading "## rigid", "## The rigid lab", "## `exact` (rigid)" ...), whose
    executables, scenes and glue the pack lacks, nor the row about one of a table of labs
    (first column "lab"); an example command for such a lab (`--lab euler`) is given for the lab
    `stand_in` (a packed one) instead, so that it runs in the pack."""
    out, skip_level, table = [], None, None
    gone = sorted(set(labs_all) - set(labs))
    for line in text.split("\n"):
        m = re.match(r"^(#{2,6})\s+(.*)$", line)
        if m:
            level = len(m.group(1))
            if skip_level is not None and level <= skip_level:
                skip_level = None
            words = re.sub(r"[`*]", "", m.group(2)).lower().split()
            named = [w for w in words if w in labs_all]
            if skip_level is None and named and all(w not in labs for w in named) and (
                    len(words) <= 3):
                skip_level = level
        if skip_level is not None:
            continue
        row = re.match(r"^\|\s*`?([A-Za-z0-9_-]+)`?\s*\|", line)
        if not line.startswith("|"):
            table = None
        elif table is None:
            table = row.group(1).lower() if row else ""  # a table's header: its first cell
        elif table == "lab" and row and row.group(1) in gone:
            continue
        for lab in gone:
            if stand_in and re.search(rf"--lab {lab}\b", line):
                line = re.sub(rf"\b{lab}\b", stand_in, line)
        out.append(line)
    return "\n".join(out)


def copy_tree(dest, labs, labs_all, order, report_dir, featured=None):
    figures = []
    for top in SHIPPED:
        src = os.path.join(SRC, top)
        if not os.path.exists(src):
            continue
        if os.path.isfile(src):
            shutil.copy2(src, os.path.join(dest, top))
            continue
        for dirpath, dirnames, filenames in os.walk(src):
            rel_dir = os.path.relpath(dirpath, SRC)
            dirnames[:] = sorted(d for d in dirnames
                                 if shipped(os.path.join(rel_dir, d), labs, labs_all))
            for name in sorted(filenames):
                rel = os.path.join(rel_dir, name)
                if not shipped(rel, labs, labs_all):
                    continue
                os.makedirs(os.path.join(dest, rel_dir), exist_ok=True)
                if rel_dir == "handouts" and name.endswith(".md"):
                    with open(os.path.join(SRC, rel), encoding="utf-8") as f:
                        text, figs = pack_handout(f.read(), report_dir)
                    with open(os.path.join(dest, rel), "w", encoding="utf-8") as f:
                        f.write(text)
                    figures += figs
                elif rel_dir == "docs" and name.endswith(".md"):
                    with open(os.path.join(SRC, rel), encoding="utf-8") as f:
                        text = drop_other_labs(INSTRUCTOR_BLOCK.sub("", f.read()), labs, labs_all,
                                               featured or next(l for l in order if l in labs))
                    with open(os.path.join(dest, rel), "w", encoding="utf-8") as f:
                        f.write(text)
                else:
                    shutil.copy2(os.path.join(SRC, rel), os.path.join(dest, rel))
    with open(os.path.join(dest, "README.md"), "w", encoding="utf-8") as f:
        f.write(make_readme(labs, order, featured))
    return figures


def copy_recorded(dest, labs, report_dir):
    """The solution's recorded runs of the packed labs' default scenes, as data for the live
    pages (live/recorded/<lab>/<scene>.json, docs/live.md): from the report's runs, the
    handouts' figures' own. Returns how many were written."""
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    from wbview.live import recorded
    from wbview.data import InputError
    count = 0
    for lab in sorted(labs):
        for path in sorted(glob.glob(os.path.join(ROOT, "scenes", lab, "*.json"))):
            stem = os.path.basename(path)[:-5]
            try:
                block = recorded.from_report(report_dir, lab, stem)
            except InputError as e:
                raise PackError(f"a recorded run for the live pages: {e}") from None
            if block is not None:
                recorded.write(os.path.join(dest, "live", "recorded"), lab, stem, block)
                count += 1
    return count


def copy_figures(dest, figures):
    missing = sorted({src for src, _ in figures if not os.path.isfile(src)})
    if missing:
        return missing
    for src, rel in figures:
        out = os.path.join(dest, "handouts", rel)
        os.makedirs(os.path.dirname(out), exist_ok=True)
        shutil.copy2(src, out)
    return []


# ------------------------------------------------------------------ prebuilt

def prebuilt_inputs(stage):
    """The files the prebuilt parts are compiled from, as cmake/prebuilt.cmake
    lists them: everything under framework/ and every labs/<lab>/*.h."""
    files = []
    for dirpath, _, filenames in os.walk(os.path.join(stage, "framework")):
        files += [os.path.relpath(os.path.join(dirpath, n), stage) for n in filenames]
    labs_dir = os.path.join(stage, "labs")
    for lab in os.listdir(labs_dir):
        if os.path.isdir(os.path.join(labs_dir, lab)):
            files += [os.path.join("labs", lab, n) for n in os.listdir(os.path.join(labs_dir, lab))
                      if n.endswith(".h")]
    return sorted(f.replace(os.sep, "/") for f in files)


def cmake_string(text):
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("$", "\\$") + '"'


def sync_tree(src, dest, skip=()):
    """Makes dest hold exactly src's files (top-level names in skip left alone), rewriting only
    those whose bytes differ: an unchanged file keeps its time, so that a build of dest
    recompiles only what changed."""
    wanted = set()
    for dirpath, dirnames, filenames in os.walk(src):
        rel_dir = os.path.relpath(dirpath, src)
        if rel_dir == ".":
            dirnames[:] = [d for d in dirnames if d not in skip]
        for name in filenames:
            rel = os.path.normpath(os.path.join(rel_dir, name))
            wanted.add(rel)
            a, b = os.path.join(src, rel), os.path.join(dest, rel)
            if os.path.islink(a):
                if not (os.path.islink(b) and os.readlink(b) == os.readlink(a)):
                    if os.path.lexists(b):
                        os.remove(b)
                    os.makedirs(os.path.dirname(b), exist_ok=True)
                    os.symlink(os.readlink(a), b)
                continue
            try:
                same = not os.path.islink(b) and os.path.getsize(a) == os.path.getsize(b)
                if same:
                    with open(a, "rb") as fa, open(b, "rb") as fb:
                        same = fa.read() == fb.read()
            except OSError:
                same = False
            if not same:
                os.makedirs(os.path.dirname(b), exist_ok=True)
                if os.path.lexists(b):
                    os.remove(b)
                shutil.copyfile(a, b)
            if os.stat(a).st_mode & 0o777 != os.stat(b).st_mode & 0o777:
                os.chmod(b, os.stat(a).st_mode & 0o777)
    for dirpath, dirnames, filenames in os.walk(dest, topdown=False):
        rel_dir = os.path.relpath(dirpath, dest)
        if rel_dir.split(os.sep)[0] in skip:
            continue
        for name in filenames:
            rel = os.path.normpath(os.path.join(rel_dir, name))
            if rel not in wanted:
                os.remove(os.path.join(dest, rel))
        if rel_dir != "." and not os.listdir(dirpath):
            os.rmdir(dirpath)


def build_prebuilt(stage, cache):
    """Compiles the staged pack's framework, glue and drivers' main.cpp with the pack's own
    preset, into stage/prebuilt/ with prebuilt/manifest.cmake (cmake/prebuilt.cmake says when
    a build uses them). The build is kept in `cache` (<build-dir>/pack/): a copy of the staged
    sources in cache/src (only changed files rewritten) and its build in cache/build, so that
    a second pack recompiles only what changed since the last."""
    src, build = os.path.join(cache, "src"), os.path.join(cache, "build")
    os.makedirs(src, exist_ok=True)
    sync_tree(stage, src, skip=("build", "prebuilt"))
    configure = ["cmake", "--preset", "default", "-B", build, "-DWB_TESTS=OFF",
                 "-DWB_PREBUILT=OFF", "-DWB_PREBUILT_EXPORT=ON"]
    t0 = time.monotonic()
    for cmd in [configure, None]:
        if cmd is None:
            with open(os.path.join(build, "wb-prebuilt.txt"), encoding="utf-8") as f:
                lines = [line.rstrip("\n").split(" ", 2) for line in f if line.strip()]
            key = next(" ".join(parts[1:]) for parts in lines if parts[0] == "key")
            parts = [(kind, target, path) for kind, target, path in
                     (p for p in lines if p[0] in ("lib", "obj"))]
            cmd = ["cmake", "--build", build, "--target"] + [t for _, t, _ in parts]
        p = subprocess.run(cmd, cwd=src, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        if p.returncode != 0:
            tail = p.stdout.decode("utf-8", "replace").strip().splitlines()[-20:]
            raise PackError(f"the prebuilt framework does not build: {' '.join(cmd)}\n"
                            + "\n".join(tail))
    compiled = sum(1 for line in p.stdout.decode("utf-8", "replace").splitlines()
                   if "Building CXX object" in line)
    # Compiled only (wbtools/answers.py): the provided code that does a packed task's job is
    # in prebuilt/ (just compiled from the real source), and its source in the pack is the
    # replacement that calls the student's own function.
    packed = [l for l in os.listdir(os.path.join(stage, "labs"))
              if os.path.isdir(os.path.join(stage, "labs", l))]
    for rel, lab in answers.COMPILED_ONLY.items():
        if lab in packed and os.path.isfile(os.path.join(stage, rel)):
            shutil.copyfile(os.path.join(SRC, "tools", "pack.d", "compiled-only", rel),
                            os.path.join(stage, rel))
            check_compiles(build, os.path.join(src, rel), os.path.join(stage, rel))
    check_no_answers(stage, packed)
    out = os.path.join(stage, "prebuilt")
    os.makedirs(out)
    rows = []
    for kind, target, path in parts:
        name = f"lib{target}.a" if kind == "lib" else f"{target}.o"
        shutil.copyfile(path, os.path.join(out, name))
        rows.append(f"  {kind} {target} {name}")
    sources = []
    for rel in prebuilt_inputs(stage):
        with open(os.path.join(stage, rel), "rb") as f:
            sources.append(f"  {rel} {hashlib.sha256(f.read()).hexdigest()}")
    with open(os.path.join(out, "manifest.cmake"), "w", encoding="utf-8") as f:
        f.write("# Written by tools/pack: the framework, glue and drivers' main.cpp compiled when\n"
                "# the pack was made, the toolchain that compiled them and the files they were\n"
                "# compiled from. cmake/prebuilt.cmake uses them only if all of it still holds.\n"
                f"set(WB_PREBUILT_KEY {cmake_string(key)})\n"
                "set(WB_PREBUILT_PARTS\n" + "\n".join(rows) + ")\n"
                "set(WB_PREBUILT_SOURCES\n" + "\n".join(sources) + ")\n")
    print(f"tools/pack:   the framework's {len(parts)} prebuilt parts ready in "
          f"{time.monotonic() - t0:.1f} s ({compiled} file(s) compiled, the rest up to date in "
          f"{shown(build)})", flush=True)


GRADER_PREBUILT = r"""
import json, os, shutil, subprocess, sys
stage, build = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(stage, "tools"))
from grader.build import Grader, PREBUILT_GRADER, prebuilt_inputs
from grader.project import known_labs, pristine_files
from grader.worker import worker_files
labs = known_labs(stage)
pristine = pristine_files(stage)
pristine.update(worker_files(stage, labs))
g = Grader(stage, build, verbose=False)
try:
    g.test_lists(labs, pristine)  # builds what its cached list does not vouch for
    # A list still current from an earlier pack names binaries of these very files (the key is
    # every pristine file's digest); one missing is built again.
    missing = [lab for lab in labs if not all(os.path.isfile(p) for p in (g.binary(lab), g.probes(lab)) if p)]
    if missing:
        g.sync(pristine)
        g.configure(labs)
        for lab in missing:
            ok, text = g.build_lab(lab, pristine=True)
            if not ok:
                sys.exit(f"the pristine skeleton of lab {lab} does not build:\n{text}")
    out = os.path.join(stage, PREBUILT_GRADER)
    os.makedirs(out)
    names = {}
    for lab in labs:
        names[lab] = []
        for path in (g.binary(lab), g.probes(lab)):
            if path and os.path.isfile(path):
                name = os.path.basename(path)
                shutil.copyfile(path, os.path.join(out, name))
                subprocess.run(["strip", "--strip-unneeded", os.path.join(out, name)], check=True)
                os.chmod(os.path.join(out, name), 0o755)
                names[lab].append(name)
    with open(os.path.join(g.build, "wb-toolchain.txt"), encoding="utf-8") as f:
        key = f.read().strip()
    with open(os.path.join(out, "manifest.json"), "w", encoding="utf-8") as f:
        json.dump({"written_by": "tools/pack: the pristine test and probe binaries of each lab "
                   "(tools/grader/build.py uses them only for this toolchain and these files)",
                   "toolchain": key, "inputs": prebuilt_inputs(pristine), "labs": names},
                  f, indent=1, sort_keys=True)
        f.write("\n")
finally:
    g.close()
"""


def build_prebuilt_grader(stage, cache):
    """Compiles the staged pack's pristine test and probe binaries of every lab with the
    grader's own machinery (the stubs of the worker linked in: no student code), into
    stage/prebuilt/grader/ with a manifest: a student's first `tools/grade` then compiles only
    the worker and the student's files (tools/grader/build.py, "prebuilt parts"). The grader's
    scratch build is kept in `cache` (<build-dir>/pack/grader): it rewrites only the files that
    changed, so that a second pack recompiles only what they touch."""
    t0 = time.monotonic()
    p = subprocess.run([sys.executable, "-c", GRADER_PREBUILT, stage, cache],
                       stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
    if p.returncode != 0:
        tail = p.stdout.decode("utf-8", "replace").strip().splitlines()[-20:]
        raise PackError("the prebuilt grader binaries do not build:\n" + "\n".join(tail))
    print(f"tools/pack:   the grader's tests and probes of every packed lab, ready in "
          f"{time.monotonic() - t0:.1f} s ({shown(cache)}: only what changed is compiled)",
          flush=True)


def check_compiles(build, built, path):
    """PackError unless `path` (a replacement of a compiled-only file) compiles with the command
    the prebuilt build compiled the real file (`built`, its copy there) with: a build that
    cannot use prebuilt/ compiles it, and no other check would."""
    import shlex
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as f:
        entries = json.load(f)
    entry = next((e for e in entries if os.path.realpath(e["file"]) == os.path.realpath(built)),
                 None)
    if entry is None:
        raise PackError(f"{built}: the prebuilt build does not compile it")
    args = entry.get("arguments") or shlex.split(entry["command"])
    kept, skip = [], False
    for a in args:  # no dependency file: -MD, -MMD, and -MT/-MF/-MQ with their argument
        if skip:
            skip = False
        elif a in ("-MT", "-MF", "-MQ"):
            skip = True
        elif a not in ("-MD", "-MMD"):
            kept.append(a)
    args = [path if a in (entry["file"], built) else a for a in kept]
    if "-o" in args:
        args[args.index("-o") + 1] = os.devnull
    p = subprocess.run(args, cwd=entry["directory"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT)
    if p.returncode != 0:
        raise PackError(f"the replacement of a compiled-only file does not compile: {path}\n" +
                        p.stdout.decode("utf-8", "replace")[-2000:])


def check_no_answers(stage, labs):
    """PackError when a source the pack ships computes what a packed task's solution computes
    (wbtools/answers.py): provided code and the skeletons."""
    shipped = {}
    for top in ("framework", "labs"):
        for dirpath, _, names in os.walk(os.path.join(stage, top)):
            for n in names:
                path = os.path.join(dirpath, n)
                with open(path, encoding="utf-8", errors="replace") as f:
                    shipped[os.path.relpath(path, stage).replace(os.sep, "/")] = f.read()
    bad = [(rel, sol, share) for rel, sol, share, why in answers.overlaps(shipped, labs, SRC)
           if not why]
    if bad:
        raise PackError("the pack would ship a task's answer: " + "; ".join(
            f"{rel} holds {100 * share:.0f} % of solutions/{sol}" for rel, sol, share in bad) +
            " (ship it compiled only, or make it call the student's function: "
            "tools/wbtools/answers.py)")


# ------------------------------------------------------------------ verify

def markdown_files(dest):
    for dirpath, _, filenames in os.walk(dest):
        if os.path.relpath(dirpath, dest).split(os.sep)[0] == "build":
            continue
        for name in filenames:
            if name.endswith(".md"):
                yield os.path.join(dirpath, name)


def check_references(dest, labs):
    """Every link, image and named path of the pack's markdown resolves inside it."""
    problems = []
    built = {f"build/bin/{lab}" for lab in labs} | {f"build/bin/{lab}-tests" for lab in labs}
    for path in sorted(markdown_files(dest)):
        rel_md = os.path.relpath(path, dest)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for m in LINK.finditer(text):
            target = m.group(1).split("#")[0]
            if not target or re.match(r"^[a-z]+:", target):
                continue  # an anchor in the same file, or a web address
            if not os.path.exists(os.path.normpath(os.path.join(os.path.dirname(path), target))):
                problems.append(f"{rel_md}: link {m.group(1)} does not resolve in the pack")
        for m in PATH_REF.finditer(text):
            ref = m.group(1).rstrip(".,:;")
            if "<" in ref or ref.endswith("/"):
                if "<" not in ref and ref != "build/bin/" and not os.path.isdir(
                        os.path.join(dest, ref)):
                    problems.append(f"{rel_md}: names `{ref}`, which is not in the pack")
                continue
            if ref.startswith("build/bin/"):
                if ref not in built:
                    problems.append(f"{rel_md}: names `{ref}`, which the pack does not build")
            elif not os.path.exists(os.path.join(dest, ref)):
                problems.append(f"{rel_md}: names `{ref}`, which is not in the pack")
    return problems


def readme_commands(dest):
    """The command lines of the README's ```sh blocks (continuations joined)."""
    with open(os.path.join(dest, "README.md"), encoding="utf-8") as f:
        return commands_of(f.read())


def commands_of(text):
    """The command lines of a README text's ```sh blocks (continuations joined)."""
    cmds = []
    for block in re.findall(r"```sh\n(.*?)```", text, re.S):
        line = ""
        for raw in block.splitlines():
            line += raw.rstrip()
            if line.endswith("\\"):
                line = line[:-1] + " "
                continue
            if line.strip():
                cmds.append(line.strip())
            line = ""
    return cmds


def run_readme_commands(dest, cmds, env, what="README"):
    """Runs each command in the pack `dest`; a command fails when it is not found,
    dies of a signal, or (tools and lab executables) exits non-zero. Test runners
    may exit non-zero: the skeletons fail their tests."""
    problems = []
    for cmd in cmds:
        first = cmd.split()[0]
        tests = first.endswith("-tests") or first == "ctest"
        print(f"+ {cmd}", flush=True)
        p = subprocess.run(["bash", "-c", cmd], cwd=dest, stdin=subprocess.DEVNULL, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=900)
        if p.returncode in (126, 127) or p.returncode < 0 or (p.returncode != 0 and not tests):
            tail = p.stdout.decode("utf-8", "replace").strip().splitlines()[-3:]
            problems.append(f"{what} command `{cmd}` exited with status {p.returncode}: "
                            + " | ".join(tail))
    return problems


def check_prebuilt_fallback(dest):
    """A pack whose framework was edited must compile it from source: configures
    a copy with one framework file changed and reads what cmake decided."""
    problems = []
    with tempfile.TemporaryDirectory(prefix=".pack-fallback-", dir=os.path.dirname(dest)) as tmp:
        copy = os.path.join(tmp, "pack")
        shutil.copytree(dest, copy, ignore=shutil.ignore_patterns("build", "out"))
        with open(os.path.join(copy, "framework", "src", "run.cpp"), "a", encoding="utf-8") as f:
            f.write("// edited\n")
        cmd = ["cmake", "-S", copy, "-B", os.path.join(tmp, "build"), "-G", "Ninja",
               "-DCMAKE_BUILD_TYPE=Release"]
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        text = p.stdout.decode("utf-8", "replace")
        if p.returncode != 0 or "not used (framework/src/run.cpp changed)" not in text:
            said = [line.strip() for line in text.splitlines() if "prebuilt" in line]
            problems.append("a pack with framework/src/run.cpp edited does not fall back to "
                            "compiling the framework: " + (" | ".join(said) or text[-300:]))
    return problems


def verify(dest, labs, grade_dir, keep_build=False, build=True):
    """Checks the staged pack; returns a list of problems (empty: the pack is good).
    Every grading in it (the README's and the score check) shares the scratch build
    grade_dir, as a student's repeated tools/grade runs would with --build-dir.
    build=False (--no-build): only what needs no build of the pack, its references
    and the prebuilt fallback; the build, its prebuilt framework used, the README's
    commands and the skeletons' scores are left to whoever builds the pack."""
    env = dict(os.environ, WB_GRADE_BUILD_DIR=grade_dir)
    problems = check_references(dest, labs)
    problems += check_prebuilt_fallback(dest)
    if not build:
        return problems
    t0 = time.monotonic()
    for cmd in (["cmake", "--preset", "default"], ["cmake", "--build", "--preset", "default"]):
        print("+", " ".join(cmd), flush=True)
        p = subprocess.run(cmd, cwd=dest, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        text = p.stdout.decode("utf-8", "replace")
        if p.returncode != 0:
            tail = text.strip().splitlines()[-20:]
            return problems + [f"the pack does not build: {' '.join(cmd)}\n" + "\n".join(tail)]
        if cmd[1] == "--preset" and "prebuilt framework: used" not in text:
            said = [line for line in text.splitlines() if "prebuilt framework" in line]
            problems.append("the pack's build does not use its prebuilt framework: "
                            + (said[0].strip() if said else "cmake said nothing about it"))
    print(f"pack: the student build took {time.monotonic() - t0:.1f} s", flush=True)
    problems += run_readme_commands(dest, readme_commands(dest), env)
    cmd = [os.path.join(dest, "tools", "grade"), os.path.join(dest, "labs"), "--require-score", "0"]
    print("+", " ".join(cmd), flush=True)
    if subprocess.run(cmd, cwd=dest, stdout=subprocess.DEVNULL, env=env).returncode != 0:
        problems.append("the pack's skeletons do not score 0 (tools/grade labs --require-score 0)")
    if not keep_build:
        clean_pack(dest)
    return problems


def clean_pack(dest):
    for extra in ("build", "out"):
        shutil.rmtree(os.path.join(dest, extra), ignore_errors=True)


# ------------------------------------------------- each lab's pack, alone

def ninja_lines(build, *args):
    p = subprocess.run(["ninja", "-C", build, "-t"] + list(args), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT)
    if p.returncode != 0:
        raise PackError(f"ninja -C {build} -t {' '.join(args)}: "
                        + p.stdout.decode("utf-8", "replace").strip()[-300:])
    return p.stdout.decode("utf-8", "replace").splitlines()


def compiled_from(build, targets):
    """Every file the build reads to make `targets`: their inputs, all the way down
    (ninja -t inputs), and the headers each object was compiled with (ninja -t deps,
    recorded by the build that ran). Absolute paths."""
    inputs = [os.path.normpath(os.path.join(build, f.strip()))
              for f in ninja_lines(build, "inputs", *targets) if f.strip()]
    # The objects this build compiled (not imported ones, such as the prebuilt parts).
    objects = [r for r in (os.path.relpath(f, build) for f in inputs if f.endswith(".o"))
               if not r.startswith("..")]
    files = set(inputs)
    for line in ninja_lines(build, "deps", *objects) if objects else []:
        if line.startswith("    "):
            files.add(os.path.normpath(os.path.join(build, line.strip())))
    return files


def lab_closure(full, lab, cache):
    """The pack files lab's executable and tests are compiled from, relative to the
    all-labs pack `full` (its build, and the build that compiled its prebuilt parts, in
    cache/build from the copy of the pack's sources in cache/src)."""
    files = compiled_from(os.path.join(full, "build"), [lab, f"{lab}-tests"])
    prebuilt_src, prebuilt_build = os.path.join(cache, "src"), os.path.join(cache, "build")
    manifest = os.path.join(full, "prebuilt", "manifest.cmake")
    out = set()
    if os.path.isfile(manifest) and os.path.isdir(prebuilt_build):
        with open(manifest, encoding="utf-8") as f:
            # "  obj rigid_main rigid_main.o)": the last part's line ends the set(...)
            parts = re.findall(r"^\s+(?:lib|obj) (\S+) ([^\s)]+)\)?$", f.read(), re.M)
        used = [t for t, name in parts if os.path.join(full, "prebuilt", name) in files]
        for f in compiled_from(prebuilt_build, used) if used else ():
            rel = os.path.relpath(f, prebuilt_src)
            if not rel.startswith("..") and rel.split(os.sep)[0] not in ("build", "prebuilt"):
                out.add(rel)
    for f in files:
        rel = os.path.relpath(f, full)
        if rel.startswith("..") or rel.split(os.sep)[0] in ("build", "prebuilt"):
            continue  # system headers, generated files, the prebuilt objects themselves
        out.add(rel)
    return out


def check_repo_build(build, labs):
    """--verify --no-build --each-lab reads each lab's closure from the repository's own
    build (tools/report's): it must exist, and every lab's executable and tests are brought
    up to date in it first (ninja: nothing to do right after tools/report; a target never
    built has no recorded headers, an edited file changes them). PackError (one line) if the
    build is missing or cannot make them."""
    shown = os.path.relpath(build, ROOT)
    shown = build if shown.startswith("..") else shown
    if not os.path.isfile(os.path.join(build, "build.ninja")):
        raise PackError(f"--no-build --each-lab: the repository's build {shown}/ (--build-dir), "
                        "which each lab's closure is read from, is missing (no build.ninja): run "
                        "tools/report (or cmake --preset default && cmake --build --preset "
                        "default) first")
    targets = [t for lab in labs for t in (lab, f"{lab}-tests")]
    p = subprocess.run(["ninja", "-C", build] + targets, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT)
    text = p.stdout.decode("utf-8", "replace")
    if p.returncode != 0:
        said = next((line for line in text.splitlines() if "error" in line.lower()),
                    text.strip().splitlines()[-1] if text.strip() else "")
        raise PackError(f"--no-build --each-lab: the repository's build {shown}/ cannot make "
                        f"every lab's executable and tests, which each lab's closure is read "
                        f"from: ninja exited {p.returncode}: {said.strip()[:300]}")
    if "no work to do" not in text:
        print(f"tools/pack: the repository's build {shown}/ was not up to date for the labs' "
              "executables and tests: ninja brought it up to date", flush=True)


def repo_lab_closure(build, lab):
    """The repository files lab's executable and tests are compiled from, relative to the
    repository, read from its own build (tools/report's, the student side's targets <lab>
    and <lab>-tests: the pack's targets of the same names, the framework compiled from
    source instead of prebuilt)."""
    out = set()
    for f in compiled_from(build, [lab, f"{lab}-tests"]):
        rel = os.path.relpath(f, ROOT)
        if rel.startswith("..") or not os.path.relpath(f, build).startswith(".."):
            continue  # system headers, generated files in the build
        out.add(rel)
    return out


def each_lab_commands(labs_deps, order):
    """[(lab, commands)]: the commands of each lab's own pack README that neither the
    all-labs pack's README nor an earlier lab's has, in teaching order: what --each-lab
    runs in the all-labs pack (with --no-build, what --lab-commands hands over)."""
    ran = set(commands_of(make_readme(set(labs_deps), order)))
    out = []
    for lab in order:
        readme = make_readme(with_deps([lab], labs_deps), order, featured=lab)
        cmds = [c for c in commands_of(readme) if c not in ran]
        ran |= set(cmds)
        out.append((lab, cmds))
    return out


def verify_each_lab(full, tmp, cache, labs_deps, order, report_dir, grade_dir, closure=None):
    """Each lab's pack (the lab and the labs it depends on) alone: its links and named
    paths resolve in it, it configures on its own, it holds every file its executable
    and tests are compiled from (closure(lab), relative paths; by default read from the
    all-labs pack's build, which must still be there), and its README's commands run (in
    the all-labs pack, whose files are a superset of its own: one build for all).
    Returns the problems. closure given (--no-build: read from the repository's build):
    the pack is not built, and the commands are not run here (each_lab_commands)."""
    env = dict(os.environ, WB_GRADE_BUILD_DIR=grade_dir)
    run_cmds = closure is None
    closures = {}

    def closure_of(lab):
        if lab not in closures:
            closures[lab] = closure(lab) if closure else lab_closure(full, lab, cache)
        return closures[lab]
    problems, lab_cmds = [], dict(each_lab_commands(labs_deps, order))
    for lab in order:
        labs = with_deps([lab], labs_deps)
        home = os.path.join(tmp, f"lab-{lab}")
        stage = os.path.join(home, "sim-workbook")
        os.makedirs(stage)
        print(f"tools/pack: verify: the pack of lab {lab} alone "
              f"(labs {', '.join(l for l in order if l in labs)})", flush=True)
        mine = []
        missing = copy_figures(stage, copy_tree(stage, labs, set(labs_deps), order, report_dir,
                                                featured=lab))
        mine += [f"handout figure {os.path.relpath(m, ROOT)} is missing" for m in missing[:3]]
        mine += check_references(stage, labs)
        cmd = ["cmake", "-S", stage, "-B", os.path.join(home, "build"), "-G", "Ninja",
               "-DCMAKE_BUILD_TYPE=Release", "-DWB_TESTS=ON"]
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        if p.returncode != 0:
            tail = p.stdout.decode("utf-8", "replace").strip().splitlines()[-5:]
            mine.append("it does not configure on its own: " + " | ".join(tail))
        for l in sorted(labs):
            for rel in sorted(closure_of(l)):
                if not os.path.exists(os.path.join(stage, rel)):
                    mine.append(f"lab {l} is compiled from {rel}, which this pack lacks")
        if run_cmds:
            mine += run_readme_commands(full, lab_cmds[lab], env, what=f"lab {lab}'s README")
        problems += [f"lab {lab} alone: {m}" for m in mine]
        shutil.rmtree(home, ignore_errors=True)
    return problems


def write_lab_commands(path, labs_deps, order):
    """--lab-commands: each lab's README commands that the all-labs README lacks, as JSON,
    whole or not at all (tools/fresh-machine's student runs them after its own)."""
    data = {"about": "tools/pack --lab-commands: the commands of each lab's own pack README "
                     "that the all-labs pack's README lacks (nor an earlier lab's), in order; "
                     "tools/pack --verify --each-lab runs them in the all-labs pack",
            "labs": [{"lab": lab, "commands": cmds}
                     for lab, cmds in each_lab_commands(labs_deps, order)]}
    with open(path + ".part", "w", encoding="utf-8") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    os.replace(path + ".part", path)


def report_not_current(report_dir, labs, root=ROOT):
    """{lab: why} for the packed labs whose figures in report_dir are not what HEAD would
    draw (tools/report records the commit it drew from in <report>/<lab>/section.json)."""
    out = {}
    for lab in sorted(labs):
        path = os.path.join(report_dir, lab, "section.json")
        try:
            with open(path, encoding="utf-8") as f:
                section = json.load(f)
        except (OSError, ValueError):
            out[lab] = "it was never drawn"
            continue
        if not isinstance(section, dict):
            out[lab] = f"{shown(path)} is not a report section"
        elif section.get("failures"):
            out[lab] = f"its last drawing failed ({len(section['failures'])} failure(s))"
        else:
            why = committed.current_for_head(root, section.get("source"))
            if why:
                out[lab] = why
    return out


def run_report(labs, report_dir):
    """Draws the figures the handouts need with tools/report (solutions), from the work tree,
    which the caller made sure holds HEAD's report inputs."""
    build_dir = os.path.dirname(report_dir)
    cmd = [os.path.join(ROOT, "tools", "report"), "--no-setup", "--labs", ",".join(sorted(labs)),
           "--build-dir", build_dir]
    print("tools/pack: +", " ".join(shown(c) for c in cmd), flush=True)
    subprocess.run(cmd, cwd=ROOT)


def current_figures(labs, report_dir, root=ROOT):
    """Makes sure the packed labs' figures in report_dir are what HEAD draws: reused when
    tools/report drew them from HEAD's inputs, drawn again (tools/report) when the work tree's
    report inputs are HEAD's, a PackError (one line naming the edited files) otherwise."""
    stale = report_not_current(report_dir, labs, root)
    if not stale:
        print(f"tools/pack:   the report in {shown(report_dir)} is current for HEAD: its figures "
              "are reused", flush=True)
        return
    for lab, why in stale.items():
        print(f"tools/pack:   {lab}: the report's figures are not current for HEAD: {why}",
              flush=True)
    try:
        edited = committed.uncommitted(root, committed.REPORT_INPUTS)
    except committed.NotCommitted as e:
        raise PackError(f"the figures must be drawn from the committed tree, and {e}")
    if edited:
        raise PackError(
            "the report must be drawn again for HEAD, but the work tree has uncommitted edits "
            f"to what it draws from: {', '.join(edited[:6])}"
            + (f" and {len(edited) - 6} more" if len(edited) > 6 else "")
            + "; commit or stash them (the pack is made from what was committed)")
    print(f"tools/pack:   drawing them again: tools/report --labs {','.join(sorted(stale))} "
          "(builds the solutions and runs every scene: minutes)", flush=True)
    run_report(sorted(stale), report_dir)


def stage_committed(root, tmp, wanted, report_dir):
    """Stages the pack of the labs `wanted` (all when empty, with the labs they depend on) in
    tmp/sim-workbook from the tree of HEAD of the checkout `root` (exported to tmp/head, which
    SRC then names), whatever its work tree holds, and says which uncommitted files it left
    out. Returns (commit, stage, {lab: deps}, packed labs, [(figure, its path in handouts/)])."""
    global SRC
    try:
        commit = committed.head(root)
        SRC = committed.export_head(root, os.path.join(tmp, "head"))
        edited = committed.uncommitted(root)
    except committed.NotCommitted as e:
        raise PackError(f"the pack is made from the committed tree (HEAD), and {e}")
    print(f"tools/pack: [1/5] the committed tree, HEAD {commit[:10]}"
          + (f"; not packed, uncommitted: {', '.join(edited[:6])}"
             + (f" and {len(edited) - 6} more" if len(edited) > 6 else "") if edited else
             " (the work tree holds no uncommitted edit)"), flush=True)
    labs_deps = known_labs()
    order = list(labs_deps)
    for lab in wanted:
        if lab not in labs_deps:
            raise PackError(f"--lab: got '{lab}', expected one of: {', '.join(order)}")
    labs = with_deps(wanted or order, labs_deps)
    stage = os.path.join(tmp, "sim-workbook")
    os.makedirs(stage)
    featured = next((l for l in order if l in wanted), None)  # the README's examples
    figures = copy_tree(stage, labs, set(labs_deps), order, report_dir, featured)
    return commit, stage, labs_deps, labs, figures


def write_tar(stage, out, tmp):
    """The staged pack as out (.tar.gz), whole or not at all."""
    tmp_tar = os.path.join(tmp, "pack.tar.gz")
    with tarfile.open(tmp_tar, "w:gz") as t:
        t.add(stage, arcname="sim-workbook")
    try:
        shutil.move(tmp_tar, out + ".part")  # a copy when out is on another file system
        os.replace(out + ".part", out)
    finally:
        if os.path.exists(out + ".part"):
            os.remove(out + ".part")


def main():
    ap = argparse.ArgumentParser(
        prog="tools/pack", description=__doc__,
        epilog="The handouts' figures come from <build-dir>/report (tools/report); missing ones "
               "are drawn first. Exit status: 0 written, 1 --verify found a problem, 2 bad "
               "input. See docs/pack.md.")
    ap.add_argument("--out",
                    help="output: a folder (new or empty), or a file ending in .tar.gz (with "
                         "--gradescope: the zip)")
    ap.add_argument("--gradescope", metavar="LAB",
                    help="build LAB's Gradescope autograder zip instead "
                         "(tools/gradescope/make_zip.py; default --out LAB-autograder.zip)")
    ap.add_argument("--lab", action="append", default=[],
                    help="a lab to ship (repeatable; default: all labs); the labs it depends on "
                         "come with it")
    ap.add_argument("--build-dir", default="build",
                    help="the instructor build whose report/ holds the figures (default "
                         "build); with --verify --no-build --each-lab, also the build each "
                         "lab's closure is read from")
    ap.add_argument("--verify", action="store_true",
                    help="check the pack: links and named paths resolve, it builds, the "
                         "README's commands run, the skeletons score 0 (with --no-build: the "
                         "first only)")
    ap.add_argument("--draft", metavar="FILE.tar.gz",
                    help="with --verify: also write the pack to FILE.tar.gz before verifying it "
                         "(tools/fresh-machine starts the student's machine on it meanwhile); "
                         "--out is still written only if the verification passes")
    ap.add_argument("--each-lab", action="store_true",
                    help="with --verify of all labs: also check each lab's pack alone (links, "
                         "named paths, configures on its own, holds every file its build "
                         "compiles, its README's commands run) against the all-labs build "
                         "(with --no-build: against the repository's build, the commands not "
                         "run)")
    ap.add_argument("--no-build", action="store_true",
                    help="with --verify: check only what needs no build of the pack (links, "
                         "named paths, the prebuilt fallback; with --each-lab each lab's pack "
                         "alone: links, named paths, configures on its own, holds every file "
                         "its executable and tests are compiled from, read from the "
                         "repository's own build in --build-dir, which must exist; its labs' "
                         "targets are brought up to date first). Whoever builds the pack must then check the rest: it builds "
                         "with its prebuilt framework, the README's commands (and each lab's: "
                         "--lab-commands) run, the skeletons score 0. tools/fresh-machine "
                         "--verify does, on its student's machine")
    ap.add_argument("--lab-commands", metavar="FILE.json",
                    help="with --each-lab: write to FILE.json (before verifying) the commands "
                         "of each lab's own README that the all-labs README lacks, the ones "
                         "--each-lab runs in the all-labs pack, for a caller that runs them "
                         "itself (with --no-build); not part of the pack")
    try:
        args = ap.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    if args.gradescope:
        sys.path.insert(0, os.path.join(ROOT, "tools", "gradescope"))
        import make_zip
        return make_zip.main([args.gradescope] + (["--out", args.out] if args.out else []))
    if not args.out:
        raise PackError("--out: missing, expected a folder or a file ending in .tar.gz")
    if args.draft and not args.draft.endswith(".tar.gz"):
        raise PackError(f"--draft: got '{args.draft}', expected a file ending in .tar.gz")
    if args.draft and not args.verify:
        raise PackError("--draft: goes with --verify (the draft is what is being verified)")
    if args.each_lab and (not args.verify or args.lab):
        raise PackError("--each-lab: goes with --verify of the pack of all labs (no --lab)")
    if args.no_build and not args.verify:
        raise PackError("--no-build: goes with --verify (it leaves the pack's build out of the "
                        "verification)")
    if args.lab_commands and not args.each_lab:
        raise PackError("--lab-commands: goes with --each-lab (the commands are each lab's "
                        "pack's)")
    if args.lab_commands and not os.path.isdir(os.path.dirname(os.path.abspath(args.lab_commands))):
        raise PackError(f"--lab-commands: folder "
                        f"'{os.path.dirname(os.path.abspath(args.lab_commands))}' does not exist")
    out = os.path.abspath(args.out)
    is_tar = out.endswith(".tar.gz")
    if not is_tar and os.path.exists(out) and (not os.path.isdir(out) or os.listdir(out)):
        raise PackError(f"--out: '{args.out}' exists and is not an empty folder, expected a new "
                        "or empty folder (or a .tar.gz file)")
    parent = os.path.dirname(out)
    if not os.path.isdir(parent):
        raise PackError(f"--out: folder '{parent}' does not exist")
    build_dir = os.path.abspath(os.path.join(ROOT, args.build_dir))
    report_dir = os.path.join(build_dir, "report")
    cache = os.path.join(build_dir, "pack")  # the prebuilt parts' builds, kept between packs
    t_start = time.monotonic()

    with tempfile.TemporaryDirectory(dir=parent, prefix=".pack-") as tmp:
        # 1. What was committed: the pack is made from HEAD's tree, whatever the work tree holds.
        commit, stage, labs_deps, labs, figures = stage_committed(ROOT, tmp, args.lab, report_dir)
        order = list(labs_deps)
        # 2. The handouts' figures: the report's, when it is current for HEAD.
        print(f"tools/pack: [2/5] the handouts' figures ({len(figures)}) from "
              f"{shown(report_dir)}", flush=True)
        current_figures(labs, report_dir)
        missing = copy_figures(stage, figures)
        if missing:
            print(f"tools/pack:   {len(missing)} handout figure(s) not drawn yet: running "
                  "tools/report", flush=True)
            run_report(labs, report_dir)
            missing = copy_figures(stage, figures)
        if missing:
            raise PackError(f"{len(missing)} handout figure(s) missing after tools/report, e.g. "
                            f"{shown(missing[0])}: see the report's failures")
        recorded_runs = copy_recorded(stage, labs, report_dir)
        print(f"tools/pack: {recorded_runs} recorded runs of the solution for the live pages "
              "(live/recorded/)", flush=True)
        repo_build = os.path.dirname(report_dir)
        if args.no_build and args.each_lab:  # before the prebuilt parts' minute of compiling
            check_repo_build(repo_build, order)
        # 3-4. The parts a student never edits, compiled once here (kept in <build-dir>/pack).
        print(f"tools/pack: [3/5] the prebuilt framework (cmake/prebuilt.cmake), built in "
              f"{shown(os.path.join(cache, 'build'))}", flush=True)
        build_prebuilt(stage, cache)
        print(f"tools/pack: [4/5] the grader's prebuilt tests and probes, built in "
              f"{shown(os.path.join(cache, 'grader'))}", flush=True)
        build_prebuilt_grader(stage, os.path.join(cache, "grader"))
        print("tools/pack: [5/5] " + ("verifying and writing" if args.verify else "writing")
              + f" {args.out}", flush=True)
        if args.lab_commands:
            write_lab_commands(os.path.abspath(args.lab_commands), labs_deps, order)
        if args.draft:
            write_tar(stage, os.path.abspath(args.draft), tmp)
        if args.verify:
            grade_dir = os.path.join(tmp, "grade")
            problems = verify(stage, labs, grade_dir, keep_build=args.each_lab,
                              build=not args.no_build)
            if args.each_lab and not any(p.startswith("the pack does not build") for p in problems):
                closure = (lambda lab: repo_lab_closure(repo_build, lab)) if args.no_build else None
                problems += verify_each_lab(stage, tmp, cache, labs_deps, order, report_dir,
                                            grade_dir, closure)
            clean_pack(stage)
            if problems:
                for p in problems:
                    print(f"tools/pack: verify: {p}", file=sys.stderr)
                print(f"tools/pack: verify: {len(problems)} problem(s)", file=sys.stderr)
                return 1
            if args.no_build:
                print("tools/pack: verify: links, named paths and the prebuilt fallback"
                      + (", and each lab's pack alone (configures, holds its closure)"
                         if args.each_lab else "")
                      + " all good; not checked here (--no-build): the build, the README's "
                        "commands" + (" (and each lab's, in " + args.lab_commands + ")"
                                      if args.lab_commands else "")
                      + " and the skeletons' scores", flush=True)
            else:
                print("tools/pack: verify: links, named paths, build, README commands and "
                      "skeleton scores all good", flush=True)
        if is_tar:
            write_tar(stage, out, tmp)
        else:
            if os.path.exists(out):
                os.rmdir(out)
            os.replace(stage, out)
    print(f"tools/pack: wrote {args.out} (labs: {', '.join(l for l in order if l in labs)}; "
          f"HEAD {commit[:10]}) in {time.monotonic() - t_start:.0f} s")
    return 0


def run():
    """The entry tools/pack calls: main() with the command line, its exit status."""
    try:
        sys.exit(main())
    except PackError as e:
        print(f"tools/pack: error: {e}", file=sys.stderr)
        sys.exit(2)
