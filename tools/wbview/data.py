"""Reads a run (trace, stats, summary, scene) into what the viewer page draws.

Every reader raises InputError with a complete message (the file, the row or key, what
was expected); tools/view prints it and exits 2."""
import json
import math
import os
from array import array

# Bad input (a complete message for the user, exit status 2): tools/plot's own class, so
# that tools/report catches the two tools' errors alike.
from wbplot.common import InputError  # noqa: F401 (re-exported)

TRACE_2D = ["t", "id", "x", "y", "vx", "vy"]
TRACE_3D = ["t", "id", "x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy",
            "wz"]
STATS_2D = ["step", "t", "energy", "kinetic", "potential", "px", "py"]
STATS_3D = ["step", "t", "energy", "kinetic", "potential", "px", "py", "pz", "Lx", "Ly", "Lz"]

# What the page keeps per particle or body and frame (docs/view.md, "Large runs"): a
# particle's velocity too, unless keeping it would thin the written steps (model.build).
KEEP_2D = ["x", "y", "vx", "vy"]
KEEP_3D = ["x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"]

# The rigid lab's contact rule: candidate points closer to a plane than this touch it
# (kContactSlop, framework/drivers/rigid/rigid_world.h). The viewer marks those points.
CONTACT_SLOP = 1e-3




def _read_bytes(path, what):
    if not os.path.exists(path):
        raise InputError(f"{path}: no such file (expected {what})")
    if os.path.isdir(path):
        raise InputError(f"{path}: is a folder, expected {what}")
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None


def _number(path, lineno, name, text):
    try:
        return float(text)
    except ValueError:
        shown = text.decode("utf-8", "replace") if isinstance(text, bytes) else text
        raise InputError(f"{path}: row {lineno}, column '{name}': got '{shown[:40]}', "
                         "expected a number") from None


class Trace:
    """One run's trace: `kind` "particles" (2D) or "rigid" (3D), `n` particles or bodies,
    `t` the written times, `frames` the values of KEEP_2D or KEEP_3D per frame and id
    (array of doubles, frame-major), `cols` their names."""

    def __init__(self, path, kind, n, t, cols, values):
        self.path, self.kind, self.n, self.t, self.cols, self.values = (
            path, kind, n, t, cols, values)

    @property
    def frames(self):
        return len(self.t)

    def at(self, k, i, col):
        return self.values[(k * self.n + i) * len(self.cols) + self.cols.index(col)]


CHUNK_ROWS = 200_000  # rows parsed at once: about 50 MB of temporary objects


