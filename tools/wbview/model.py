"""What one viewer page holds: the runs packed for drawing, their curves, the exact
motion, the difference between two runs and the frame budget (docs/view.md)."""
import base64
import bisect
import itertools
import math
import operator
import sys
from array import array

from .data import InputError, particle_scene, rigid_scene

# Positions are stored as 32-bit floats relative to the scene's centre: 7 significant
# digits of the scene's size, far below a pixel. A page holds at most this many of them
# in all (about 32 MB, 43 MB as base64 text); a longer run keeps every k-th written step
# (always the first and the last): docs/view.md, "Large runs".
MAX_STORED_VALUES = 8_000_000
MAX_CHART_POINTS = 4000     # points of a curve (stats rows, differences) kept for drawing
MAX_SPRINGS = 200_000       # springs drawn; a larger network is drawn as particles only
MAX_EXACT_PATHS = 50        # exact paths drawn as curves (every particle gets its marker)
FRAME_MS = 1000.0 / 60.0    # one frame at 60 frames per second
# Forces whose cost grows with the square of the particle count (docs/scenes.md, Limits).
QUADRATIC_FORCES = ("newton", "boids")


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def clean(x):
    """A number for JSON: None when not finite (JSON has no NaN or infinity)."""
    return x if finite(x) else None


def clean_all(v):
    """A JSON value with every number that is not finite replaced by None, at any depth."""
    if isinstance(v, float):
        return clean(v)
    if isinstance(v, list):
        return [clean_all(x) for x in v]
    if isinstance(v, dict):
        return {k: clean_all(x) for k, x in v.items()}
    return v


def kept_frames(frames, per_frame, budget):
    """Indices of the written steps a page keeps: all of them when frames × per_frame
    values fit in `budget`, else every k-th, the first and the last always."""
    if frames * per_frame <= budget or frames <= 2:
        return list(range(frames)), 1
    k = math.ceil(frames * per_frame / max(budget, 1))
    keep = list(range(0, frames, k))
    if keep[-1] != frames - 1:
        keep.append(frames - 1)
    return keep, k


def thin(n, limit=MAX_CHART_POINTS, always=()):
    """Row indices of a curve of n points, at most about `limit` of them, evenly spread,
    with the first, the last and `always` kept."""
    step = max(1, math.ceil(n / limit))
    keep = set(range(0, n, step)) | {n - 1} | {i for i in always if 0 <= i < n}
    return sorted(keep)


def fit_box(trace, diverged=False):
    """The box the camera fits: every finite position of the run; for a run whose summary
    says it diverged, only the frames before it left 10 times its scene's size S behind
    (S as in the run contract's rule: the larger of the first frame's extent and its
    largest distance from the origin), which would shrink the scene to a dot. The page's
    `follow` button fits the current frame instead."""
    dims = 3 if trace.kind == "rigid" else 2
    c, n = len(trace.cols), trace.n
    v = trace.values
    if not diverged:
        lo, hi = [], []
        for d in range(dims):
            col = v[d::c]
            if not math.isfinite(sum(col)):  # a NaN or an infinity (or a sum that overflows)
                col = [x for x in col if math.isfinite(x)]
            if not len(col):
                return None
            lo.append(min(col))
            hi.append(max(col))
        return {"lo": lo, "hi": hi}

    def box(k):
        lo, hi = [math.inf] * dims, [-math.inf] * dims
        for d in range(dims):
            col = [x for x in v[k * n * c + d:(k + 1) * n * c:c] if math.isfinite(x)]
            if len(col) < n:
                return None
            lo[d], hi[d] = min(col), max(col)
        return lo, hi
    first = box(0)
    if first is None:
        return None
    lo, hi = list(first[0]), list(first[1])
    scale = max(max(h - l for l, h in zip(lo, hi)),
                max(math.sqrt(sum(v[i * c + d] ** 2 for d in range(dims))) for i in range(n)),
                1e-9)
    for k in range(1, trace.frames):
        b = box(k)
        if b is None:
            break
        lo2 = [min(x, y) for x, y in zip(lo, b[0])]
        hi2 = [max(x, y) for x, y in zip(hi, b[1])]
        if max(h - l for l, h in zip(lo2, hi2)) > 10 * scale:
            break
        lo, hi = lo2, hi2
    return {"lo": lo, "hi": hi}


def pack_floats(values):
    """Little-endian float32, base64: what the page decodes into a Float32Array."""
    a = array("f", values)
    if sys.byteorder == "big":
        a.byteswap()
    return base64.b64encode(a.tobytes()).decode("ascii")


