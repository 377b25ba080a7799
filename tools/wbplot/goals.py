"""The measured goals of the constraint scenes (issue 21; handouts/rigid.md#r6, #r7,
handouts/collisions.md#c5): each goal runs a scene with the solution executable, reads
its trace and stats, and compares one number with its bound. tools/goals prints them;
tools/report draws them into its tables; ctest runs tools/goals (label solution)."""
import csv
import json
import math
import os
import subprocess

G = 9.81
SLOP = 1e-3  # m: kContactSlop (framework/drivers/rigid/rigid_world.h)


# ----------------------------------------------------------------------------
# Reading runs


def run(exe, scene, out_dir, stem, every=1, extra=()):
    """Runs exe on scene writing <stem>.csv and <stem>-stats.csv; returns the summary."""
    trace = os.path.join(out_dir, stem + ".csv")
    stats = os.path.join(out_dir, stem + "-stats.csv")
    argv = [exe, "--scene", scene, "--out", trace, "--stats", stats, "--every", str(every)]
    argv += list(extra)
    p = subprocess.run(argv, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)}: exit {p.returncode}: {p.stderr.strip()}")
    return json.loads(p.stdout.strip().splitlines()[-1]), trace, stats


def read_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        r = csv.reader(f)
        head = next(r)
        cols = {h: [] for h in head}
        for row in r:
            for h, v in zip(head, row):
                cols[h].append(float(v))
    return cols


def bodies(trace):
    """{id: {column: [...]}} of a trace (rigid or particle)."""
    cols = read_rows(trace)
    out = {}
    for k, b in enumerate(cols["id"]):
        d = out.setdefault(int(b), {c: [] for c in cols if c != "id"})
        for c in d:
            d[c].append(cols[c][k])
    return out


def rot(qw, qx, qy, qz):
    n = math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    w, x, y, z = qw / n, qx / n, qy / n, qz / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def mul(R, p):
    return [sum(R[i][j] * p[j] for j in range(3)) for i in range(3)]


def mul_t(R, p):
    return [sum(R[j][i] * p[j] for j in range(3)) for i in range(3)]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(a):
    return math.sqrt(dot(a, a))


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = norm(a)
    return [x / n for x in a]


def state(d, k):
    x = [d["x"][k], d["y"][k], d["z"][k]]
    R = rot(d["qw"][k], d["qx"][k], d["qy"][k], d["qz"][k])
    v = [d["vx"][k], d["vy"][k], d["vz"][k]]
    w = [d["wx"][k], d["wy"][k], d["wz"][k]]
    return x, R, v, w


