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

A default scene must also run without a cost warning (none of them is slow), and no
case may be refused. Exit status 0 when every case holds, 1 otherwise.

  tests/badinput/check_cost.py --bin build/bin [-k NAME] [-v]
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
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="wb-cost-")
    rows, problems = [], []
    try:
        for name, lab, argv in cases(tmp):
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
        raw = sorted(cpu / est["seconds"] for _, est, cpu in rows)
        speed = raw[len(raw) // 2]
        print(f"machine speed against the model's rates: {speed:.2f} (the median of "
              f"measured / estimate over {len(rows)} cases)")
        if not SPEED_BAND[0] <= speed <= SPEED_BAND[1]:
            print(f"check_cost: SKIPPED: speed {speed:.2f} outside {SPEED_BAND}: not the "
                  "optimised build the rates describe")
            return 0
        print(f"{'case':58s} {'estimate':>9s} {'measured':>9s} {'raw':>6s} {'ratio':>6s}")
        worst = 0.0
        for name, est, cpu in rows:
            ratio = cpu / (speed * est["seconds"])
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
        print(f"check_cost: {len(rows)} cases, the worst off by a factor {math.exp(worst):.2f} "
              f"(allowed {FACTOR:g})")
        for p in problems:
            print("FAIL " + p)
        return 1 if problems else 0
    finally:
        for f in glob.glob(os.path.join(tmp, "*")):
            os.remove(f)
        os.rmdir(tmp)


if __name__ == "__main__":
    sys.exit(main())
