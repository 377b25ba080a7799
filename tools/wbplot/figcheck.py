"""The report's own checks of what its figures show (tools/report runs them on every figure
of every lab, present and future; docs/report.md, "What the figures may say"). From the facts
figfacts.py records as each figure is saved:

- diverged: a figure says a run diverged (or blew up) only when a run of its scene did, by
  that run's own summary; a symmetric-log axis (a blow-up's drawing) likewise;
- rounding: no linear axis is zoomed into rounding: its view spans at least ROUNDING_VIEW
  of its own magnitude and of 1 (SI units), and the three axes of a 3D view in one unit
  span within a factor SAME_UNIT_RATIO of each other, so that a constant quantity is a
  flat line with its value (flat.py), not noise blown up to fill the axes;
- frames: a picture of bodies (3D axes in metres, or any animation) tags its bodies, its
  view fits them (along every axis what is drawn of the bodies, with the nearest point of
  each plane in view, spans at least FIT_MIN of the view, or of FLOOR of its longest side:
  no cube around a strip, no ±10 m around a door; no body a speck below SPECK of it), the scene's planes and hinge axes are drawn where the scene
  puts them and inside the view, a 3D plane is painted under the bodies (fixed order, not
  mplot3d's depth sort, which paints a plane across a box resting on it), and the picture
  fills its frame (its axes reach across at least FILL_MIN of the figure along one side, a
  GIF has at least MIN_PIXELS on its long side);
- stub: a figure of a stub run (its summary's "stub") says so on the figure (tools/pattern
  stubfigs draws the skeletons' runs, where the report only draws the solutions').

Each check returns findings, one line each: the figure, what is wrong, what to do.
"""
import math
import os
import re

# "diverged", "diverges", not "divergence" (of a flow: the smoke figure's div u).
DIVERGED_WORDS = re.compile(r"\bdiverg(?:e|ed|es|ing)\b|blew up|blow-up|blows up|blown up",
                            re.I)
STUB_WORDS = re.compile(r"\bstub", re.I)
ROUNDING_VIEW = 1e-9
SAME_UNIT_RATIO = 1e6
FIT_MIN = 0.4
FLOOR = 0.3  # a view keeps this fraction of its largest side on every side (scene3d.view_box)
SPECK = 0.03
FILL_MIN = 0.5
MIN_PIXELS = 480
GEOMETRY_TOL = 1e-6  # of the view's span: how far a drawn plane or hinge may sit off its place


def _name(facts):
    return os.path.basename(facts["path"])


def check_diverged(facts, diverged_runs):
    """diverged_runs: how many runs of the figure's scene diverged by their summaries."""
    if diverged_runs:
        return []
    out = []
    said = [t for t in facts["texts"] if DIVERGED_WORDS.search(t)]
    if said:
        out.append(f"{_name(facts)}: says \"{said[0][:80]}\" but no run of its scene diverged "
                   "(their summaries say ok): take 'diverged' from the summaries (--summary, "
                   "--diverged), never from a rule of the figure's own")
    for fr in facts["frames"][:1]:
        for ax in fr["axes"]:
            if "symlog" in (ax["yscale"], ax["xscale"]):
                out.append(f"{_name(facts)}: a symmetric-log axis ('{ax['ylabel'][:40]}') on a "
                           "scene whose runs stayed ok: draw it linear, constant parts flat "
                           "(flat.py)")
    return out


def _unit(label):
    m = re.search(r"\(([^()]*)\)\s*$", label or "")
    return m.group(1).strip() if m else None


def _span_problem(lo, hi):
    span, mag = abs(hi - lo), max(abs(lo), abs(hi))
    if span < ROUNDING_VIEW * max(mag, 1.0):
        return f"spans {span:.2g} around {0.5 * (lo + hi):.6g}"
    return ""


