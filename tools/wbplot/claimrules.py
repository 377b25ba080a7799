"""Two rules on claims (docs/report.md, Claims), for every handout, present and future:

- **A claim on a timing keeps a margin the machine's noise cannot eat.** A claim whose
  measure reads a CPU or wall time, or a ratio of them (the summary's cpu_s, a sweep's
  wall_s, a plug-in column a lab declares timed in TIMED_COLUMNS), holds only with a
  factor TIMING_MARGIN to spare: `> V` needs at least 2 V, `< V` at most V / 2, `in [A, B]`
  between 2 A and B / 2, and `= V ± T` is no claim on a timing at all. A ratio measured
  at 1.4 against a bound of 1 is a coin a busy machine flips (tools/claims fails it,
  saying why; wbplot/claims.py calls margin_problem).
- **A claim about motion is checked on what a student looks at.** A handout sentence that
  says a scene's bodies come to rest, stand still, wander or creep must carry a claim on
  positions (a trace's x, y, disp or move@T, a closed-form offset, a plug-in column of
  distances moved), not only on speeds or energies: a solver can keep a velocity that its
  position correction cancels every step, and a column "that never comes to rest" then
  stands perfectly still (tools/pattern claims calls lint_motion).
"""
import re

TIMING_MARGIN = 2.0
TIMED_NAMES = {"cpu_s", "wall_s"}  # in any summary, sweep or plug-in file


def _timed_columns(lab, fname):
    """The columns a lab plug-in declares timed in a file it writes (TIMED_COLUMNS)."""
    import importlib
    import os
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "labs", f"{lab}.py")
    if not re.fullmatch(r"[A-Za-z0-9_]+", lab or "") or not os.path.exists(here):
        return set()
    mod = importlib.import_module(f"{__package__}.labs.{lab}")
    return set(getattr(mod, "TIMED_COLUMNS", {}).get(fname, ()))


def timed(claim):
    """True when the claim's measure reads a timing (see above)."""
    name, args = claim.measure[0], claim.measure[1:]
    if any(a in TIMED_NAMES for a in args):
        return True
    if name == "csv" and len(args) >= 2:
        lab, _, fname = args[0].partition("/")
        return args[1] in _timed_columns(lab, fname)
    return False


def margin_problem(claim, got):
    """'' when a timing claim holds with TIMING_MARGIN to spare (or is no timing claim)."""
    if not timed(claim) or not isinstance(got, (int, float)):
        return ""
    m = TIMING_MARGIN
    why = (f" (a claim on a timing must hold by a factor {m:g}, the machine's noise can eat "
           "less; docs/report.md, Claims): measured " + f"{got:.4g}")
    if claim.op in (">", ">="):
        if not claim.value > 0:
            return "a claim on a timing needs a bound > 0" + why
        return "" if got >= m * claim.value else f"not above {m:g} x {claim.value:g}" + why
    if claim.op in ("<", "<="):
        if not claim.value > 0:
            return "a claim on a timing needs a bound > 0" + why
        return "" if got <= claim.value / m else f"not below {claim.value:g} / {m:g}" + why
    if claim.op == "in":
        if not (claim.lo > 0 and claim.hi > 0):
            return "a claim on a timing needs bounds > 0" + why
        return "" if m * claim.lo <= got <= claim.hi / m else \
            f"not within [{m:g} x {claim.lo:g}, {claim.hi:g} / {m:g}]" + why
    return "a timing is no value to claim with = (state a direction with a margin)" + why


# ----------------------------------------------------------------------------
# Motion claims

REST_WORDS = re.compile(
    r"\b(comes? to rest|came to rest|coming to rest|stands? still|stood still|"
    r"stays? (?:still|put)|held still|never (?:stops|settles)|"
    r"(?<!energy )(?<!error )(?:wanders?|creeps?)|"
    r"keeps? (?:moving|sliding|creeping))\b", re.I)
POSITION_QUANTITIES = re.compile(r"^(x|y|z|r|disp|rchange|r@.*|move@.*)(:end)?$")
POSITION_COLUMNS = re.compile(r"(moved|disp|height|position|^x$|^y$|^z$|gap|overlap|"
                              r"drift|angle|offset)", re.I)
MARKER = re.compile(r"<!--\s*claim:\s*(.*?)\s*-->", re.S)


def positional(body):
    """True when a claim's body reads positions (see REST above)."""
    words = body.split()
    if len(words) < 3:
        return False
    name, args = words[0], words[1:]
    if name == "offset":
        return True
    if name == "trace":
        return bool(POSITION_QUANTITIES.match(args[1]))
    if name == "csv":
        return bool(POSITION_COLUMNS.search(args[1]))
    if name == "summary":
        return args[1] in ("hinge_drift", "hinge_angle")
    return False


def _paragraphs(text):
    """(first line, paragraph) outside code blocks; a table row or a heading alone, a list
    item with its continuation lines."""
    out, par, start, in_code = [], [], 0, False
    for i, ln in enumerate(text.split("\n"), 1):
        if ln.strip().startswith("```"):
            in_code = not in_code
            if par:
                out.append((start, "\n".join(par)))
            par = []
            continue
        if in_code:
            continue
        alone = re.match(r"\s*(\||#)", ln)             # a table row, a heading
        item = re.match(r"\s*([-*+]\s|\d+\.\s)", ln)    # a list item and its next lines
        if not ln.strip() or alone or item:
            if par:
                out.append((start, "\n".join(par)))
            par = []
            if alone:
                out.append((i, ln))
                continue
            if not item:
                continue
        if not par:
            start = i
        par.append(ln)
    if par:
        out.append((start, "\n".join(par)))
    return out


def lint_motion(path, scene_names):
    """[(line, sentence)] of sentences that say a named scene's bodies rest, stand still,
    wander or creep, or say so with claim markers, and carry no claim on positions."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    named = re.compile(r"`(" + "|".join(re.escape(n) for n in sorted(scene_names)) + r")`") \
        if scene_names else None
    findings = []
    for line, par in _paragraphs(text):
        for sent in re.split(r"(?<=[.!?;])\s+(?=[A-Z*(`$])", par):
            plain = MARKER.sub(" ", sent)
            if not REST_WORDS.search(plain):
                continue
            bodies = MARKER.findall(sent)
            about_run = bodies or (named is not None and named.search(plain))
            if about_run and not any(positional(b) for b in bodies):
                findings.append((line, " ".join(plain.split())[:160]))
    return findings
