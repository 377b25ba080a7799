#!/usr/bin/env -S sh -c 'exec "${0%/*}/../../tools/lib/start-python" "$0" "$@"'
"""The cost model against measured run times (issue 31; docs/scenes.md, "Cost").

Runs every default scene of every lab whose solution executable is in --bin, the scene
generators at their limits and a few sweeps, each twice: with --estimate (the model's
estimate, nothing run) and for real, measuring the process's CPU time (user + system,
from wait4: what other work on the machine does not inflate). The model's rates were
measured on one machine; the median of measured / estimate over the cases, measured here
in the same run, is this machine's speed against it, and every case must then be within
FACTOR of its estimate, either way:

  measured / (speed x estimate) in [1/FACTOR, FACTOR]

(both sides taken as at least NOISE_FLOOR_S of CPU: a run of a few milliseconds measures the
process's start and the machine's load more than the model's work).

A default scene must also run without a cost warning (none of them is slow), and no
case may be refused. Exit status 0 when every case holds, 1 otherwise.

With --shapes it also runs twenty scenes of other shapes (SHAPES: sizes, force terms,
solvers and contacts the default scenes do not have, each about a second) and prints
their spread separately: a measurement for docs/scenes.md ("How good it is"), not a
check (the model is a model; the budget measured while running is the wall).

  tests/badinput/check_cost.py --bin build/bin [-k NAME] [-v] [--shapes]
"""
import argparse
import glob
import json
import math
import os
import selectors
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FACTOR = 3.0
# Below this much CPU time a run's measurement is the process's start, the scene's reading and
# the machine's load more than the work the model counts: both sides of the ratio are taken
# as at least NOISE_FLOOR_S. Measured: collisions/billiards, estimated 0.046 s, took 0.0155 s
# of CPU on the fresh machine beside the other stages (ratio 0.30) and about twice that when
# quiet. An underestimate, the direction the budget cares about, is still caught whenever the
# run itself takes over FACTOR x NOISE_FLOOR_S.
NOISE_FLOOR_S = 0.03
# The machine's speed against the model's must be within this band, else the build is
# not the optimised one the rates describe (a debug or sanitizer build: 10-50 times slower).
SPEED_BAND = (1 / 3, 3.0)