def check_rounding(facts):
    out = []
    for k, fr in enumerate(facts["frames"][:1] + facts["frames"][-1:] if len(
            facts["frames"]) > 1 else facts["frames"]):
        for ax in fr["axes"]:
            if not ax["drawn"]:
                continue
            dims = [("x", ax["xlim"], ax["xscale"], ax["xlabel"]),
                    ("y", ax["ylim"], ax["yscale"], ax["ylabel"])]
            if ax["is3d"]:
                dims.append(("z", ax["zlim"], ax["zscale"], ax["zlabel"]))
            for d, lim, scale, label in dims:
                if scale != "linear":
                    continue
                why = _span_problem(*lim)
                if why:
                    out.append(f"{_name(facts)}: axis '{label or d}' {why}: it shows rounding "
                               "noise; draw a quantity constant to rounding flat, with its "
                               "value (flat.py)")
            if ax["is3d"]:
                units = {_unit(lab) for _, _, _, lab in dims}
                spans = [abs(lim[1] - lim[0]) for _, lim, _, _ in dims]
                if len(units) == 1 and None not in units and min(spans) > 0 and \
                        max(spans) / min(spans) > SAME_UNIT_RATIO:
                    out.append(f"{_name(facts)}: its 3D axes share the unit '{units.pop()}' "
                               f"but span from {min(spans):.2g} to {max(spans):.2g}: the "
                               "short one is noise blown up; draw the three at one scale")
    return list(dict.fromkeys(out))


def _box(ax):
    lims = [ax["xlim"], ax["ylim"]] + ([ax["zlim"]] if ax["is3d"] else [])
    return [min(l) for l in lims], [max(l) for l in lims]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def is_frame_figure(facts):
    """A picture of bodies: an animation, or a figure with 3D axes in metres, or one that
    tagged bodies."""
    if facts["path"].endswith(".gif"):
        return True
    for fr in facts["frames"]:
        for ax in fr["axes"]:
            if any(t["kind"] == "body" for t in ax["tags"]):
                return True
            if ax["is3d"] and _unit(ax["xlabel"]) == "m" and _unit(ax["zlabel"]) == "m":
                return True
    return False


def _merged(frames):
    """An animation whose view stays put is judged as one picture: its bodies over all its
    frames (the view holds the whole run), its geometry from the first frame."""
    if len(frames) < 2:
        return frames
    first = frames[0]
    if any(len(f["axes"]) != len(first["axes"]) or any(
            (a["xlim"], a["ylim"], a.get("zlim")) != (b["xlim"], b["ylim"], b.get("zlim"))
            for a, b in zip(f["axes"], first["axes"])) for f in frames):
        return frames
    axes = []
    for i, ax in enumerate(first["axes"]):
        bodies = [t for f in frames for t in f["axes"][i]["tags"] if t["kind"] == "body"]
        pts = [p for t in bodies for p in t["points"]]
        union = dict(bodies[0], points=pts) if bodies else None
        sizes = [t for t in bodies]  # each drawing keeps its own size for the speck test
        tags = [t for t in ax["tags"] if t["kind"] != "body"] + sizes
        if union is not None:
            tags.append(union)
        axes.append(dict(ax, tags=tags))
    return [dict(first, axes=axes)]