def pack_trace(trace, keep, origin, width=None):
    """The kept frames' values (the first `width` columns of each row, all by default),
    positions relative to `origin` (float64 in the page's metadata), as float32 base64."""
    c, n = len(trace.cols), trace.n
    w = width or c
    dims = len(origin)
    out = array("d")
    v = trace.values
    for k in keep:
        chunk = v[k * n * c:(k + 1) * n * c]
        if w < c:
            chunk = array("d", (x for i in range(n) for x in chunk[i * c:i * c + w]))
        for d in range(dims):
            if origin[d]:
                col = chunk[d::w]
                chunk[d::w] = array("d", map(operator.sub, col,
                                             itertools.repeat(origin[d], len(col))))
        out.extend(chunk)
    return pack_floats(out)


def kept_columns(trace, others=(), budget=None):
    """How many columns of each row the page keeps: all (a particle's velocity with its
    position) unless that would thin the written steps of this run or the others, whose
    velocities would then be left out (positions only, as before)."""
    c = len(trace.cols)
    if trace.kind != "particles":
        return c
    frames = sum(t.frames for t in (trace,) + tuple(others))
    return c if frames * trace.n * c <= (budget or MAX_STORED_VALUES) else 2


def step_numbers(times, stats, summary, doc):
    """The step number of each written time: from the stats (step and t of the same
    written steps), else t / dt with dt = t / steps of the summary, else the scene's dt.
    Returns (steps or None, dt or None, where from)."""
    if stats:
        by_t = dict(zip(stats["t"], stats["step"]))
        got = [by_t.get(t) for t in times]
        if all(s is not None and finite(s) for s in got):
            steps = [int(s) for s in got]
            dt = None
            if steps[-1] > 0:
                dt = times[-1] / steps[-1]
            return steps, dt, "stats"
    dt = None
    if summary and isinstance(summary.get("steps"), int) and summary["steps"] > 0 \
            and finite(summary.get("t")) and summary["t"] > 0:
        dt, where = summary["t"] / summary["steps"], "summary"
    elif finite(doc.get("dt")) and doc["dt"] > 0 if doc else False:
        dt, where = float(doc["dt"]), "scene"
    if dt is None:
        return None, None, None
    return [round(t / dt) for t in times], dt, where


def stats_curves(stats, kind, always_t=()):
    """The stats columns the charts draw, thinned to MAX_CHART_POINTS rows."""
    if not stats:
        return None
    rows = len(stats["t"])
    always = [bisect.bisect_left(stats["t"], t) for t in always_t]
    keep = thin(rows, always=always)
    names = ["step", "t", "energy", "kinetic", "potential", "px", "py"]
    if kind == "rigid":
        names += ["pz", "Lx", "Ly", "Lz"]
    return {c: [clean(stats[c][i]) for i in keep] for c in names}


def exact_motion(doc, trace):
    """(kind, at) of the scene's closed form (tools/wbplot/exact.py, the report's), or
    (None, None). Not for scenes whose contacts or pins the closed forms ignore."""
    if trace.kind != "particles" or not doc:
        return None, None
    if doc.get("planes") or doc.get("pinned") or doc.get("rope") or doc.get("cloth"):
        return None, None
    from wbplot.exact import motion
    kind, at = motion(doc)
    if kind is None:
        return None, None
    count = len(doc.get("particles", []) or [])
    if count != trace.n:
        return None, None
    return kind, at


def exact_block(kind, at, trace, keep, origin):
    """The exact positions at the kept frames, the exact paths (one period, or the run's
    time span) and the distance of the run from the exact motion at every written step."""
    n = trace.n
    pos = array("d")
    for k in keep:
        t = trace.t[k]
        for i in range(n):
            x, y = at(i, t)
            pos.extend((x - origin[0], y - origin[1]))
    span = getattr(at, "period", None) or (trace.t[-1] - trace.t[0])
    paths = []
    for i in range(min(n, MAX_EXACT_PATHS)):
        pts = []
        for s in range(257):
            t = trace.t[0] + span * s / 256
            x, y = at(i, t)
            pts.append([x, y])
        paths.append(pts)
    dist = []
    for k in range(trace.frames):
        t, worst = trace.t[k], 0.0
        for i in range(n):
            ex, ey = at(i, t)
            d = math.hypot(trace.at(k, i, "x") - ex, trace.at(k, i, "y") - ey)
            worst = max(worst, d) if math.isfinite(d) else math.inf
        dist.append(worst)
    keep_c = thin(len(dist))
    return {"kind": kind, "pos": pack_floats(pos), "paths": paths,
            "periodic": bool(getattr(at, "period", None)),
            "distance": {"t": [trace.t[i] for i in keep_c], "v": [clean(dist[i]) for i in keep_c]}}


