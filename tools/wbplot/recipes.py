"""How the report runs a scene: the commands and the step ladders, shared by tools/report
and tools/claims so that a claim is checked against exactly the runs the figures show."""
import math
import re

MAX_WRITTEN_STEPS = 2000   # trace rows per particle, at most
MAX_TRACE_ROWS = 200_000   # trace rows in all (about 20 MB of CSV), at most
MAX_SWEEP_STEPS = 4_000_000  # sweep step sizes needing more steps are left out (time)
SWEEP_REPEATS = 5          # timed repeats per sweep run: wall_s is the least of them


def offers(help_text, flag):
    """True if --help lists `flag` as an option (a line starting with it)."""
    return re.search(r"^\s+" + re.escape(flag) + r"\b", help_text, re.M) is not None


def particle_count(doc):
    n = len(doc.get("particles", []) or [])
    for e in doc.get("emitters", []) or []:
        if isinstance(e, dict) and isinstance(e.get("count"), int):
            n += e["count"]
    return max(n, 1)


def every_for(doc, n=None):
    """--every K: at most MAX_WRITTEN_STEPS written steps per particle, MAX_TRACE_ROWS in all."""
    n = particle_count(doc) if n is None else n
    try:
        steps = round(float(doc["t_end"]) / float(doc["dt"]))
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return 1
    return max(1, math.ceil(steps / MAX_WRITTEN_STEPS), math.ceil(steps * n / MAX_TRACE_ROWS))


def length_scale(doc):
    """The size of the scene at t = 0 (m): extent of the initial positions, or their distance
    from the origin, whichever is larger; 1 when neither is known."""
    pts = []
    for p in doc.get("particles", []) or []:
        if isinstance(p, dict) and isinstance(p.get("x"), list) and len(p["x"]) == 2:
            pts.append(p["x"])
    for e in doc.get("emitters", []) or []:
        if isinstance(e, dict):
            pts += [c for c in (e.get("min"), e.get("max")) if isinstance(c, list) and len(c) == 2]
    try:
        pts = [(float(a), float(b)) for a, b in pts]
    except (TypeError, ValueError):
        return 1.0
    if not pts:
        return 1.0
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    diag = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    far = max(math.hypot(a, b) for a, b in pts)
    s = max(diag, far)
    return s if math.isfinite(s) and s > 0 else 1.0


def oscillator(doc):
    """(h w, zeta, anchor, linear) for a one-particle scene on a single spring to an anchor,
    else None. linear: rest length 0 and no gravity, so the motion is the ellipse of
    x'' = -w^2 x (a spring with a rest length, or under gravity, is a nonlinear pendulum)."""
    parts = doc.get("particles", []) or []
    if len(parts) != 1 or doc.get("emitters"):
        return None
    forces = doc.get("forces", []) or []
    springs = [f for f in forces if isinstance(f, dict) and f.get("type") == "spring"]
    others = [f for f in forces if isinstance(f, dict) and f.get("type") != "spring"]
    if len(springs) != 1 or "anchor" not in springs[0]:
        return None
    if any(f.get("type") not in ("gravity", "damping") for f in others):
        return None
    try:
        k = float(springs[0]["k"])
        m = float(parts[0]["m"])
        dt = float(doc["dt"])
        rest = float(springs[0].get("rest", 0.0))
        c = float(springs[0].get("damping", 0.0)) + sum(float(f.get("b", 0.0)) for f in others
                                                         if f.get("type") == "damping")
    except (KeyError, TypeError, ValueError):
        return None
    if not (k > 0 and m > 0 and dt > 0):
        return None
    w = math.sqrt(k / m)
    linear = rest == 0.0 and not any(f.get("type") == "gravity" for f in others)
    return dt * w, c / (2 * math.sqrt(k * m)), springs[0]["anchor"], linear


