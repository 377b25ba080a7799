"""The solution's recorded runs of a lab's default scenes, as data a live page draws
beside the student's run (docs/live.md, "Side by side"): positions at the written steps
(float32), the energy there, the run's step and integrator and whether it diverged.
Made from tools/report's runs (build/report/<lab>/<scene>.csv, -stats.csv,
-summary.json); tools/pack ships them as live/recorded/<lab>/<scene>.json. Never code."""
import json
import math
import os

from wbview import model
from wbview.data import InputError, read_stats, read_summary, read_trace

MAX_VALUES = 1_000_000   # floats kept per scene (4 MB, 5.3 MB as base64)
MAX_FRAMES = 1200        # written steps kept per scene


def from_report(report_dir, lab, stem):
    """The recorded run of scene `stem` from a report's files, or None when the report
    has no run of it. Raises InputError on files that cannot be read."""
    base = os.path.join(report_dir, lab, stem)
    if not os.path.isfile(base + ".csv"):
        return None
    trace = read_trace(base + ".csv")
    stats = read_stats(base + "-stats.csv", trace.kind) if os.path.isfile(base + "-stats.csv") \
        else None
    summary = read_summary(base + "-summary.json") \
        if os.path.isfile(base + "-summary.json") else {}
    return pack(trace, stats, summary)


def pack(trace, stats, summary):
    cols = 7 if trace.kind == "rigid" else 2  # positions (and orientations)
    keep, every = model.kept_frames(trace.frames, trace.n * cols,
                                    min(MAX_VALUES, MAX_FRAMES * trace.n * cols))
    dims = 3 if trace.kind == "rigid" else 2
    box = model.fit_box(trace, diverged=summary.get("status") == "diverged")
    origin = [(lo + hi) / 2 for lo, hi in zip(box["lo"], box["hi"])] if box else [0.0] * dims
    values = []
    width = len(trace.cols)
    for k in keep:
        for i in range(trace.n):
            row = trace.values[(k * trace.n + i) * width:(k * trace.n + i) * width + cols]
            values.extend(v - origin[d] if d < dims else v for d, v in enumerate(row))
    times = [trace.t[k] for k in keep]
    steps, dt, _ = model.step_numbers(times, stats, summary, None)
    energy = [None] * len(keep)
    if stats:
        by_t = dict(zip(stats["t"], stats["energy"]))
        energy = [model.clean(by_t.get(t)) for t in times]
    div = None
    if summary.get("status") == "diverged":
        div = {"step": summary.get("steps"), "t": model.clean(summary.get("t")),
               "why": str(summary.get("diverged", ""))}
    return {"kind": trace.kind, "n": trace.n, "cols": cols, "origin": origin, "every": every,
            "t": times, "steps": steps or [None] * len(keep), "dt": dt,
            "energy": energy, "diverged": div, "pos": model.pack_floats(values)}


def load(folder, lab, stem):
    """A recorded run shipped as data (live/recorded/<lab>/<stem>.json), or None."""
    path = os.path.join(folder, lab, stem + ".json")
    if not os.path.isfile(path):
        return None
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: cannot read a recorded run ({e})") from None


def write(folder, lab, stem, block):
    os.makedirs(os.path.join(folder, lab), exist_ok=True)
    with open(os.path.join(folder, lab, stem + ".json"), "w", encoding="utf-8") as f:
        json.dump(block, f, separators=(",", ":"), allow_nan=False)


def finite_or_none(x):
    return x if isinstance(x, (int, float)) and math.isfinite(x) else None