def corners(size):
    return [[sx * size[0] / 2, sy * size[1] / 2, sz * size[2] / 2]
            for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def lowest(d, k, size, point, n):
    """The smallest height of the box's corners above the plane (m) at row k."""
    x, R, _, _ = state(d, k)
    return min(dot(sub([a + b for a, b in zip(x, mul(R, c))], point), n) for c in corners(size))


# ----------------------------------------------------------------------------
# The goals. Each returns a list of (goal, measured, bound, holds).


def _goal(name, value, op, bound):
    ok = value < bound if op == "<" else value <= bound if op == "<=" else value > bound
    return {"goal": name, "value": value, "op": op, "bound": bound, "holds": bool(ok)}


def rigid_box_rest(doc, d, stats):
    size = doc["bodies"][0]["size"]
    n, point = doc["planes"][0]["normal"], doc["planes"][0].get("point", [0, 0, 0])
    t = d["t"]
    land = next(k for k in range(len(t)) if lowest(d, k, size, point, n) <= SLOP)
    t0 = t[land] + 1.0
    window = [k for k in range(len(t)) if t0 <= t[k] <= t0 + 10.0]
    if not window or t[window[-1]] < t0 + 10.0 - 1e-9:
        raise RuntimeError("box-rest: the run ends before 11 s after landing")
    k0 = window[0]
    speed = max(norm(state(d, k)[2]) for k in window)
    spin = max(norm(state(d, k)[3]) for k in window)
    pen = max(-lowest(d, k, size, point, n) for k in window)
    side = max(math.hypot(d["x"][k] - d["x"][k0], d["y"][k] - d["y"][k0]) for k in window)
    e = stats["energy"]
    ks = [k for k in range(len(stats["t"])) if stats["t"][k] >= t0 and stats["t"][k] <= t0 + 10]
    gain = max(e[k] - e[ks[0]] for k in ks)
    return [_goal("box-rest: largest speed from 1 s after landing, for 10 s (m/s)", speed, "<",
                  1e-6),
            _goal("box-rest: largest angular speed, same window (rad/s)", spin, "<", 1e-6),
            _goal("box-rest: deepest penetration, same window (m; the slop is 1e-3)", pen, "<",
                  SLOP),
            _goal("box-rest: largest energy gain over the window (J)", gain, "<=", 1e-9),
            _goal("box-rest: sideways drift over the window (m)", side, "<", 1e-6)]


def _slope(doc):
    n = unit(doc["planes"][0]["normal"])
    down = unit(sub([0, 0, -1], [c * dot([0, 0, -1], n) for c in n]))  # fall line
    theta = math.acos(n[2])
    return n, down, theta


def rigid_slope_stick(doc, d, stats):
    n, down, theta = _slope(doc)
    t = d["t"]
    ks = [k for k in range(len(t)) if 1.0 <= t[k] <= 11.0]
    x0 = state(d, ks[0])[0]
    disp = max(abs(dot(sub(state(d, k)[0], x0), down)) for k in ks)
    mu = doc["contact"]["friction"]
    return [_goal(f"slope-stick: mu = {mu:g} > tan(theta) = {math.tan(theta):.3f}",
                  mu - math.tan(theta), ">", 0),
            _goal("slope-stick: displacement along the slope from 1 s to 11 s (m)", disp, "<",
                  1e-6)]


def rigid_slope_slide(doc, d, stats):
    n, down, theta = _slope(doc)
    mu = doc["contact"]["friction"]
    t = d["t"]
    ks = [k for k in range(len(t)) if t[k] >= 0.5]
    # Least-squares fit s(t) = s0 + v0 t + a t^2 / 2 on the distance along the fall line.
    s = [dot(state(d, k)[0], down) for k in ks]
    ts = [t[k] for k in ks]
    a = _quadratic(ts, s)
    expected = G * (math.sin(theta) - mu * math.cos(theta))
    return [_goal(f"slope-slide: mu = {mu:g} < tan(theta) = {math.tan(theta):.3f}",
                  math.tan(theta) - mu, ">", 0),
            _goal(f"slope-slide: |a / (g (sin - mu cos)) - 1|, a measured {a:.6g} m/s^2, "
                  f"expected {expected:.6g}", abs(a / expected - 1), "<", 0.01)]


def _quadratic(ts, ys):
    """The second-derivative of the least-squares parabola through (ts, ys)."""
    n = len(ts)
    m = sum(ts) / n
    u = [t - m for t in ts]
    S = [[sum(x ** (i + j) for x in u) for j in range(3)] for i in range(3)]
    b = [sum(y * x ** i for x, y in zip(u, ys)) for i in range(3)]
    # Solve the 3x3 normal equations (Cramer).
    def det(M):
        return (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
                - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
    D = det(S)
    M2 = [row[:] for row in S]
    for i in range(3):
        M2[i][2] = b[i]
    return 2 * det(M2) / D


def _hinge_errors(doc, d, t_max=10.0):
    hg = doc["hinges"][0]
    b0 = doc["bodies"][0]
    x0, R0 = b0.get("x", [0, 0, 0]), _q(b0.get("q", [1, 0, 0, 0]))
    anchor = hg["anchor"]
    r_body = mul_t(R0, sub(anchor, x0))
    axis = unit(hg["axis"])
    axis_body = mul_t(R0, axis)
    worst_angle = worst_anchor = 0.0
    for k in range(len(d["t"])):
        if d["t"][k] > t_max + 1e-9:
            break
        x, R, _, _ = state(d, k)
        u = mul(R, axis_body)
        worst_angle = max(worst_angle, math.atan2(norm(cross(u, axis)), dot(u, axis)))
        worst_anchor = max(worst_anchor, norm(sub([a + b for a, b in zip(x, mul(R, r_body))],
                                                  anchor)))
    return worst_angle, worst_anchor


def _q(q):
    return rot(*q)


def _energy_spread(stats, skip=1):
    e = stats["energy"][skip:]
    scale = max(abs(v) for v in e)
    return (max(e) - min(e)) / scale


def rigid_revolute(name):
    def check(doc, d, stats):
        angle, anchor = _hinge_errors(doc, d)
        out = [_goal(f"{name}: largest angle between the body's axis and the hinge axis, "
                     "first 10 s (rad)", angle, "<", 1e-3),
               _goal(f"{name}: largest distance of the pinned point from the anchor, first "
                     "10 s (m)", anchor, "<", 1e-4),
               _goal(f"{name}: energy spread (max - min) / max |E| after the first step",
                     _energy_spread(stats), "<", 1e-2)]
        if name == "revolute-pendulum":
            out.append(_period_goal(doc, d))
        return out
    return check


def _period_goal(doc, d):
    b = doc["bodies"][0]
    a, bb, c = b["size"]
    m = b["m"]
    hg = doc["hinges"][0]
    x0, R0 = b["x"], _q(b["q"])
    dvec = sub(x0, hg["anchor"])
    axis = unit(hg["axis"])
    # Inertia about the axis: the box's tensor about its centre along the axis (body frame),
    # plus m times the squared distance of the centre from the axis (parallel axis).
    ab = mul_t(R0, axis)
    I_c = m / 12 * ((bb * bb + c * c) * ab[0] ** 2 + (a * a + c * c) * ab[1] ** 2
                    + (a * a + bb * bb) * ab[2] ** 2)
    dperp = sub(dvec, [dot(dvec, axis) * u for u in axis])
    dist = norm(dperp)
    I_a = I_c + m * dist * dist
    theta0 = math.asin(min(1.0, abs(dperp[0]) / dist))
    T0 = 2 * math.pi * math.sqrt(I_a / (m * G * dist)) * (1 + theta0 ** 2 / 16)
    # Zero crossings of the centre's x, downward (interpolated).
    t, xs = d["t"], d["x"]
    cross_t = [t[k - 1] + (t[k] - t[k - 1]) * xs[k - 1] / (xs[k - 1] - xs[k])
               for k in range(1, len(t)) if xs[k - 1] > 0 >= xs[k]]
    T = (cross_t[-1] - cross_t[0]) / (len(cross_t) - 1)
    return _goal(f"revolute-pendulum: |T / T0 - 1|, T measured {T:.6g} s, closed form "
                 f"{T0:.6g} s", abs(T / T0 - 1), "<", 0.01)


RIGID = {"box-rest": rigid_box_rest, "slope-stick": rigid_slope_stick,
         "slope-slide": rigid_slope_slide, "door": rigid_revolute("door"),
         "wheel": rigid_revolute("wheel"),
         "revolute-pendulum": rigid_revolute("revolute-pendulum")}


# ----------------------------------------------------------------------------
# Collisions


def collisions_column(doc, d, stats):
    r = max(p.get("radius", 0) for p in doc["particles"])
    x0 = doc["particles"][0]["x"][0]
    t = next(iter(d.values()))["t"]
    late = [k for k in range(len(t)) if t[k] >= 1.0]
    speed = max(math.hypot(p["vx"][k], p["vy"][k]) for p in d.values() for k in late)
    off = max(abs(p["x"][k] - x0) for p in d.values() for k in range(len(t)))
    return [_goal("column: largest speed of any disc after 1 s (m/s)", speed, "<", 1e-3),
            _goal("column: largest sideways distance of a disc from the column's axis (m; "
                  f"a radius is {r:g})", off, "<", r)]


def collisions_pile(doc, d, stats):
    """Every disc at the end within one radius of a disc or a wall (nothing flies above the
    surface), from the last row of the trace."""
    k = len(next(iter(d.values()))["t"]) - 1
    xs = [(p["x"][k], p["y"][k]) for p in d.values()]
    radius = doc["emitters"][0]["radius"]
    cell = 4 * radius
    grid = {}
    for i, (x, y) in enumerate(xs):
        grid.setdefault((math.floor(x / cell), math.floor(y / cell)), []).append(i)
    planes = [(p["point"], unit(p["normal"])) for p in doc["planes"]]
    worst = 0.0
    for i, (x, y) in enumerate(xs):
        gap = min((x - p[0]) * n[0] + (y - p[1]) * n[1] - radius for p, n in planes)
        cx, cy = math.floor(x / cell), math.floor(y / cell)
        for gx in (cx - 1, cx, cx + 1):
            for gy in (cy - 1, cy, cy + 1):
                for j in grid.get((gx, gy), ()):
                    if j != i:
                        gap = min(gap, math.hypot(x - xs[j][0], y - xs[j][1]) - 2 * radius)
        worst = max(worst, gap)
    return [_goal("pile: largest gap between a disc and its nearest disc or wall at the end "
                  f"(m; a radius is {radius:g})", worst, "<=", radius)]


COLLISIONS = {"column": collisions_column, "pile": collisions_pile}
GOALS = {"rigid": RIGID, "collisions": COLLISIONS}


def every(lab, stem):
    return 1 if stem != "pile" else 100000


def measure(lab, stem, exe, scene, out_dir):
    with open(scene, encoding="utf-8") as f:
        doc = json.load(f)
    _, trace, stats = run(exe, scene, out_dir, f"goals-{stem}", every=every(lab, stem))
    traced = bodies(trace)
    return GOALS[lab][stem](doc, traced[0] if lab == "rigid" else traced, read_rows(stats))
