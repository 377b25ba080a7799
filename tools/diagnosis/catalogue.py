"""The diagnosis catalogue of tools/mutants: each lab's probes (tests/<lab>/probes/, built as
<lab>-probes-direct in the mutants' scratch build) run on the solution, the skeleton, every
mutant and every alternative, and written to tests/mutants/<lab>/signatures.json (numbers
only: the pack ships it, never the mutants), with the leave-one-out figures of the rule that
names a mistake's part (hints.py; docs/grading.md, "Diagnosis").

Trust: runs our own code (the solution, the skeleton, the mutants), never a submission."""
import collections
import hashlib
import json
import os
import re
import subprocess
import time

from . import hints as wh

PROBE_TIMEOUT = 60.0  # s, one variant's probes run directly (the slowest take < 1 s)


# ------------------------------------------------------------------- tasks

# An output the header says to add to: "f  2 x n forces (N); add, do not overwrite",
# "b.f, b.tau  ADDED to (other forces may already be there)".
_ADDS = re.compile(r"^//\s+(?:Outputs?:\s*)?([A-Za-z_][\w.]*(?:,\s*[A-Za-z_][\w.]*)*)\s.*?"
                   r"\b(?:add(?:,|\s+to\b)|added\s+to\b)", re.I | re.M)


def header_adds(text):
    """The outputs a header's contract says to add to, never to overwrite (the only ones for
    which the diagnosis may say "add to ..., do not overwrite it")."""
    return sorted({n.strip() for m in _ADDS.finditer(text) for n in m.group(1).split(",")})


def lab_tasks(repo, lab):
    """{task: {"title", "handout", "files", "adds"}} from the 'TODO(<task>) <title>: ...
    Handout: ...' line that opens each of the lab's headers, and the outputs each header says
    to add to (header_adds)."""
    tasks = {}
    d = os.path.join(repo, "labs", lab)
    for name in sorted(os.listdir(d)):
        if not name.endswith(".h"):
            continue
        with open(os.path.join(d, name), encoding="utf-8") as f:
            text = f.read()
        head = re.sub(r"\n//\s*", " ", text[:600])  # the opening comment on one line
        m = re.search(r"TODO\((\w+)\)\s*([^:.]*)", head)
        if not m:
            continue
        t = tasks.setdefault(m.group(1), {"title": m.group(2).strip(), "handout": "", "files": [],
                                          "adds": []})
        t["adds"] = sorted(set(t["adds"]) | set(header_adds(text)))
        h = re.search(r"Handout:\s*(\S+?)\.?\s", head.replace("\n//", " "))
        if h and not t["handout"]:
            t["handout"] = h.group(1)
        cpp = name[:-2] + ".cpp"
        if os.path.isfile(os.path.join(d, cpp)):
            t["files"].append(cpp)
            with open(os.path.join(d, cpp), "rb") as f:  # the skeleton, to tell "not started"
                t.setdefault("skeleton_sha256", {})[cpp] = hashlib.sha256(f.read()).hexdigest()
    return tasks


def task_of_file(tasks):
    return {f: t for t, info in tasks.items() for f in info["files"]}


def mutant_task(tasks, name):
    return task_of_file(tasks).get(name.split(".")[0] + ".cpp", "")


# ---------------------------------------------------------------- recording

def header_value(comments, key):
    """The text of the '# <key>: ...' lines of a mutant's header, joined ("" when there is
    none)."""
    out = []
    for c in comments:
        m = re.match(rf"^{key}:\s*(.*)$", c, re.IGNORECASE)
        if m and m.group(1).strip():
            out.append(m.group(1).strip())
    return " ".join(out)


def has_probes(repo, lab):
    return os.path.isdir(os.path.join(repo, "tests", lab, "probes"))