def read_trace(path):
    """The trace CSV of any lab (docs/run-contract.md): the header tells the kind.

    Each block of whole written steps (about CHUNK_ROWS rows) is split into fields at
    once (a 10^4-particle run of 300 written steps is 3·10^6 rows); when a field count or
    a number is wrong, that block's rows are read one by one to name the first bad one."""
    if not os.path.exists(path):
        raise InputError(f"{path}: no such file (expected a trace CSV (the --out file of a run))")
    if os.path.isdir(path):
        raise InputError(f"{path}: is a folder, expected a trace CSV (the --out file of a run)")
    try:
        f = open(path, "rb")
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    with f:
        head = f.readline()
        header = [h.strip() for h in head.decode("utf-8", "replace").strip().split(",")]
        if header == TRACE_3D:
            kind, keep = "rigid", KEEP_3D
        elif header == TRACE_2D:
            kind, keep = "particles", KEEP_2D
        else:
            raise InputError(f"{path}: header is '{','.join(header)[:200]}', expected a run's "
                             f"trace: {','.join(TRACE_2D)} (particle labs) or "
                             f"{','.join(TRACE_3D)} (the rigid lab), docs/run-contract.md")
        width = len(header)
        cols = [header.index(c) for c in keep]
        # The particle count: rows up to the second id 0 (ids 0 ... n-1 each written step).
        first = []
        for line in f:
            if not line.strip():
                continue
            if first and line.split(b",", 2)[1:2] == [b"0"]:
                rest = [line]
                break
            first.append(line)
        else:
            rest = []
        if not first:
            raise InputError(f"{path}: no data rows after the header, expected at least one")
        n = len(first)
        per_chunk = max(1, CHUNK_ROWS // n) * n
        values, times = array("d"), []
        pending = first + rest
        lineno = 2  # of the first row in `pending`
        expected = [str(i).encode() for i in range(n)]
        while True:
            while len(pending) < per_chunk:
                more = f.readlines(1 << 24)
                if not more:
                    break
                pending += [x for x in more if x.strip()]
            if not pending:
                break
            block, pending = pending[:per_chunk], pending[per_chunk:]
            if len(block) % n:
                raise InputError(f"{path}: {lineno - 2 + len(block)} rows is not a whole number "
                                 f"of written steps of {n} ids (0 to {n - 1}, from the first "
                                 "step), docs/run-contract.md")
            _parse_block(path, block, lineno, header, width, n, expected, cols, values, times)
            lineno += len(block)
    for k in range(1, len(times)):
        if not times[k] > times[k - 1]:
            raise InputError(f"{path}: row {k * n + 2}: t = {times[k]!r} after t = "
                             f"{times[k - 1]!r}, expected written steps in increasing time")
    return Trace(path, kind, n, times, keep, values)


def _parse_block(path, block, lineno, header, width, n, expected, cols, values, times):
    """Whole written steps of rows (bytes lines) into `values` (kept columns) and `times`."""
    body = b"".join(block).replace(b"\r", b"").replace(b"\n", b",")
    fields = body.split(b",")
    if fields and fields[-1] == b"":
        fields.pop()
    if len(fields) != len(block) * width:
        _find_bad_row(path, block, lineno, header)
    ids, tcol = fields[1::width], fields[0::width]
    for k in range(len(block) // n):
        got = ids[k * n:(k + 1) * n]
        if got != expected:
            j = next(j for j in range(n) if got[j] != expected[j])
            raise InputError(f"{path}: row {lineno + k * n + j}: id "
                             f"{got[j].decode('utf-8', 'replace')}, expected {j} (each written "
                             f"step lists ids 0 to {n - 1} in order, docs/run-contract.md)")
        if len(set(tcol[k * n:(k + 1) * n])) != 1:
            raise InputError(f"{path}: rows {lineno + k * n} to {lineno + (k + 1) * n - 1} (one "
                             "written step) do not share one t")
        times.append(_number(path, lineno + k * n, "t", tcol[k * n]))
    try:
        per_col = [array("d", map(float, fields[c::width])) for c in cols]
    except ValueError:
        _find_bad_row(path, block, lineno, header)
        raise
    out = array("d", bytes(8 * len(cols) * len(block)))
    for j, col in enumerate(per_col):
        out[j::len(cols)] = col
    values.extend(out)


def _find_bad_row(path, block, lineno, header):
    """Raises InputError naming the first row of `block` with the wrong field count or a
    field that is not a number."""
    for k, line in enumerate(block):
        rec = line.rstrip(b"\r\n").split(b",")
        if len(rec) != len(header):
            raise InputError(f"{path}:{lineno + k}: {len(rec)} fields, expected {len(header)} "
                             f"(header '{','.join(header)}')")
        for name, text in zip(header, rec):
            _number(path, lineno + k, name, text)


def read_stats(path, kind):
    """{column: [floats]} of a --stats CSV of the trace's kind."""
    need = STATS_3D if kind == "rigid" else STATS_2D
    raw = _read_bytes(path, "a stats CSV (the --stats file of a run)").replace(b"\r", b"")
    text = raw.decode("utf-8", "replace").rstrip("\n")
    lines = text.split("\n")
    header = [h.strip() for h in lines[0].split(",")]
    missing = [c for c in need if c not in header]
    if missing:
        other = "a rigid" if kind != "rigid" else "a particle"
        hint = (f" (it looks like {other} lab's stats: the trace and the stats must come from "
                "one run)" if ("Lx" in header) != (kind == "rigid") else "")
        raise InputError(f"{path}: missing column '{missing[0]}' (header is "
                         f"'{','.join(header)[:200]}', expected {','.join(need)}){hint}")
    out = {c: [] for c in need}
    idx = [header.index(c) for c in need]
    for lineno, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        rec = line.split(",")
        if len(rec) != len(header):
            raise InputError(f"{path}:{lineno}: {len(rec)} fields, expected {len(header)}")
        for c, j in zip(need, idx):
            out[c].append(_number(path, lineno, c, rec[j].strip()))
    if not out["t"]:
        raise InputError(f"{path}: no data rows after the header, expected at least one")
    return out


def read_summary(path):
    """The run's summary: the last non-empty line of the file (a run's stdout saved with
    `> run-summary.json`, or the report's <scene>-summary.json) as a JSON object."""
    raw = _read_bytes(path, "a run's summary line (its stdout, saved to a file)")
    lines = [s for s in raw.decode("utf-8", "replace").splitlines() if s.strip()]
    if not lines:
        raise InputError(f"{path}: empty, expected a run's JSON summary line on its last line")
    try:
        s = json.loads(lines[-1])
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: the last line is not JSON ({e.msg}), expected the run's "
                         "summary line (the last line a run prints, docs/run-contract.md)"
                         ) from None
    if not isinstance(s, dict) or "status" not in s:
        raise InputError(f"{path}: the last line is not a run's summary (a JSON object with "
                         "\"status\", docs/run-contract.md)")
    return s


def read_scene(path):
    raw = _read_bytes(path, "a scene JSON file")
    try:
        doc = json.loads(raw.decode("utf-8", "replace"))
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: not JSON ({e.msg} at line {e.lineno})") from None
    if not isinstance(doc, dict):
        raise InputError(f"{path}: expected a scene (a JSON object), docs/scenes.md")
    return doc


# ----------------------------------------------------------------------------
# What the page draws of a scene


def _vec(v, size):
    if not isinstance(v, list) or len(v) != size:
        return None
    try:
        out = [float(c) for c in v]
    except (TypeError, ValueError):
        return None
    return out if all(math.isfinite(c) for c in out) else None


def _unit(v):
    if v is None:
        return None
    big = max(abs(c) for c in v)
    if not big > 0:
        return None
    v = [c / big for c in v]
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def _whole(x):
    return isinstance(x, int) and not isinstance(x, bool) or (
        isinstance(x, float) and x.is_integer())


def particle_scene(doc, n, scene_path):
    """The drawable parts of a particle scene: radii, springs, pins, planes, obstacles,
    centres of forces. The particle count must be the trace's."""
    radii, count = [], 0
    for p in doc.get("particles", []) or []:
        r = p.get("radius", 0) if isinstance(p, dict) else 0
        radii.append(float(r) if isinstance(r, (int, float)) else 0.0)
    for e in doc.get("emitters", []) or []:
        c = e.get("count") if isinstance(e, dict) else None
        if not _whole(c) or c < 0:
            raise InputError(f"{scene_path}: emitters: a count that is not a whole number "
                             f"({c!r}): is this the scene of the run?")
        r = e.get("radius", 0)
        radii += [float(r) if isinstance(r, (int, float)) else 0.0] * int(c)
    springs, anchored, pinned = [], [], []
    rope, cloth = doc.get("rope"), doc.get("cloth")
    first = len(radii)
    if isinstance(rope, dict) and _whole(rope.get("beads")):
        beads = int(rope["beads"])
        radii += [0.0] * beads
        springs += [(first + q - 1, first + q) for q in range(1, beads)]
        pin = rope.get("pin", "start")
        if pin != "none":
            pinned.append(first)
        if pin == "ends":
            pinned.append(first + beads - 1)
        first += beads
    if isinstance(cloth, dict) and _whole(cloth.get("rows")) and _whole(cloth.get("cols")):
        R, C = int(cloth["rows"]), int(cloth["cols"])
        radii += [0.0] * (R * C)
        k = cloth.get("k", 0)
        ks, kb = cloth.get("k_shear", k), cloth.get("k_bend", 0)

        def idx(r, q):
            return first + r * C + q
        for r in range(R):
            for q in range(C):
                if k and q + 1 < C:
                    springs.append((idx(r, q), idx(r, q + 1)))
                if k and r + 1 < R:
                    springs.append((idx(r, q), idx(r + 1, q)))
                if ks and r + 1 < R and q + 1 < C:
                    springs += [(idx(r, q), idx(r + 1, q + 1)), (idx(r, q + 1), idx(r + 1, q))]
                if kb and q + 2 < C:
                    springs.append((idx(r, q), idx(r, q + 2)))
                if kb and r + 2 < R:
                    springs.append((idx(r, q), idx(r + 2, q)))
        pin = cloth.get("pin", "corners")
        if pin == "corners":
            pinned += [idx(0, 0), idx(0, C - 1)]
        elif pin == "top":
            pinned += [idx(0, q) for q in range(C)]
    if len(radii) != n:
        raise InputError(f"{scene_path}: declares {len(radii)} particles, the trace has {n}: "
                         "give --scene the scene file of the run")
    for p in doc.get("pinned", []) or []:
        if _whole(p) and 0 <= p < n:
            pinned.append(int(p))
    planes, discs, marks = [], [], []
    for pl in doc.get("planes", []) or []:
        if not isinstance(pl, dict):
            continue
        point, normal = _vec(pl.get("point"), 2), _unit(_vec(pl.get("normal"), 2))
        if point and normal:
            th = pl.get("thickness")
            planes.append({"point": point, "normal": normal,
                           "thickness": float(th) if isinstance(th, (int, float)) else None})
    for f in doc.get("forces", []) or []:
        if not isinstance(f, dict):
            continue
        kind = f.get("type")
        if kind == "spring" and _whole(f.get("i")):
            i = int(f["i"])
            if _whole(f.get("j")):
                springs.append((i, int(f["j"])))
            elif _vec(f.get("anchor"), 2):
                anchored.append([i] + _vec(f["anchor"], 2))
        elif kind == "attractor":
            marks.append({"at": _vec(f.get("center", [0, 0]), 2), "label": "attractor"})
        elif kind == "vortex":
            c = _vec(f.get("center", [0, 0]), 2)
            marks.append({"at": c, "label": "vortex core", "radius": f.get("core")})
        elif kind == "boids" and f.get("goal_weight"):
            marks.append({"at": _vec(f.get("goal", [0, 0]), 2), "label": "goal"})
        elif kind == "curl-noise":
            for o in f.get("obstacles", []) or []:
                c = _vec(o.get("center") if isinstance(o, dict) else None, 2)
                if c and isinstance(o.get("radius"), (int, float)):
                    discs.append({"center": c, "radius": float(o["radius"])})
    springs = [s for s in springs if 0 <= s[0] < n and 0 <= s[1] < n]
    anchored = [a for a in anchored if 0 <= a[0] < n]
    return {"radii": radii, "springs": springs, "anchored": anchored,
            "pinned": sorted(set(pinned)), "planes": planes, "discs": discs,
            "marks": [m for m in marks if m["at"] is not None]}


def rigid_scene(doc, n, scene_path):
    """The drawable parts of a rigid scene: shapes, planes, hinges, the up direction."""
    bodies = doc.get("bodies")
    if not isinstance(bodies, list):
        raise InputError(f"{scene_path}: expected a rigid scene with a 'bodies' array "
                         "(the trace is the rigid lab's)")
    if len(bodies) != n:
        raise InputError(f"{scene_path}: declares {len(bodies)} bodies, the trace has {n}: "
                         "give --scene the scene file of the run")
    shapes = []
    for b in bodies:
        b = b if isinstance(b, dict) else {}
        kind = b.get("shape")
        if kind == "box" and _vec(b.get("size"), 3):
            shapes.append({"shape": "box", "size": _vec(b["size"], 3)})
        elif kind == "sphere" and isinstance(b.get("radius"), (int, float)):
            shapes.append({"shape": "sphere", "radius": float(b["radius"])})
        elif kind == "cylinder" and isinstance(b.get("radius"), (int, float)) \
                and isinstance(b.get("length"), (int, float)):
            shapes.append({"shape": "cylinder", "radius": float(b["radius"]),
                           "length": float(b["length"])})
        else:
            shapes.append({"shape": "unknown"})
    planes = []
    for pl in doc.get("planes", []) or []:
        if isinstance(pl, dict) and _unit(_vec(pl.get("normal"), 3)):
            planes.append({"point": _vec(pl.get("point", [0, 0, 0]), 3) or [0, 0, 0],
                           "normal": _unit(_vec(pl["normal"], 3))})
    hinges = []
    for h in doc.get("hinges", []) or []:
        if isinstance(h, dict) and _whole(h.get("body")) and 0 <= h["body"] < n \
                and _vec(h.get("anchor"), 3):
            hinges.append({"body": int(h["body"]), "anchor": _vec(h["anchor"], 3),
                           "axis": _unit(_vec(h.get("axis"), 3))})
    g = [0.0, 0.0, 0.0]
    for f in doc.get("forces", []) or []:
        if isinstance(f, dict) and f.get("type") == "gravity" and _vec(f.get("g"), 3):
            g = [a + b for a, b in zip(g, _vec(f["g"], 3))]
    up = _unit([-c for c in g]) if any(g) else (planes[0]["normal"] if planes else [0, 0, 1])
    return {"shapes": shapes, "planes": planes, "hinges": hinges, "up": up,
            "contact_slop": CONTACT_SLOP}