def _quat_angle(a, b):
    """The angle (rad) of the rotation between two orientation quaternions."""
    na = math.sqrt(sum(x * x for x in a))
    nb = math.sqrt(sum(x * x for x in b))
    if not (na > 0 and nb > 0):
        return math.nan
    d = abs(sum(x * y for x, y in zip(a, b))) / (na * nb)
    return 2 * math.acos(min(1.0, d))


def difference(t1, t2):
    """max over ids of the distance between the two runs at each written time of the
    first (the second's state linearly interpolated between its written steps when it
    did not write that time; None past its end), and for rigid bodies the largest angle
    between their orientations."""
    dims = 3 if t1.kind == "rigid" else 2
    c1, c2 = len(t1.cols), len(t2.cols)
    dist, ang = [], []
    tol = 1e-9 * max(abs(t1.t[-1]), abs(t2.t[-1]), 1e-300)
    for k in range(t1.frames):
        t = t1.t[k]
        j = bisect.bisect_left(t2.t, t - tol)
        if j >= t2.frames or t2.t[j] > t + tol and j == 0:
            dist.append(None)
            ang.append(None)
            continue
        if abs(t2.t[j] - t) <= tol:
            lo, hi, w = j, j, 0.0
        else:
            lo, hi = j - 1, j
            w = (t - t2.t[lo]) / (t2.t[hi] - t2.t[lo])
        worst, worst_a = 0.0, 0.0
        for i in range(t1.n):
            b1 = (k * t1.n + i) * c1
            bl, bh = (lo * t2.n + i) * c2, (hi * t2.n + i) * c2
            p1 = t1.values[b1:b1 + dims]
            p2 = [t2.values[bl + d] * (1 - w) + t2.values[bh + d] * w for d in range(dims)]
            d = math.sqrt(sum((a - b) ** 2 for a, b in zip(p1, p2)))
            worst = max(worst, d) if math.isfinite(d) else math.inf
            if dims == 3:
                q1 = t1.values[b1 + 3:b1 + 7]
                q2 = t2.values[(bl if w < 0.5 else bh) + 3:(bl if w < 0.5 else bh) + 7]
                a = _quat_angle(q1, q2)
                worst_a = max(worst_a, a) if math.isfinite(a) else math.inf
        dist.append(worst)
        ang.append(worst_a)
    keep = thin(len(dist))
    out = {"t": [t1.t[i] for i in keep], "v": [clean(dist[i]) for i in keep],
           "identical": all(d == 0 for d in dist) and all(a in (0, None) for a in ang)
           and None not in dist}
    if dims == 3:
        out["angle"] = [clean(ang[i]) for i in keep]
    return out


def frame_budget(summary, doc, n, kind):
    """The step loop's CPU time per simulated 1/60 s against a 60 Hz frame, and how many
    particles or bodies would fit in one frame at this cost (docs/view.md, "The frame
    budget"). From the summary's cpu_s and t: never timed here."""
    what = "bodies" if kind == "rigid" else "particles"
    if not summary:
        return {"available": False, "why": "no summary given (--summary: the run's last "
                                           "stdout line saved to a file)"}
    cpu, t, steps = summary.get("cpu_s"), summary.get("t"), summary.get("steps")
    if not finite(cpu):
        return {"available": False, "why": "the summary's cpu_s is null (the CPU clock was "
                                           "unavailable)"}
    if not (finite(t) and t > 0 and isinstance(steps, int) and steps > 0):
        return {"available": False, "why": "the run took no steps"}
    ms = cpu * 1000.0 / (t * 60.0)
    forces = [f.get("type") for f in (doc or {}).get("forces", []) or [] if isinstance(f, dict)]
    quadratic = [f for f in forces if f in QUADRATIC_FORCES]
    ratio = FRAME_MS / ms if ms > 0 else math.inf
    fit = n * (math.sqrt(ratio) if quadratic else ratio)
    return {"available": True, "cpu_s": cpu, "t": t, "steps": steps, "ms_per_frame": ms,
            "frame_ms": FRAME_MS, "share": ms / FRAME_MS, "n": n, "what": what,
            "steps_per_frame": (1 / 60) / (t / steps),
            "fit": clean(math.floor(fit)) if math.isfinite(fit) else None,
            "scaling": (f"n² ({', '.join(sorted(set(quadratic)))})" if quadratic else "n")}