def record(grader, lab, files, built=False):
    """Runs the lab's probes on `files` ({student file name: bytes}, the others pristine) from
    <lab>-probes-direct (built here, unless `built`: the caller built it with these files);
    returns ({probe id: record}, None) or (None, why not)."""
    from grader.project import pristine_files
    from grader.worker import worker_files
    from grader.project import known_labs
    if not has_probes(grader.repo, lab):
        return {}, None
    binary = os.path.join(grader.build, "bin", f"{lab}-probes-direct")
    if not built:
        pristine = pristine_files(grader.repo)
        pristine.update(worker_files(grader.repo, known_labs(grader.repo)))
        grader.stage_direct(lab, files, pristine)
        if os.path.exists(binary):
            os.remove(binary)
        proc = subprocess.run(["cmake", "--build", grader.build, "--target",
                               f"{lab}-probes-direct", "-j", str(grader.jobs)],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=900)
        if proc.returncode != 0 or not os.path.isfile(binary):
            return None, ("the probes do not build:\n" +
                          proc.stdout.decode("utf-8", "replace")[-3000:])
    listed = subprocess.run([binary, "--list"], stdout=subprocess.PIPE, timeout=60, cwd=grader.cwd)
    ids = [r["probe"] for r in wh.parse_lines(listed.stdout.decode("utf-8", "replace"))]
    out, todo = {}, list(ids)
    while todo:  # a probe that crashes the process: recorded as an error, the rest run again
        try:
            p = subprocess.run([binary] + todo, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               timeout=PROBE_TIMEOUT, cwd=grader.cwd, stdin=subprocess.DEVNULL)
            recs = wh.parse_lines(p.stdout.decode("utf-8", "replace"))
            crash = f"crashed (status {p.returncode})"
        except subprocess.TimeoutExpired as e:
            recs = wh.parse_lines((e.stdout or b"").decode("utf-8", "replace"))
            crash = f"did not finish within {PROBE_TIMEOUT:g} s"
        for r in recs:
            if r.get("error"):  # the words the grader's path gives it (probes.py)
                from grader import wording
                r = dict(r, error=wording.probe_error(str(r["error"])))
            out[r["probe"]] = r
        done = {r["probe"] for r in recs}
        rest = [i for i in todo if i not in done]
        if not rest:
            break
        out[rest[0]] = {"probe": rest[0], "error": f"the probe {crash}"}
        todo = rest[1:]
    return out, None


def probe_inputs_digest(repo, lab):
    """A hash of what the skeleton's probe outputs depend on: the lab's skeleton files, its
    probes and the probe headers (the stored skeleton outputs are reused while it holds)."""
    h = hashlib.sha256()
    paths = [os.path.join(repo, "labs", lab, n) for n in sorted(os.listdir(os.path.join(repo, "labs", lab)))]
    pdir = os.path.join(repo, "tests", lab, "probes")
    paths += [os.path.join(pdir, n) for n in sorted(os.listdir(pdir))] if os.path.isdir(pdir) else []
    common = os.path.join(repo, "tests", "common")
    paths += [os.path.join(common, n) for n in sorted(os.listdir(common)) if n.startswith("wb_probe")]
    for p in paths:
        with open(p, "rb") as f:
            h.update(os.path.relpath(p, repo).encode() + b"\0" + f.read() + b"\0")
    return h.hexdigest()


# ----------------------------------------------------------------- the file

# A list whose items are each a number (or "nan", "inf", "-inf") or such a list on one line.
_ITEM = r'(?:-?[0-9.eE+-]+|"-?(?:nan|inf)"|true|false|null)'
_FLAT = re.compile(r"\[\n((?:[ ]*(?:" + _ITEM + r"|\[[^\[\]{}\n\"]*(?:\"-?(?:nan|inf)\"[^\[\]{}\n\"]*)*\]),?\n)+)[ ]*\]")


def dumps(data):
    """The catalogue's text: indented, but a list of numbers (or of such lists) on one line (the
    probe outputs are thousands of short lists)."""
    text = json.dumps(data, indent=1, ensure_ascii=False, sort_keys=False)
    while True:
        flat = _FLAT.sub(lambda m: "[" + ", ".join(
            x.strip().rstrip(",") for x in m.group(1).strip("\n").split("\n")) + "]", text)
        if flat == text:
            return text + "\n"
        text = flat

