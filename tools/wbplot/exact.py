"""Closed-form motions of the scenes that have one, for overlays and claims.

- "exact": "oscillator" (one particle on a zero-rest-length spring to an anchor):
  x(t) = c + (x0 - c) cos wt + (v0 / w) sin wt, w = sqrt(k/m);
- "exact": "kepler" (one attractor, bound orbits): the f and g functions of Kepler's problem;
- a scene whose only force is uniform gravity: the parabola x0 + v0 t + g t^2 / 2.
Each function returns None when the scene is not of its kind (docs/report.md)."""
import math


def _particles(doc):
    out = []
    for p in doc.get("particles", []) or []:
        try:
            out.append(((float(p["x"][0]), float(p["x"][1])),
                        (float(p["v"][0]), float(p["v"][1])), float(p["m"])))
        except (KeyError, IndexError, TypeError, ValueError):
            return None
    return out or None


def _forces(doc):
    return [f for f in doc.get("forces", []) or [] if isinstance(f, dict)]


def parabola(doc):
    forces = _forces(doc)
    parts = _particles(doc)
    if parts is None or doc.get("emitters") or len(forces) != 1 or forces[0].get("type") != "gravity":
        return None
    try:
        gx, gy = (float(c) for c in forces[0]["g"])
    except (KeyError, TypeError, ValueError):
        return None

    def at(i, t):
        (x, y), (vx, vy), _ = parts[i]
        return x + vx * t + 0.5 * gx * t * t, y + vy * t + 0.5 * gy * t * t
    return at


def oscillator(doc):
    if doc.get("exact") != "oscillator":
        return None
    parts = _particles(doc)
    springs = [f for f in _forces(doc) if f.get("type") == "spring"]
    if parts is None or len(parts) != 1 or len(springs) != 1 or "anchor" not in springs[0]:
        return None
    try:
        cx, cy = (float(c) for c in springs[0]["anchor"])
        w = math.sqrt(float(springs[0]["k"]) / parts[0][2])
    except (KeyError, TypeError, ValueError):
        return None
    (x, y), (vx, vy), _ = parts[0]

    def at(i, t):
        c, s = math.cos(w * t), math.sin(w * t)
        return cx + (x - cx) * c + vx / w * s, cy + (y - cy) * c + vy / w * s
    at.period = 2 * math.pi / w
    return at


def kepler(doc):
    if doc.get("exact") != "kepler":
        return None
    parts = _particles(doc)
    att = [f for f in _forces(doc) if f.get("type") == "attractor"]
    if parts is None or len(att) != 1:
        return None
    try:
        cx, cy = (float(c) for c in att[0].get("center", [0.0, 0.0]))
        gm = float(att[0]["GM"])
    except (KeyError, TypeError, ValueError):
        return None
    orbits = []
    for (x, y), (vx, vy), _ in parts:
        rx, ry = x - cx, y - cy
        r0 = math.hypot(rx, ry)
        inv_a = 2 / r0 - (vx * vx + vy * vy) / gm
        if not (r0 > 0 and inv_a > 0):
            return None  # only bound orbits
        a = 1 / inv_a
        orbits.append((rx, ry, vx, vy, r0, a, math.sqrt(gm / a ** 3),
                       (rx * vx + ry * vy) / math.sqrt(gm * a)))

    def at(i, t):
        rx, ry, vx, vy, r0, a, n, sigma = orbits[i]
        period = 2 * math.pi / n
        t = math.fmod(t, period)
        m = n * t
        e0 = 1 - r0 / a

        def kep(d):  # n t as a function of the eccentric-anomaly change d
            return d - e0 * math.sin(d) + sigma * (1 - math.cos(d))
        lo, hi = m - 2.0, m + 2.0  # |kep(d) - d| <= e0 + |sigma| < 2 for a bound orbit
        d = m
        for _ in range(100):
            fd = kep(d) - m
            if abs(fd) < 1e-15:
                break
            if fd > 0:
                hi = d
            else:
                lo = d
            step = fd / (1 - e0 * math.cos(d) + sigma * math.sin(d))
            d = d - step if lo < d - step < hi else 0.5 * (lo + hi)
        f = 1 - a / r0 * (1 - math.cos(d))
        g = t - (d - math.sin(d)) / n
        return cx + f * rx + g * vx, cy + f * ry + g * vy
    at.period = max(2 * math.pi / o[6] for o in orbits)
    return at


def motion(doc):
    """(kind, at(i, t) -> (x, y)) of the scene's closed-form motion, or (None, None).
    at.period, when set, is the time after which the motion repeats (closed curves)."""
    for kind, fn in (("parabola", parabola), ("oscillator", oscillator), ("kepler", kepler)):
        at = fn(doc)
        if at is not None:
            return kind, at
    return None, None