def stiffest_w(doc):
    """The largest sqrt(k/m) over the scene's springs and particles (rad/s), 0 without springs."""
    parts = doc.get("particles", []) or []
    w = 0.0
    for f in doc.get("forces", []) or []:
        if not (isinstance(f, dict) and f.get("type") == "spring"):
            continue
        try:
            k = float(f["k"])
            idx = [f["i"]] + ([f["j"]] if "j" in f else [])
            m = min(float(parts[i]["m"]) for i in idx)
        except (KeyError, IndexError, TypeError, ValueError):
            continue
        if k > 0 and m > 0:
            w = max(w, math.sqrt(k / m))
    return w


STIFF_HW = 0.5       # a scene whose dt * w passes this gets a ladder of its own
STIFF_PERIODS = 10   # ... over at most this many periods of its stiffest spring


def sweep_ladder(doc, help_text):
    """(step sizes or None, t_end or None, why) for the report's sweep of a scene; None keeps
    the executable's default (ladder dt*2^k, k = 3..-6; the scene's t_end).

    The ladder must reach the asymptotic range, where error ~ C h^p, so that the
    convergence figure measures an order (docs/report.md):
    - a stiff scene (some spring with dt * w > STIFF_HW) gets ten halvings from
      h w = STIFF_HW down, over at most STIFF_PERIODS periods of that spring;
    - every sweep ends, if need be earlier than the scene, so that its smallest step takes
      at most MAX_SWEEP_STEPS steps (a long run keeps all its step sizes, over a shorter
      time, rather than losing the small ones)."""
    if not offers(help_text, "--dts"):
        return None, None, ""
    try:
        dt, t_end = float(doc["dt"]), float(doc["t_end"])
    except (KeyError, TypeError, ValueError):
        return None, None, ""
    if not (dt > 0 and t_end > 0):
        return None, None, ""
    w = stiffest_w(doc)
    why = []
    if w > 0 and dt * w > STIFF_HW:
        ladder = [STIFF_HW / w * 2.0 ** -k for k in range(10)]
        t = min(t_end, STIFF_PERIODS * 2 * math.pi / w)
        why.append(f"the scene's h w = {dt * w:.3g} is far from the asymptotic range, so the "
                   f"sweep steps from h w = {STIFF_HW:g} down to {STIFF_HW / 512:.2g} "
                   f"(h = {fmt_dt(ladder[0])} to {fmt_dt(ladder[-1])} s)")
    else:
        ladder, t = None, t_end
        smallest = dt / 64
        if round(t / smallest) > MAX_SWEEP_STEPS:
            t = MAX_SWEEP_STEPS * smallest
    top = ladder[0] if ladder else 8 * dt
    if t < t_end:
        t = top * max(1, math.floor(t / top + 1e-9))  # a whole number of the largest steps
        why.append(f"it runs the first {t:.4g} s of the scene's {t_end:g} s (at most "
                   f"{MAX_SWEEP_STEPS:.0e} steps" + (f", {STIFF_PERIODS} periods of the "
                                                      "stiffest spring)" if ladder else ")"))
    return ladder, (t if t < t_end else None), "; ".join(why)


def fmt_dt(h):
    """A step size in a short form: 0.0166667, 1/60 shown as 0.0167; 3 significant digits."""
    if h is None:
        return "?"
    try:
        h = float(h)
    except (TypeError, ValueError):
        return str(h)
    return f"{h:.3g}"


def run_argv(exe, scene_path, doc, trace, stats, integrator=None):
    """The report's run of a scene as shipped (or with one integrator)."""
    argv = [exe, "--scene", scene_path]
    if integrator:
        argv += ["--integrator", integrator]
    return argv + ["--out", trace, "--stats", stats, "--every", str(every_for(doc))]


def sweep_argv(exe, scene_path, doc, help_text, sweep_csv, repeats=None):
    """(argv, why) of the report's sweep of a scene; why says how the ladder was chosen."""
    argv = [exe, "--scene", scene_path, "--sweep", sweep_csv]
    if repeats and offers(help_text, "--repeats"):
        argv += ["--repeats", str(repeats)]
    dts, t_end, why = sweep_ladder(doc, help_text)
    if dts:
        argv += ["--dts", ",".join(repr(h) for h in dts)]
    if t_end:
        argv += ["--t-end", repr(t_end)]
    return argv, why