def probe_entry(rec, skeleton):
    e = {"probe": rec["probe"], "task": rec.get("task", ""), "title": rec.get("title", "")}
    for k in ("call", "notes", "tol", "in"):
        if rec.get(k) is not None:
            e[k] = rec[k]
    if rec.get("simple"):
        e["simple"] = True
    flags = [{k: o[k] for k in ("name", "each", "group") if o.get(k)}
             for o in rec.get("out") or [] if isinstance(o, dict) and (o.get("each") or o.get("group"))]
    if flags:
        e["out"] = flags
    e["expected"] = wh.compact(rec)
    e["skeleton"] = skeleton
    return e


def deviates(probes_by_id, records, task):
    """Whether `records` differ from the expected outputs on a probe of `task`."""
    return any(not wh.same(wh.compact(records.get(pid)), p["expected"], wh.tolerance(p))
               for pid, p in probes_by_id.items() if p["task"] == task)


def catalogue(repo, lab, tests, solution, skeleton, mutants, digest):
    """The lab's catalogue (hints.py reads it).

    solution, skeleton: {probe id: record}; mutants: [(name, comments, failed {test: text},
    records)] with header values read by `value(comments, key)`."""
    tasks = lab_tasks(repo, lab)
    probes = [probe_entry(r, wh.compact_any(skeleton.get(pid)) if skeleton is not None else None)
              for pid, r in solution.items()]
    by_id = {p["probe"]: p for p in probes}
    uses = collections.defaultdict(set)
    muts = {}
    for name, comments, failed, records in mutants:
        task = mutant_task(tasks, name) or header_value(comments, "task")
        for t in tasks:
            if t != task and records is not None and deviates(by_id, records, t):
                uses[t].add(task)  # t's probes go wrong when task's code is wrong: t uses it
        m = {"task": task, "kind": header_value(comments, "kind"),
             "hint": header_value(comments, "hint"), "failed": dict(sorted(failed.items()))}
        if records is not None:
            m["probes"] = {pid: wh.compact(records.get(pid)) for pid, p in by_id.items()
                           if p["task"] == task}
        muts[name] = m
    for t, info in tasks.items():
        info["uses"] = sorted(uses.get(t, ()))
    return {"version": wh.CATALOGUE_VERSION, "lab": lab,
            "generated_by": "tools/mutants --signatures: do not edit by hand",
            "skeleton_inputs": digest, "tests": tests, "tasks": tasks, "probes": probes,
            "mutants": muts}


# ------------------------------------------------------------- leave-one-out

def outcome(cat, name, leave_out=True):
    """What the diagnosis says of mutant `name` (left out of the catalogue, or not: what a
    student with exactly that mistake reads): ("mistake"|"part"|"counterexample"|"tests"|...,
    the part named or None, the Diagnosis)."""
    m = cat["mutants"][name]
    task = m.get("task", "")
    failed = m.get("failed") or {}
    tests = [(t, t not in failed, failed.get(t, "")) for t in cat.get("tests", [])
             if re.match(rf"^{re.escape(task)}\b", t)]
    d = wh.diagnose(cat, task, m.get("probes") or {}, tests or [("?", False, "")],
                    wh.task_title(cat, task), exclude={name} if leave_out else ())
    if d.status == "mistake":
        parts = {wh.part_key(n, cat["mutants"][n]) for n in d.mistake_names}
        return d.status, parts.pop() if len(parts) == 1 else None, d
    return d.status, d.part, d


def leave_one_out(cat):
    """[(mutant, has a peer of its part?, right|wrong|counterexample|tests|...)]."""
    muts = cat.get("mutants", {})
    peers = collections.Counter(wh.part_key(n, m) for n, m in muts.items() if m.get("kind"))
    rows = []
    for name in sorted(muts):
        m = muts[name]
        key = wh.part_key(name, m)
        status, part, d = outcome(cat, name)
        if part is not None:
            res = "right" if part == key else "wrong"
        elif status == "tests" and d.test_message.split(":\n", 1)[-1].strip():
            res = "tests"  # no probe differs: the failed test's own message is shown
        elif status in ("counterexample",):
            res = status
        else:
            res = "silent"  # nothing a student can act on
        rows.append((name, peers[key] > 1 and bool(m.get("kind")), res, part))
    return rows


