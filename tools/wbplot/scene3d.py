"""A 3D view of bodies with the scene's fixed geometry where it is (rigid-frames,
rigid-animate).

- The view is fitted to what is drawn of the bodies (outlines and paths), at one scale on
  the three axes, never to the planes (they are infinite) or to a cube around the origin.
- A plane is drawn as its intersection with that view box, a polygon lying exactly in it;
  a hinge as the part of its axis line inside the box, through its anchor (dashed, with
  the anchor marked).
- mplot3d sorts artists by depth on its own and may paint a translucent plane over a body
  resting on it; here the order is fixed (planes first, bodies last) and the camera looks
  from the open side of every plane, so a plane is never drawn across a body.
Every drawing is tagged (figfacts.tag) for the report's checks (figcheck.py).
"""
import math

from .figfacts import tag

PLANE_COLOR = "#8c6d31"
HINGE_COLOR = "#444444"
PLANE_Z, BODY_Z = 1, 3


def view_box(points, pad=0.08, floor=0.3):
    """(lo, hi) corners of a box holding `points` with a margin of `pad` of its largest
    side, each side at least `floor` of the largest (a flat scene keeps some depth)."""
    pts = [p for p in points if all(math.isfinite(c) for c in p)]
    if not pts:
        return (-1.0, -1.0, -1.0), (1.0, 1.0, 1.0)
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    big = max(max(h - l for l, h in zip(lo, hi)), 1e-3)
    half = [max(h - l, floor * big) / 2 + pad * big for l, h in zip(lo, hi)]
    mid = [(l + h) / 2 for l, h in zip(lo, hi)]
    return tuple(m - s for m, s in zip(mid, half)), tuple(m + s for m, s in zip(mid, half))


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _unit(v):
    n = math.sqrt(_dot(v, v))
    return [c / n for c in v] if n > 0 and math.isfinite(n) else None


def plane_polygon(point, normal, box):
    """The polygon where the plane through `point` with `normal` cuts the box (corners in
    order), or [] when it misses the box."""
    n = _unit(normal)
    if n is None:
        return []
    lo, hi = box
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    side = [_dot([c - o for c, o in zip(p, point)], n) for p in corners]
    pts = []
    for i in range(8):
        for j in range(i + 1, 8):
            if bin(i ^ j).count("1") != 1:
                continue  # not an edge of the box
            a, b = side[i], side[j]
            if a == 0:
                pts.append(corners[i])
            if (a < 0 < b) or (b < 0 < a):
                s = a / (a - b)
                pts.append(tuple(p + s * (q - p) for p, q in zip(corners[i], corners[j])))
    if len(pts) < 3:
        return []
    c = [sum(p[i] for p in pts) / len(pts) for i in range(3)]
    a = [0.0, 0.0, 1.0] if abs(n[2]) < 0.9 else [1.0, 0.0, 0.0]
    u = _unit([n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]])
    w = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]]
    pts.sort(key=lambda p: math.atan2(_dot([x - y for x, y in zip(p, c)], w),
                                      _dot([x - y for x, y in zip(p, c)], u)))
    out = []
    for p in pts:  # drop repeated corners
        if not out or math.dist(p, out[-1]) > 1e-12 * (1 + max(map(abs, p))):
            out.append(p)
    return out if len(out) >= 3 else []


def line_in_box(anchor, axis, box):
    """The part of the line anchor + s axis inside the box, (p, q), or None."""
    u = _unit(axis)
    if u is None:
        return None
    lo, hi = box
    s0, s1 = -math.inf, math.inf
    for i in range(3):
        if abs(u[i]) < 1e-15:
            if not lo[i] <= anchor[i] <= hi[i]:
                return None
            continue
        a, b = (lo[i] - anchor[i]) / u[i], (hi[i] - anchor[i]) / u[i]
        s0, s1 = max(s0, min(a, b)), min(s1, max(a, b))
    if not s0 < s1:
        return None
    return (tuple(a + s0 * c for a, c in zip(anchor, u)),
            tuple(a + s1 * c for a, c in zip(anchor, u)))