def check_frames(facts, scene=None):
    """Fit, fixed geometry and frame size of a picture of bodies (see the module's doc)."""
    if not is_frame_figure(facts):
        return []
    out = []
    name = _name(facts)
    gif = name.endswith(".gif")
    frames = _merged(facts["frames"])
    bodies_anywhere = False
    for k, fr in enumerate(frames):
        # Panels that share one view (one per sampled time) hold the bodies together.
        shared = {}
        for ax in fr["axes"]:
            shared.setdefault(_box(ax).__repr__(), []).extend(
                p for t in ax["tags"] if t["kind"] == "body" for p in t["points"]
                if all(math.isfinite(c) for c in p))
        for ax in fr["axes"]:
            bodies = [t for t in ax["tags"] if t["kind"] == "body"]
            if not bodies:
                continue
            bodies_anywhere = True
            lo, hi = _box(ax)
            view = max(h - l for l, h in zip(lo, hi))
            pts = shared[_box(ax).__repr__()]
            if pts and view > 0:
                # What the view must hold: the bodies, and the point of each plane drawn in
                # view nearest to them (a floor a ball rests on or floats above).
                mid = [(max(p[i] for p in pts) + min(p[i] for p in pts)) / 2
                       for i in range(len(lo))]
                held = list(pts)
                for t in ax["tags"]:
                    if t["kind"] == "plane":
                        o, n = t["point"], t["normal"]
                        dd = _dot([c - oo for c, oo in zip(mid, o)], n)
                        q = [c - dd * nn for c, nn in zip(mid, n)]
                        if all(l <= c <= h for c, l, h in zip(q, lo, hi)):
                            held.append(q)
                ext = [max(p[i] for p in held) - min(p[i] for p in held) for i in range(len(lo))]
                for i, axis in enumerate("xyz"[:len(lo)]):
                    allowed = max(ext[i], FLOOR * max(ext)) / FIT_MIN
                    if hi[i] - lo[i] > allowed:
                        out.append(f"{name}: the view spans {hi[i] - lo[i]:.3g} m along {axis} "
                                   f"where the bodies span {ext[i]:.3g} m: fit the view to the "
                                   "bodies' extent (scene3d.view_box)")
                sizes = []
                for t in bodies:
                    q = [p for p in t["points"] if all(math.isfinite(c) for c in p)]
                    if len(q) > 1:
                        sizes.append(max(max(p[i] for p in q) - min(p[i] for p in q)
                                         for i in range(len(lo))))
                if sizes and max(sizes) < SPECK * view:
                    out.append(f"{name}: each body is drawn {max(sizes):.3g} m across in a "
                               f"{view:.3g} m view: a speck")
            tol = GEOMETRY_TOL * max(view, 1e-9)
            for t in ax["tags"]:
                if t["kind"] == "plane":
                    o, n = t["point"], t["normal"]
                    off = max(abs(_dot([c - oo for c, oo in zip(p, o)], n)) for p in t["points"])
                    if off > tol:
                        out.append(f"{name}: plane {t['index']} is drawn {off:.3g} m off the "
                                   "plane the scene gives")
                    if ax["is3d"]:
                        outside = [p for p in t["points"] if any(
                            c < l - tol or c > h + tol for c, l, h in zip(p, lo, hi))]
                        if outside:
                            out.append(f"{name}: plane {t['index']} is drawn outside the view "
                                       "(clip it to the view box: scene3d.plane_polygon)")
                        if ax.get("computed_zorder", True) or t["zorder"] >= min(
                                b["zorder"] for b in bodies):
                            out.append(f"{name}: plane {t['index']} may be painted over the "
                                       "bodies (mplot3d's own depth order): draw planes first, "
                                       "computed_zorder off (scene3d.setup)")
                if t["kind"] == "hinge" and t.get("axis") is not None:
                    a, u = t["anchor"], t["axis"]
                    for p in t["points"]:
                        d = [c - aa for c, aa in zip(p, a)]
                        along = _dot(d, u)
                        off = math.sqrt(max(_dot(d, d) - along * along, 0.0))
                        if off > tol:
                            out.append(f"{name}: hinge {t['index']} is drawn {off:.3g} m off "
                                       "its axis")
                            break
            if scene is not None and k == 0:
                want = {("plane", i) for i, _ in enumerate(scene.get("planes", []) or [])}
                want |= {("hinge", i) for i, _ in enumerate(scene.get("hinges", []) or [])}
                have = {(t["kind"], t.get("index")) for t in ax["tags"]}
                for kind, i in sorted(want - have):
                    out.append(f"{name}: the scene's {kind} {i} is not drawn")
        # The pictures' reach across the figure along its longer side (a picture of equal
        # aspect cannot fill both sides of a frame of another shape).
        boxes = [ax["position"] for ax in fr["axes"]
                 if any(t["kind"] == "body" for t in ax["tags"])]
        if boxes:
            reach = max(max(b[0] + b[2] for b in boxes) - min(b[0] for b in boxes),
                        max(b[1] + b[3] for b in boxes) - min(b[1] for b in boxes))
            if reach < FILL_MIN:
                out.append(f"{name}: the pictures of the bodies reach across {100 * reach:.0f} "
                           "% of the figure: give the axes the figure's room")
        px = pixel_size(facts["path"]) if gif and k == 0 else None
        if px and max(px) < MIN_PIXELS:
            out.append(f"{name}: {px[0]} x {px[1]} px: an animation needs at least "
                       f"{MIN_PIXELS} px on its long side")
    if not bodies_anywhere:
        out.append(f"{name}: a picture of bodies that tags none (figfacts.tag(artist, "
                   "'body', points)): the checks cannot see whether its view fits them")
    return list(dict.fromkeys(out))