def print_table(head, table, markdown=False):
    """A table of figures: Markdown, or columns padded to their widest cell."""
    if markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for l in table:
            print("| " + " | ".join(l) + " |")
        return
    w = [max(len(h), *(len(l[k]) for l in table)) for k, h in enumerate(head)]
    print("  ".join(h.ljust(w[k]) for k, h in enumerate(head)))
    for l in table:
        print("  ".join(c.ljust(w[k]) for k, c in enumerate(l)))


def loo_table(repo, labs, markdown=False, verbose=False, min_right=None, max_wrong=None,
              max_wrong_alone=None, max_silent=None):
    """The leave-one-out figures of every lab with a catalogue; returns the exit status."""
    head = ["lab", "mutants", "with a peer: right", "wrong", "counterexample", "alone: wrong",
            "alone: counterexample", "probes blind", "silent"]
    lines, totals = [], [0] * 9
    for lab in labs:
        cat = wh.load_catalogue(repo, lab)
        if cat is None:
            print(f"{lab}: no catalogue (tools/mutants --signatures --lab {lab})")
            continue
        rows = leave_one_out(cat)
        if verbose:
            for name, peer, res, part in rows:
                print(f"  {lab:10} {name:44} {'peer' if peer else 'alone':5} {res:14} "
                      f"{part[1] if part else ''}")
        peer = [r for r in rows if r[1]]
        alone = [r for r in rows if not r[1]]
        counts = [len(rows), sum(r[2] == "right" for r in peer), sum(r[2] == "wrong" for r in peer),
                  sum(r[2] == "counterexample" for r in peer), sum(r[2] == "wrong" for r in alone),
                  sum(r[2] == "counterexample" for r in alone),
                  sum(r[2] == "tests" for r in rows), sum(r[2] == "silent" for r in rows)]
        lines.append((lab, counts, len(peer), len(alone)))
        for k, c in enumerate(counts):
            totals[k] += c
        totals[8] += len(peer)
    if not lines:
        return 1
    allpeer = totals[8]
    allalone = totals[0] - allpeer
    lines.append(("all", totals[:8], allpeer, allalone))

    def pct(a, b):
        return f"{a}/{b} ({100 * a / b:.0f}%)" if b else "0/0"
    table = [[lab, str(c[0]), pct(c[1], p), pct(c[2], p), pct(c[3], p), pct(c[4], a),
              pct(c[5], a), str(c[6]), str(c[7])] for lab, c, p, a in lines]
    print_table(head, table, markdown)
    status = 0
    right_pct = 100 * totals[1] / allpeer if allpeer else 0
    wrong_pct = 100 * totals[2] / allpeer if allpeer else 0
    if min_right is not None and right_pct < min_right:
        print(f"mutants: leave-one-out: right for {right_pct:.0f}% < --min-right {min_right:g}%")
        status = 1
    if max_wrong is not None and wrong_pct > max_wrong:
        print(f"mutants: leave-one-out: wrong for {wrong_pct:.0f}% > --max-wrong {max_wrong:g}%")
        status = 1
    if max_silent is not None and totals[7] > max_silent:
        print(f"mutants: leave-one-out: {totals[7]} mutants get nothing to act on > --max-silent "
              f"{max_silent}")
        status = 1
    if max_wrong_alone is not None and totals[4] > max_wrong_alone:
        print(f"mutants: leave-one-out: {totals[4]} mutants alone in their part named another "
              f"part > --max-wrong-alone {max_wrong_alone}")
        status = 1
    print("\nright/wrong: the part named (a catalogued mistake matched exactly, or the part the "
          "wrong probes point at) is / is not the left-out mutant's file and '# kind:'; "
          "counterexample: no part named, the first wrong probe shown; silent: none of these, "
          "nor a failed test's message; probes blind: every "
          "probe agrees with the solution (the failed test's own message is shown).")
    return status


