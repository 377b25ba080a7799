"""tools/live-check --pack: a student with the pack edits a force and sees it live (issue 43).

In a copy of a student pack (tools/pack's .tar.gz or folder), as its README and docs/live.md
say: `tools/view --live --lab forces` builds the forces page from the skeleton; the student
writes F6 (accumulate_forces.cpp) and F1 (uniform_gravity.cpp), runs the same command, and
the chain falls at g = 9.81 m/s^2 in the page; the student turns gravity's sign, runs it
again, and the chain rises at 9.81. Each build is timed (wall and CPU of the build's
processes); the page is read in headless Chromium (window.wbLive): the chain's beads, whose
springs and damping are still stubs, fall freely, so their mean height is -g t^2 / 2 to the
integrator's O(h) (h = 1 ms) at the run's t."""
import os
import re
import shutil
import subprocess
import tarfile
import tempfile
import time

from . import browser

LAB, SCENE = "forces", "chain"
G = 9.81                   # scenes/forces/chain.json: g = (0, -9.81)
G_TOL = 0.03               # the fitted g within 3 %: the step's O(h/t) error is 0.2 % at t = 0.5 s
REGION = re.compile(r"(  // ---- Replace with your code ----\n).*?(  // ---- end ----\n)", re.S)
# What a student writes (their own words, not the solution's file): F6, then F1.
STUDENT = {
    "accumulate_forces.cpp": "  f.setZero(2, x.cols());\n"
                             "  for (const auto& force : forces) force->add(x, v, m, f);\n",
    "uniform_gravity.cpp": "  for (Eigen::Index i = 0; i < f.cols(); ++i) f.col(i) += m(i) * g;\n",
}
FLIP = ("f.col(i) += m(i) * g", "f.col(i) -= m(i) * g")  # the edit: gravity's sign


def log(msg):
    print(msg, flush=True)


class PackLiveError(Exception):
    """The student's path through the pack broke: one line."""


def fill(path, body):
    """Replaces the 'Replace with your code' region of a skeleton file by body."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    new, n = REGION.subn(lambda m: m.group(1) + body + m.group(2), text)
    if n != 1:
        raise PackLiveError(f"{path}: no single '---- Replace with your code ----' region to fill")
    with open(path, "w", encoding="utf-8") as f:
        f.write(new)


def replace_once(path, old, new):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if text.count(old) != 1:
        raise PackLiveError(f"{path}: '{old}' is not there once")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text.replace(old, new))


def unpack(pack, into):
    """The pack's folder (sim-workbook/) copied or extracted into `into`."""
    if os.path.isdir(pack):
        dest = os.path.join(into, os.path.basename(os.path.normpath(pack)))
        shutil.copytree(pack, dest, symlinks=True, ignore=shutil.ignore_patterns("build"))
        return dest
    if not tarfile.is_tarfile(pack):
        raise PackLiveError(f"--pack: '{pack}' is neither a folder nor a .tar.gz")
    with tarfile.open(pack) as t:
        t.extractall(into, filter="data") if hasattr(tarfile, "data_filter") else t.extractall(into)
    tops = [d for d in os.listdir(into) if os.path.isdir(os.path.join(into, d))]
    if len(tops) != 1:
        raise PackLiveError(f"--pack: '{pack}' holds {len(tops)} top folders, expected one")
    return os.path.join(into, tops[0])


def view_live(root):
    """The docs' one command in the pack; returns (wall s, CPU s of the build, its output)."""
    cmd = [os.path.join(root, "tools", "view"), "--no-setup", "--live", "--lab", LAB]
    c0, t0 = os.times(), time.monotonic()
    p = subprocess.run(cmd, cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, errors="replace")
    c1 = os.times()
    wall, cpu = time.monotonic() - t0, (c1.children_user + c1.children_system
                                         - c0.children_user - c0.children_system)
    if p.returncode != 0:
        raise PackLiveError(f"`tools/view --live --lab {LAB}` in the pack failed (status "
                            f"{p.returncode}): {p.stdout.strip()[-1500:]}")
    return wall, cpu, p.stdout.strip()


def fitted_g(b, page):
    """Opens the page, runs the chain for a while, pauses: (g fitted from the beads' mean
    height as -g t^2 / 2, t, the page's warnings)."""
    b.open("file://" + page, ready="window.wbLive && window.wbLive.ready")
    b.evaluate(f"wbLive.load('{SCENE}')")
    b.pump(0.8)
    b.evaluate("wbLive.play(false)")
    b.pump(0.1)
    r = b.evaluate("wbLive.run(0)")
    ys = [b.evaluate(f"wbLive.position(0, {i})")[1] for i in range(r["n"])]
    t = r["t"]
    if r["error"]:
        raise PackLiveError(f"the page's run stopped: {r['error']}")
    if b.errors:
        raise PackLiveError(f"console errors on the page: {' | '.join(b.errors[:3])}")
    g = -2 * (sum(ys) / len(ys)) / (t * t) if t > 0 else float("nan")
    return g, t, r["status"].get("warnings", [])


def run(pack, shots):
    """The student's path, in a scratch copy of the pack; screenshots of the page after each
    command go to shots/. Returns problems (one line each)."""
    problems = []
    tmp = tempfile.mkdtemp(prefix="wb-live-pack-")
    try:
        root = unpack(os.path.abspath(pack), tmp)
        log(f"live-check: pack: unpacked in {root}")
        page = os.path.join(root, "build", "live", f"{LAB}.html")
        labdir = os.path.join(root, "labs", LAB)
        if not os.path.isdir(labdir):
            raise PackLiveError(f"the pack has no labs/{LAB}/ (tools/pack --lab {LAB})")
        # (what, the edit before the command, the g the page must show: None, no motion)
        steps = [("the skeleton, first build", None, None),
                 ("F6 and F1 written", "fill", G),
                 ("gravity's sign turned (one file)", "flip", -G)]
        with browser.Browser(width=1500, height=900) as b:
            for what, edit, want in steps:
                if edit == "fill":
                    for name, body in STUDENT.items():
                        fill(os.path.join(labdir, name), body)
                elif edit == "flip":
                    replace_once(os.path.join(labdir, "uniform_gravity.cpp"), *FLIP)
                wall, cpu, said = view_live(root)
                g, t, warnings = fitted_g(b, page)
                seen = (f"the chain's beads fall at g = {g:.3f} m/s^2" if g > 0 else
                        f"the chain's beads rise at {-g:.3f} m/s^2" if g < 0 else
                        "the chain's beads do not move")
                log(f"live-check: pack: {what}: tools/view --live --lab {LAB} took {wall:.1f} s "
                    f"wall, {cpu:.1f} s CPU; in the page {seen} (t = {t:.2f} s)"
                    + (f"; the page warns: {warnings[0]}" if warnings else ""))
                shot = os.path.join(shots, f"pack-{edit or 'skeleton'}.png")
                b.screenshot(shot)
                if want is None:
                    ok = abs(g) * t * t < 1e-9 and bool(warnings)
                    expect = "no motion and a stub warning"
                else:
                    ok = abs(g - want) <= G_TOL * G
                    expect = f"g = {want:+.2f} m/s^2 (to {G_TOL:.0%})"
                if not ok:
                    problems.append(f"pack: {what}: the page shows g = {g:.4g} m/s^2 at t = "
                                    f"{t:.3g} s (warnings {warnings}), expected {expect}")
    except (PackLiveError, browser.BrowserError, OSError, tarfile.TarError) as e:
        problems.append(f"pack: {e}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return problems