def _vec(v, n=3):
    try:
        out = [float(c) for c in v]
    except (TypeError, ValueError):
        return None
    return out if len(out) == n and all(math.isfinite(c) for c in out) else None


def planes_of(scene):
    out = []
    for k, p in enumerate((scene or {}).get("planes", []) or []):
        n = _vec(p.get("normal")) if isinstance(p, dict) else None
        o = _vec(p.get("point", [0, 0, 0])) if isinstance(p, dict) else None
        if n is not None and o is not None and _unit(n) is not None:
            out.append((k, o, _unit(n)))
    return out


def hinges_of(scene):
    """(k, anchor, axis or None) of each hinge: a point joint has no axis to draw."""
    out = []
    for k, h in enumerate((scene or {}).get("hinges", []) or []):
        a = _vec(h.get("anchor")) if isinstance(h, dict) else None
        if a is not None:
            u = _vec(h.get("axis")) if "axis" in h else None
            out.append((k, a, _unit(u) if u is not None else None))
    return out


def camera(scene, elev=25.0, azim=-60.0):
    """(elev, azim) of a camera on the open side of every plane (the default if it is)."""
    normals = [n for _, _, n in planes_of(scene)]

    def ok(e, a):
        d = (math.cos(math.radians(e)) * math.cos(math.radians(a)),
             math.cos(math.radians(e)) * math.sin(math.radians(a)), math.sin(math.radians(e)))
        return all(_dot(d, n) > 0.1 for n in normals)
    for da in (0, 30, -30, 60, -60, 90, -90, 120, -120, 150, -150, 180):
        for e in (elev, 40.0, 60.0, 10.0, -20.0):
            if ok(e, azim + da):
                return e, azim + da
    return elev, azim


def setup(ax, box, scene):
    """Limits, one scale on the three axes, labels, the fixed drawing order, the camera."""
    lo, hi = box
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect([h - l for l, h in zip(lo, hi)], zoom=0.82)  # room for the z label
    ax.computed_zorder = False
    ax.view_init(*camera(scene))
    from matplotlib.ticker import MaxNLocator
    for a, side in zip((ax.xaxis, ax.yaxis, ax.zaxis), [h - l for l, h in zip(lo, hi)]):
        # Fewer ticks on a short side: its labels would run into each other.
        a.set_major_locator(MaxNLocator(max(2, min(6, round(6 * side / max(
            h - l for l, h in zip(lo, hi)))))))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


def draw_geometry(ax, scene, box):
    """The scene's planes (clipped to the box) and hinge axes, tagged."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    for k, o, n in planes_of(scene):
        poly = plane_polygon(o, n, box)
        if poly:
            art = Poly3DCollection([poly], facecolor=PLANE_COLOR, edgecolor=PLANE_COLOR,
                                   alpha=0.18, linewidths=0.6, zorder=PLANE_Z)
            ax.add_collection3d(art)
            tag(art, "plane", poly, index=k, point=o, normal=n)
    for k, a, u in hinges_of(scene):
        if u is not None:
            seg = line_in_box(a, u, box)
            if seg:
                (line,) = ax.plot(*zip(*seg), color=HINGE_COLOR, ls=(0, (5, 3)), lw=1.2,
                                  zorder=BODY_Z + 1, label="hinge axis" if k == 0 else None)
                tag(line, "hinge", seg, index=k, anchor=a, axis=u)
        (dot,) = ax.plot([a[0]], [a[1]], [a[2]], marker="o", ms=4, color=HINGE_COLOR,
                         ls="", zorder=BODY_Z + 1)
        tag(dot, "hinge", [a], index=k, anchor=a, axis=u)


def draw_lines(ax, segments, color, lw=1.0, kind="body"):
    """Segments [(p, q), ...] as one collection, tagged as a body's drawing."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    segs = [s for s in segments if all(math.isfinite(c) for p in s for c in p)]
    if not segs:
        return None
    art = Line3DCollection(segs, colors=color, linewidths=lw, zorder=BODY_Z)
    ax.add_collection3d(art)
    tag(art, kind, [p for s in segs for p in s])
    return art