def disagreements(solution, records):
    """The probes on which `records` (a correct variant's) differ from the solution's."""
    out = []
    for pid, rec in solution.items():
        probe = {"probe": pid, "tol": rec.get("tol"), "expected": wh.compact(rec)}
        if not wh.same(wh.compact(records.get(pid)), probe["expected"], wh.tolerance(probe)):
            out.append(pid)
    return out


# ------------------------------------------------------------------ mid-lab

def mid_lab_variants(repo, lab, cat, variant_files):
    """Two submissions of one lab, each with every other task at its skeleton and the rest
    holding one catalogued mistake each (the first of the task the probes can see), the tasks
    alternating between the two; a task that a mistake's task builds on (tasks[...].uses)
    gets the solution's files instead of the skeleton's. Returns [(files, {task: mutant or
    None})]. variant_files: {mutant name: its files} (the solution's with the patch)."""
    from grader.project import student_files
    tasks = cat.get("tasks") or {}
    names = student_files(repo, lab)
    skeleton = {}
    solution = {}
    for n in names:
        with open(os.path.join(repo, "labs", lab, n), "rb") as f:
            skeleton[n] = f.read()
        with open(os.path.join(repo, "solutions", lab, n), "rb") as f:
            solution[n] = f.read()
    picks = {}
    for task in sorted(tasks):
        for name, m in sorted(cat.get("mutants", {}).items()):
            if m.get("task") != task or name not in variant_files:
                continue
            status, _, _ = outcome(cat, name, leave_out=False)
            if status not in ("tests", "no probes"):
                picks[task] = name
                break
    order = sorted(tasks)
    out = []
    for parity in (0, 1):
        files, plan = dict(skeleton), {}
        for k, task in enumerate(order):
            if k % 2 != parity or task not in picks:
                plan[task] = None
                continue
            plan[task] = picks[task]
            for f in tasks[task].get("files") or []:
                files[f] = variant_files[picks[task]][f]
            for dep in tasks[task].get("uses") or []:
                for f in tasks.get(dep, {}).get("files") or []:
                    files[f] = solution[f]
                plan[dep] = "solution"
        out.append((files, plan))
    return out


def mid_lab_check(repo, grader, lab, cat, variant_files, log):
    """Grades the two mid-lab submissions through the grader (sandboxed tests, the probes
    through the worker) and compares each task's diagnosis with the whole-lab one (the same
    mistake, every other task correct: from the catalogue), and reads what the student reads
    (the table: no line over 100 characters, no word of the harness). Returns a list of
    problems."""
    import io
    from grader import results
    problems = []
    for files, plan in mid_lab_variants(repo, lab, cat, variant_files):
        t0 = time.monotonic()
        rep = grader.grade({lab: files}, [lab])[lab]
        if not rep.gradable:
            problems.append(f"{lab}: the mid-lab submission {plan} does not compile or was refused")
            continue
        text = io.StringIO()
        results.print_table({lab: rep}, {}, out=text, seed=grader.seed)
        problems += [f"{lab} (mid-lab, what the student reads): {p}"
                     for p in results.student_text_problems(text.getvalue())]
        for task, mutant in plan.items():
            got = rep.diagnosis.get(task)
            if mutant is None:
                if got is None or got.status != "not started":
                    problems.append(f"{lab} {task} (skeleton, mid-lab): expected 'not started', "
                                    f"got {got.status if got else 'no diagnosis'}")
                continue
            if mutant == "solution":
                if got is not None:
                    problems.append(f"{lab} {task} (solution, mid-lab): expected no diagnosis, "
                                    f"got {got.status}")
                continue
            _, _, want = outcome(cat, mutant, leave_out=False)
            if got is None or got.lines() != want.lines():
                problems.append(f"{lab} {task} ({mutant}): mid-lab diagnosis differs from "
                                "whole-lab:\n  whole-lab: " + "\n    ".join(want.lines()) +
                                "\n  mid-lab:   " + "\n    ".join(got.lines() if got else ["(none)"]))
        log(f"mutants: {lab}: mid-lab {sorted(t for t, m in plan.items() if m and m != 'solution')} "
            f"in {time.monotonic() - t0:.1f} s")
    return problems