def run_block(trace, stats, summary, label, keep, every, origin, width=None):
    steps, dt, step_from = step_numbers([trace.t[k] for k in keep], stats, summary, None)
    div = None
    if summary and summary.get("status") == "diverged":
        div = {"step": summary.get("steps"), "t": clean(summary.get("t")),
               "why": str(summary.get("diverged", ""))}
    return {"label": label, "path": trace.path, "n": trace.n, "frames_written": trace.frames,
            "kept_every": every, "t": [trace.t[k] for k in keep], "steps": steps, "dt": dt,
            "step_from": step_from, "data": pack_trace(trace, keep, origin, width),
            "stats": stats_curves(stats, trace.kind, [div["t"]] if div and div["t"] else ()),
            "summary": clean_all(summary or {}),
            "diverged": div}


def build(trace, stats, summary, doc, scene_path, run2=None, labels=("run", "run 2")):
    """The page's data: a dict for JSON (binary blocks as base64 strings)."""
    kind = trace.kind
    width = kept_columns(trace, (run2[0],) if run2 is not None else ())
    per = width * trace.n
    budget = MAX_STORED_VALUES // (2 if run2 else 1)
    keep, every = kept_frames(trace.frames, per, budget)
    box = fit_box(trace, diverged=bool(summary and summary.get("status") == "diverged"))
    if run2 is not None and box and run2[0].kind == kind:
        b2 = fit_box(run2[0], diverged=bool(run2[2] and run2[2].get("status") == "diverged"))
        if b2:
            box = {"lo": [min(a, b) for a, b in zip(box["lo"], b2["lo"])],
                   "hi": [max(a, b) for a, b in zip(box["hi"], b2["hi"])]}
    dims = 3 if kind == "rigid" else 2
    origin = [0.0] * dims
    if box:
        origin = [(lo + hi) / 2 for lo, hi in zip(box["lo"], box["hi"])]
    scene = None
    if doc is not None:
        scene = (rigid_scene if kind == "rigid" else particle_scene)(doc, trace.n, scene_path)
        if kind == "particles" and len(scene["springs"]) > MAX_SPRINGS:
            scene["springs_left_out"] = len(scene["springs"])
            scene["springs"] = []
    r1 = run_block(trace, stats, summary, labels[0], keep, every, origin, width)
    if doc and r1["steps"] is None:
        r1["steps"], r1["dt"], r1["step_from"] = step_numbers(r1["t"], None, None, doc)
    out = {"version": 1, "kind": kind, "n": trace.n, "cols": trace.cols[:width], "origin": origin,
           "scene_dt": (doc or {}).get("dt") if finite((doc or {}).get("dt")) else None,
           "box": box, "scene": scene, "runs": [r1],
           "name": (doc or {}).get("name") or None, "description": None,
           "scene_path": scene_path, "exact": None, "difference": None,
           "budget": frame_budget(summary, doc, trace.n, kind),
           "limits": {"max_values": MAX_STORED_VALUES}}
    if doc and isinstance(doc.get("description"), str):
        from wbplot.claims import strip_markers
        out["description"] = strip_markers(doc["description"])
    ek, at = exact_motion(doc, trace)
    if ek:
        out["exact"] = exact_block(ek, at, trace, keep, origin)
    if run2 is not None:
        t2, s2, sum2 = run2
        if t2.kind != kind:
            raise InputError(f"{t2.path}: a {'rigid-body' if t2.kind == 'rigid' else 'particle'} "
                             f"run, the first run ({trace.path}) is a "
                             f"{'rigid-body' if kind == 'rigid' else 'particle'} run: a second "
                             "run must be of the same scene")
        if t2.n != trace.n:
            what = "bodies" if kind == "rigid" else "particles"
            raise InputError(f"{t2.path}: {t2.n} {what}, the first run ({trace.path}) has "
                             f"{trace.n}: a second run must be of the same scene")
        keep2, every2 = kept_frames(t2.frames, per, budget)
        b2 = run_block(t2, s2, sum2, labels[1], keep2, every2, origin, width)
        if doc and b2["steps"] is None:
            b2["steps"], b2["dt"], b2["step_from"] = step_numbers(b2["t"], None, None, doc)
        out["runs"].append(b2)
        out["difference"] = difference(trace, t2)
    return out