def pixel_size(path):
    """(width, height) of a PNG or GIF file, from its header; None if unreadable."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if head[:6] in (b"GIF87a", b"GIF89a"):
        return int.from_bytes(head[6:8], "little"), int.from_bytes(head[8:10], "little")
    if head[:8] == b"\x89PNG\r\n\x1a\n":
        return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
    return None


def check_stub(facts, stub):
    if stub and not any(STUB_WORDS.search(t) for t in facts["texts"]):
        return [f"{_name(facts)}: a figure of a stub run (its summary says \"stub\") that does "
                "not say so: draw it with --summary (runinfo.stamp marks it)"]
    return []


def check_figure(facts, diverged_runs=0, scene=None, stub=False):
    """Every check on one figure's facts."""
    return (check_diverged(facts, diverged_runs) + check_rounding(facts)
            + check_frames(facts, scene) + check_stub(facts, stub))


def diverged_count(runs):
    """How many runs of a scene diverged by their summaries: [(label, summary, why)] as the
    report keeps them (a sweep's summary counts its diverged runs)."""
    n = 0
    for _, s, _ in runs:
        if not s:
            continue
        if isinstance(s.get("diverged"), int) and "sweep" in s:
            n += s["diverged"]
        elif s.get("status") == "diverged":
            n += 1
    return n


def _diverged_rows(args):
    """Rows with status "diverged" in the CSV files a figure draws that carry a status
    column (a sweep, a plug-in's table): their runs' own verdicts."""
    import csv
    n = 0
    for a in args:
        if not (isinstance(a, str) and a.endswith(".csv") and os.path.isfile(a)):
            continue
        try:
            with open(a, encoding="utf-8", newline="") as f:
                rows = csv.DictReader(f)
                if "status" in (rows.fieldnames or []):
                    n += sum(1 for r in rows if (r.get("status") or "").strip() == "diverged")
        except (OSError, UnicodeDecodeError, csv.Error):
            continue
    return n


def check_section(sec, facts_by_path):
    """Findings over every figure of a lab's report section (tools/report, after the lab):
    each figure's facts with its scene's runs and scene, its caption counted as its words."""
    out = []
    for sc in sec.scenes:
        diverged = diverged_count(sc.runs)
        scene = sc.doc if isinstance(sc.doc, dict) else None
        for path, caption, args in sc.figures:
            facts = facts_by_path.get(os.path.abspath(path))
            if facts is None:
                continue
            facts = dict(facts, texts=facts["texts"] + [caption])
            out += [f"{sec.lab}/{f}" for f in check_figure(
                facts, diverged_runs=diverged + _diverged_rows(args),
                scene=scene if ("planes" in (scene or {}) or "hinges" in (scene or {})) else None)]
    return list(dict.fromkeys(out))