# ------------------------------------------------------------ fresh mistakes

def fresh_outcome(cat, name, kind, rep, changed=""):
    """What a mistake written apart from the catalogue gets (tools/mutants --fresh): (verdict,
    part named or why, the diagnosis' lines). verdict: right, wrong (another part named, or
    "not started" for started code), counterexample (no part named, the first wrong probe
    shown), tests (every probe agrees: the failed test's message shown), silent (nothing to
    act on: no diagnosis, or expected and got printed alike), missed (100 points), does not
    compile. changed: the student file the mistake is in (by default the name's first word)."""
    stem = changed[:-len(".cpp")] if changed.endswith(".cpp") else name.split(".")[0]
    if rep.compile_error:
        return "does not compile", rep.compile_error.splitlines()[-1:], []
    if rep.score >= rep.max_score:
        return "missed", "", []
    task = task_of_file((cat or {}).get("tasks") or {}).get(stem + ".cpp", "")
    d = rep.diagnosis.get(task)
    if d is None:
        return "silent", f"no diagnosis of {task or stem}", []
    lines = d.lines()
    named = None
    if d.status == "mistake":
        parts = {wh.part_key(n, cat["mutants"][n]) for n in d.mistake_names}
        named = parts.pop() if len(parts) == 1 else None
    elif d.status == "part":
        named = tuple(d.part)
    if named is not None:
        if not kind:
            return "named", f"{named[0]}: {named[1]}", lines
        return ("right" if named == (stem, kind) else "wrong"), f"{named[0]}: {named[1]}", lines
    if d.status == "not started":
        return "wrong", "not started", lines
    if d.status == "counterexample":
        return "counterexample", "", lines
    if d.status in ("tests", "no probes"):
        pairs = re.findall(r"expected[:\s]+(.+?)\s*\n\s*got[:\s]+(.+)", d.test_message)
        if pairs and all(a.strip() == b.strip() for a, b in pairs):
            return "silent", "expected and got printed alike", lines
        return "tests", "", lines
    return "silent", d.status, lines


FRESH = ["right", "counterexample", "tests", "wrong", "silent", "missed"]


def fresh_table(rows, labs, markdown=False, verbose=False):
    """The figures of tools/mutants --fresh; returns the exit status (1: a mistake missed, a
    wrong part named, a silent one, or a student's text with a long line or harness words)."""
    for lab, name, kind, verdict, named, lines, problems in sorted(rows):
        print(f"{lab:10} {name:44} {verdict:14} {named if isinstance(named, str) else ''}"
              + (f"  (expected: {kind})" if verdict == "wrong" else ""))
        if verbose or verdict in ("wrong", "silent", "bad"):
            print("\n".join("      " + l for l in lines))
        for p in problems:
            print(f"      TEXT: {p}")
    head = ["lab", "mistakes"] + FRESH
    table = []
    for lab in labs + ["all"]:
        rs = [r for r in rows if lab in ("all", r[0])]
        n = len(rs)
        table.append([lab, str(n)] + [f"{sum(r[3] == v for r in rs)} ({100 * sum(r[3] == v for r in rs) / n:.0f}%)"
                                      if n else "0" for v in FRESH])
    print()
    print_table(head, table, markdown)
    text = sum(1 for r in rows if r[6])
    print(f"\n{text} of {len(rows)} students' texts have a line over 100 characters or a word "
          "of the harness")
    bad = [r for r in rows if r[3] in ("wrong", "silent", "missed", "bad", "does not compile")]
    return 1 if bad or text else 0
