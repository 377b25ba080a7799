"""Force laws of a scene drawn from its parameters, with where the particles of a run sit on
them: the vortex's swirl speed against radius, a spring's force against its stretch, the
attractor's pull against distance."""
import math

from .common import InputError, finite, new_figure, save_figure
from .runs import read_scene, read_trace

KINDS = ("vortex", "spring", "attractor")


def _last_state(trace):
    """{id: (x, y, vx, vy)} at each particle's last finite row."""
    out = {}
    for pid, d in trace.items():
        for k in range(len(d["t"]) - 1, -1, -1):
            row = (d["x"][k], d["y"][k], d["vx"][k], d["vy"][k])
            if all(finite(c) for c in row):
                out[pid] = row + (d["t"][k],)
                break
    return out


def _num(f, key, default=None):
    v = f.get(key, default)
    try:
        return float(v)
    except (TypeError, ValueError):
        raise InputError(f"force '{f.get('type')}': key '{key}': got {v!r}, expected a number") \
            from None


def plot_forcelaw(scene, out, trace=None, title=None):
    doc = read_scene(scene)
    forces = [f for f in doc.get("forces", []) or [] if isinstance(f, dict)
              and f.get("type") in KINDS]
    kinds = [k for k in KINDS if any(f["type"] == k for f in forces)]
    if not kinds:
        raise InputError(f"{scene}: nothing to plot: the scene has no {', '.join(KINDS)} force")
    state = _last_state(read_trace(trace)) if trace else {}
    t_end = max((s[4] for s in state.values()), default=None)
    at = f" at t = {t_end:g} s" if t_end is not None else ""
    fig, axes = new_figure(1, len(kinds), figsize=(5.2 * len(kinds), 4.2), squeeze=False)
    for ax, kind in zip(axes[0], kinds):
        mine = [f for f in forces if f["type"] == kind]
        if kind == "vortex":
            f = mine[0]
            cx, cy = (float(c) for c in f.get("center", [0, 0]))
            w, core = _num(f, "omega"), _num(f, "core")
            rs = [math.hypot(s[0] - cx, s[1] - cy) for s in state.values()]
            r_max = max(rs + [3 * core])
            grid = [r_max * k / 400 for k in range(401)]
            ax.plot(grid, [w * r if r <= core else w * core * core / r for r in grid],
                    color="black", lw=1.6, label=f"flow u(r): ωr inside R = {core:g}, "
                                                 "ωR²/r outside")
            ax.axvline(core, color="0.5", ls=":", lw=1)
            if state:
                swirl = []
                for x, y, vx, vy, _ in state.values():
                    dx, dy = x - cx, y - cy
                    r = math.hypot(dx, dy)
                    swirl.append((r, (-dy * vx + dx * vy) / r if r > 0 else 0.0))
                ax.scatter([a for a, _ in swirl], [b for _, b in swirl], s=8, alpha=0.6,
                           color="#1f77b4", label=f"particles' swirl speed{at}")
            ax.set_xlabel("distance r from the centre (m)")
            ax.set_ylabel("swirl (tangential) speed (m/s)")
            ax.set_title("vortex: swirl speed against radius")
        elif kind == "spring":
            pts, laws = [], {}
            for f in mine:
                k, rest = _num(f, "k"), _num(f, "rest", 0.0)
                laws[(k, rest)] = True
                i = f.get("i")
                a = (state.get(i) if isinstance(i, int) else None)
                b = state.get(f["j"]) if isinstance(f.get("j"), int) else None
                if a is None:
                    continue
                if b is None and "anchor" in f:
                    b = (float(f["anchor"][0]), float(f["anchor"][1]))
                if b is None:
                    continue
                L = math.hypot(a[0] - b[0], a[1] - b[1])
                pts.append((L - rest, -k * (L - rest)))
            ext = max([abs(s) for s, _ in pts] + [max(r for _, r in laws) * 0.5 or 0.1])
            grid = [-ext * 1.2 + 2.4 * ext * q / 200 for q in range(201)]
            for k, rest in laws:
                ax.plot(grid, [-k * s for s in grid], lw=1.6,
                        label=f"F = -k (L - rest), k = {k:g} N/m, rest {rest:g} m")
            if pts:
                ax.scatter([s for s, _ in pts], [g for _, g in pts], s=22, color="black",
                           zorder=3, label=f"the scene's {len(pts)} springs{at}")
            ax.axhline(0, color="0.4", lw=0.7)
            ax.axvline(0, color="0.4", lw=0.7)
            ax.set_xlabel("stretch L - rest (m)")
            ax.set_ylabel("spring force along the spring (N), + pushes apart")
            ax.set_title("spring: force against stretch (damper left out)")
        else:
            f = mine[0]
            cx, cy = (float(c) for c in f.get("center", [0, 0]))
            gm = _num(f, "GM")
            rs = [math.hypot(s[0] - cx, s[1] - cy) for s in state.values()]
            hi = max(rs + [2.0]) * 1.2
            grid = [hi * q / 300 for q in range(1, 301)]
            ax.loglog(grid, [gm / r ** 2 for r in grid], color="black", label="GM / r²")
            if rs:
                ax.scatter(rs, [gm / r ** 2 for r in rs if r > 0], s=15, color="#d62728",
                           zorder=3, label=f"particles{at}")
            ax.set_xlabel("distance r (m)")
            ax.set_ylabel("pull per unit mass (m/s²)")
            ax.set_title("attractor: inverse-square pull")
        ax.legend(loc="best", fontsize=7.5, framealpha=0.85)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    save_figure(fig, out)