def write(tmp, name, doc):
    path = os.path.join(tmp, name + ".json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    return path


def cases(tmp):
    """(name, lab, argv after the executable)."""
    g = [{"type": "gravity", "g": [0, -9.81]}]
    out = []
    # Every lab (a folder labs/<lab>/), a new one too; main() skips a lab not built in --bin.
    for lab in sorted(d for d in os.listdir(os.path.join(REPO, "labs"))
                      if os.path.isdir(os.path.join(REPO, "labs", d))):
        for scene in sorted(glob.glob(os.path.join(REPO, "scenes", lab, "*.json"))):
            out.append((f"{lab}/{os.path.basename(scene)}", lab, ["--scene", scene]))
    rope = write(tmp, "rope-max", {"dt": 1e-3, "t_end": 0, "forces": g, "rope": {
        "start": [0, 0], "end": [1000, 0], "beads": 1000000, "m": 0.01, "k": 100}})
    cloth = write(tmp, "cloth-max", {"dt": 1e-3, "t_end": 0, "forces": g, "cloth": {
        "origin": [0, 0], "rows": 1000, "cols": 1000, "spacing": 0.01, "m": 0.001, "k": 10,
        "k_bend": 1}})
    cloth32 = write(tmp, "cloth-32", {"dt": 0.01, "t_end": 0.05, "forces": g, "cloth": {
        "origin": [0, 0], "rows": 32, "cols": 32, "spacing": 0.05, "m": 0.01, "k": 100,
        "k_bend": 10}})
    out += [
        ("rope generator at its limit (10^6 beads), 1 step", "implicit",
         ["--scene", rope, "--integrator", "symplectic-euler", "--steps", "1"]),
        ("cloth generator at its limit (1000 x 1000), 1 step", "implicit",
         ["--scene", cloth, "--integrator", "symplectic-euler", "--steps", "1"]),
        ("cloth 32 x 32, backward-euler (Newton, LDLT)", "implicit", ["--scene", cloth32]),
        ("cloth 32 x 32, backward-euler-fast", "implicit",
         ["--scene", cloth32, "--integrator", "backward-euler-fast"]),
        ("sweep: euler oscillator (exact)", "euler",
         ["--scene", os.path.join(REPO, "scenes/euler/oscillator.json"),
          "--sweep", os.path.join(tmp, "sweep.csv")]),
        ("sweep: midpoint pendulum (rk4 reference)", "midpoint",
         ["--scene", os.path.join(REPO, "scenes/midpoint/pendulum.json"),
          "--sweep", os.path.join(tmp, "sweep.csv")]),
        ("sweep: rigid dzhanibekov to t = 10, 1 repeat", "rigid",
         ["--scene", os.path.join(REPO, "scenes/rigid/dzhanibekov.json"),
          "--sweep", os.path.join(tmp, "sweep.csv"), "--t-end", "10", "--repeats", "1"]),
    ]
    return out


def emitter(count, lo, hi, **kw):
    return dict({"count": count, "seed": 1, "min": lo, "max": hi, "m": 1}, **kw)


def shape_cases(tmp):
    """Twenty scenes of other shapes than the default ones (name, lab, argv)."""
    g = [{"type": "gravity", "g": [0, -9.81]}]
    box = [{"point": [0, 0], "normal": [0, 1]}, {"point": [-5, 0], "normal": [1, 0]},
           {"point": [5, 0], "normal": [-1, 0]}]
    chain = [{"type": "spring", "i": i, "j": i + 1, "k": 100} for i in range(199)]
    scenes = [
        ("nbody 400, symplectic-euler", "forces", {"dt": 1e-3, "t_end": 2, "forces": [
            {"type": "newton", "G": 1e-3, "softening": 0.05}],
            "emitters": [emitter(400, [0, 0], [1, 1])]}, []),
        ("boids 1500", "forces", {"dt": 0.01, "t_end": 2, "forces": [{"type": "boids",
            "separation": {"weight": 1, "radius": 1}, "alignment": {"weight": 1, "radius": 2},
            "cohesion": {"weight": 1, "radius": 3}}],
            "emitters": [emitter(1500, [0, 0], [40, 40], speed=1)]}, []),
        ("chain of 200 hand-written springs, 20000 steps", "forces", {"dt": 1e-4, "t_end": 2,
            "particles": [{"x": [0.1 * i, 0], "m": 0.01} for i in range(200)],
            "forces": chain + g}, []),
        ("vortex and damping, 30000 particles", "forces", {"dt": 0.01, "t_end": 2, "forces": [
            {"type": "vortex", "omega": 2, "core": 1, "drag": 0.5}, {"type": "damping", "b": 0.1}],
            "emitters": [emitter(30000, [-5, -5], [5, 5])]}, []),
        ("curl noise, 4000 particles, 40 obstacles", "forces", {"dt": 0.01, "t_end": 2, "forces": [
            {"type": "curl-noise", "b": 1, "amplitude": 1, "scale": 2, "seed": 3,
             "obstacles": [{"center": [i - 20, (i % 5) - 2], "radius": 0.3} for i in range(40)]}],
            "emitters": [emitter(4000, [-20, -5], [20, 5])]}, []),
        ("20000 particles, 3 attractors, explicit Euler", "euler", {"dt": 1e-3, "t_end": 1,
            "forces": [{"type": "attractor", "center": [c, 0], "GM": 1} for c in (-2, 0, 2)],
            "emitters": [emitter(20000, [-5, 1], [5, 5])]}, ["--integrator", "explicit-euler"]),
        ("rk4 on 20000 falling particles with drag", "midpoint", {"dt": 1e-3, "t_end": 0.5,
            "forces": g + [{"type": "damping", "b": 0.2}],
            "emitters": [emitter(20000, [0, 0], [10, 10], speed=2)]}, ["--integrator", "rk4"]),
        ("trapezoid on a 200-spring chain", "midpoint", {"dt": 1e-4, "t_end": 1,
            "particles": [{"x": [0.1 * i, 0], "m": 0.01} for i in range(200)],
            "forces": chain + g}, ["--integrator", "trapezoid"]),
        ("rope of 20000 beads, baraff-witkin (LDLT)", "implicit", {"dt": 1 / 60, "t_end": 5,
            "rope": {"start": [0, 0], "end": [100, 0], "beads": 20000, "m": 0.01, "k": 1e4},
            "forces": g}, ["--integrator", "baraff-witkin"]),
        ("cloth 60 x 60 without a newton key, baraff-witkin", "implicit", {"dt": 1 / 60,
            "t_end": 3, "cloth": {"origin": [0, 0], "rows": 60, "cols": 60, "spacing": 0.05,
                                  "m": 0.01, "k": 1e4, "k_bend": 100}, "forces": g},
         ["--integrator", "baraff-witkin"]),
        ("cloth 40 x 40, backward-euler-fast", "implicit", {"dt": 1 / 60, "t_end": 3, "cloth": {
            "origin": [0, 0], "rows": 40, "cols": 40, "spacing": 0.05, "m": 0.01, "k": 1e3},
            "forces": g}, ["--integrator", "backward-euler-fast"]),
        ("rope of 3000 beads, backward-euler (Newton)", "implicit", {"dt": 1 / 60, "t_end": 5,
            "rope": {"start": [0, 0], "end": [30, 0], "beads": 3000, "m": 0.01, "k": 1e4},
            "forces": g}, ["--integrator", "backward-euler"]),
        ("cloth 24 x 24, implicit trapezoid", "implicit", {"dt": 1 / 60, "t_end": 3, "cloth": {
            "origin": [0, 0], "rows": 24, "cols": 24, "spacing": 0.05, "m": 0.01, "k": 1e3},
            "forces": g}, ["--integrator", "implicit-trapezoid"]),
        ("gas of 4000 discs in a box, accumulated", "collisions", {"dt": 2e-3, "t_end": 1,
            "planes": box + [{"point": [0, 10], "normal": [0, -1]}], "contact": {},
            "emitters": [emitter(4000, [-4.9, 0.1], [4.9, 9.9], speed=2, radius=0.03)]}, []),
        ("pile of 3000 discs, passes and shock propagation", "collisions", {"dt": 2e-3,
            "t_end": 1, "planes": box, "forces": g, "contact": {"solver": "passes",
            "iterations": 4, "shock_propagation": True},
            "emitters": [emitter(3000, [-4.9, 0.05], [4.9, 2], radius=0.05)]}, []),
        ("2000 fast particles against thin walls, ccd", "collisions", {"dt": 1e-3, "t_end": 1,
            "planes": [{"point": [-1, 0], "normal": [1, 0], "thickness": 0.01},
                       {"point": [1, 0], "normal": [-1, 0], "thickness": 0.01}],
            "contact": {"ccd": True},
            "emitters": [emitter(2000, [-0.9, -1], [0.9, 1], speed=50, radius=0.001)]}, []),
    ]
    rigid = [
        ("200 boxes resting on a plane, accumulated", {"dt": 1e-3, "t_end": 1, "bodies": [
            {"shape": "box", "size": [1, 1, 1], "m": 1, "x": [2 * k, 0, 0.5]} for k in range(200)],
            "planes": [{"normal": [0, 0, 1]}], "forces": [{"type": "gravity", "g": [0, 0, -9.81]}],
            "contact": {}}),
        ("100 cylinders rolling, passes", {"dt": 1e-3, "t_end": 2, "bodies": [
            {"shape": "cylinder", "radius": 0.2, "length": 0.5, "m": 1, "x": [k, 0, 0.2],
             "q": [0.7071067811865476, 0.7071067811865476, 0, 0], "omega": [0, 3, 0]}
            for k in range(100)], "planes": [{"normal": [0, 0, 1]}],
            "forces": [{"type": "gravity", "g": [0, 0, -9.81]}]}),
        ("500 revolute pendulums", {"dt": 1e-3, "t_end": 2, "bodies": [
            {"shape": "box", "size": [0.1, 0.1, 1], "m": 1, "x": [k, 0, 0],
             "omega": [1, 0, 0]} for k in range(500)],
            "hinges": [{"body": k, "anchor": [k, 0, 0.5], "axis": [1, 0, 0]} for k in range(500)],
            "forces": [{"type": "gravity", "g": [0, 0, -9.81]}]}),
    ]
    out = []
    for name, lab, doc, extra in scenes:
        out.append((name, lab, ["--scene", write(tmp, "shape-" + str(len(out)), doc)] + extra))
    for name, doc in rigid:
        out.append((name, "rigid", ["--scene", write(tmp, "shape-" + str(len(out)), doc)]))
    sweep = write(tmp, "shape-sweep", {"dt": 0.01, "t_end": 1, "forces": chain[:49] + g,
                                        "particles": [{"x": [0.1 * i, 0], "m": 0.01}
                                                      for i in range(50)]})
    out.append(("sweep: a 50-bead chain (rk4 reference)", "euler",
                ["--scene", sweep, "--sweep", os.path.join(tmp, "sweep.csv"), "--repeats", "1"]))
    return out


def measured(argv):
    """CPU seconds (user + system) of one run of argv, its stdout, stderr and status."""
    r, w = os.pipe()
    e_r, e_w = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: argv with stdout and stderr to the pipes
        os.dup2(w, 1)
        os.dup2(e_w, 2)
        for fd in (r, w, e_r, e_w):
            os.close(fd)
        try:
            os.execv(argv[0], argv)
        finally:
            os._exit(127)
    os.close(w)
    os.close(e_w)
    out, err = [], []
    sel = selectors.DefaultSelector()
    sel.register(r, selectors.EVENT_READ, out)
    sel.register(e_r, selectors.EVENT_READ, err)
    open_fds = 2
    while open_fds:
        for key, _ in sel.select():
            chunk = os.read(key.fd, 65536)
            if chunk:
                key.data.append(chunk)
            else:
                sel.unregister(key.fd)
                os.close(key.fd)
                open_fds -= 1
    _, status, ru = os.wait4(pid, 0)
    code = os.waitstatus_to_exitcode(status)
    return (ru.ru_utime + ru.ru_stime, b"".join(out).decode("utf-8", "replace"),
            b"".join(err).decode("utf-8", "replace"), code)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(REPO, "build", "bin"),
                    help="folder of the lab executables (default: build/bin)")
    ap.add_argument("-k", dest="only", help="run only the cases whose name contains this")
    ap.add_argument("-v", "--verbose", action="store_true", help="print every estimate's terms")
    ap.add_argument("--shapes", action="store_true",
                    help="also twenty scenes of other shapes, their spread printed apart")
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="wb-cost-")
    rows, problems = [], []
    shapes = {name for name, _, _ in shape_cases(tmp)} if args.shapes else set()
    try:
        for name, lab, argv in cases(tmp) + (shape_cases(tmp) if args.shapes else []):
            exe = os.path.join(args.bin, lab + "-solution")
            if not os.path.exists(exe):
                continue
            if args.only and args.only not in name:
                continue
            _, out, err, code = measured([exe] + argv + ["--estimate"])
            try:
                est = json.loads(out.strip().splitlines()[-1])
            except (ValueError, IndexError):
                problems.append(f"{name}: --estimate printed no estimate ({err.strip()[:200]})")
                continue
            if est.get("verdict") == "refused":
                problems.append(f"{name}: refused: {est.get('refusal', '')[:200]}")
                continue
            cpu, out, err, code = measured([exe] + argv)
            if code != 0:
                problems.append(f"{name}: exit status {code}: {err.strip()[:200]}")
                continue
            if "warning: " in err and "Cost" in err and lab + "/" in name:
                problems.append(f"{name}: a default scene warns that it is slow: "
                                f"{err.strip()[:200]}")
            rows.append((name, est, cpu))
        if not rows:
            print("check_cost: no case ran: no solution executable in " + args.bin)
            return 0
        raw = sorted(cpu / est["seconds"] for name, est, cpu in rows if name not in shapes)
        speed = raw[len(raw) // 2]
        print(f"machine speed against the model's rates: {speed:.2f} (the median of "
              f"measured / estimate over {len(raw)} cases)")
        if not SPEED_BAND[0] <= speed <= SPEED_BAND[1]:
            print(f"check_cost: SKIPPED: speed {speed:.2f} outside {SPEED_BAND}: not the "
                  "optimised build the rates describe")
            return 0
        print(f"{'case':58s} {'estimate':>9s} {'measured':>9s} {'raw':>6s} {'ratio':>6s}")
        worst = 0.0
        spread = {False: [], True: []}
        for name, est, cpu in rows:
            ratio = max(cpu, NOISE_FLOOR_S) / max(speed * est["seconds"], NOISE_FLOOR_S)
            spread[name in shapes].append(ratio)
            if name in shapes:  # measured, not checked
                print(f"{name[:58]:58s} {est['seconds']:9.4f} {cpu:9.4f} "
                      f"{cpu / est['seconds']:6.2f} {ratio:6.2f}  (shape)")
                if args.verbose:
                    for t in sorted(est["terms"], key=lambda t: -t["seconds"])[:5]:
                        print(f"      {t['seconds']:10.5f} s  {t['what']}")
                continue
            ok = 1 / FACTOR <= ratio <= FACTOR
            worst = max(worst, abs(math.log(ratio)))
            print(f"{name[:58]:58s} {est['seconds']:9.4f} {cpu:9.4f} "
                  f"{cpu / est['seconds']:6.2f} {ratio:6.2f}{'' if ok else '  <- outside'}")
            if not ok:
                problems.append(f"{name}: measured {cpu:.4f} s, estimated {est['seconds']:.4f} s "
                                f"x speed {speed:.2f}: ratio {ratio:.2f}, expected within "
                                f"a factor {FACTOR:g}")
            if args.verbose or not ok:
                for t in sorted(est["terms"], key=lambda t: -t["seconds"])[:5]:
                    print(f"      {t['seconds']:10.5f} s  {t['what']}")
        for kind, values in (("default scenes and generators", spread[False]),
                             ("scenes of other shapes", spread[True])):
            if values:
                v = sorted(values)
                print(f"spread, {kind} ({len(v)}): measured / (speed x estimate) from "
                      f"{v[0]:.2f} to {v[-1]:.2f}, median {v[len(v) // 2]:.2f}")
        print(f"check_cost: {len(rows) - len(shapes & {n for n, _, _ in rows})} cases, the worst "
              f"off by a factor {math.exp(worst):.2f} (allowed {FACTOR:g})")
        for p in problems:
            print("FAIL " + p)
        return 1 if problems else 0
    finally:
        for f in glob.glob(os.path.join(tmp, "*")):
            os.remove(f)
        os.rmdir(tmp)


if __name__ == "__main__":
    sys.exit(main())
