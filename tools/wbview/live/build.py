"""Builds a lab's live modules with emscripten (cmake/live.cmake) in build/live/: one
JavaScript file per lab and side with the WebAssembly inside. Only what changed is
compiled again (ninja), so that a student's edit is live again in seconds."""
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))
# Debian's emscripten runs its JavaScript tools (acorn) with the machine's node: when
# that node is not Debian's own, they are found only on Debian's modules folder.
DEBIAN_NODE_MODULES = "/usr/share/nodejs"
MISSING = ("em++ not found: the live pages need Debian's emscripten (tools/setup --live "
           "installs it; nothing else in the workbook needs it)")


class BuildError(Exception):
    """The build could not run or failed: one line for the user (exit 2, or 1)."""

    def __init__(self, msg, status=2):
        super().__init__(msg)
        self.status = status


def have_emscripten():
    return shutil.which("em++") is not None and shutil.which("emcmake") is not None


def environment():
    env = dict(os.environ)
    if os.path.isdir(DEBIAN_NODE_MODULES):
        paths = [p for p in env.get("NODE_PATH", "").split(os.pathsep) if p]
        if DEBIAN_NODE_MODULES not in paths:
            env["NODE_PATH"] = os.pathsep.join(paths + [DEBIAN_NODE_MODULES])
    return env


def configured(build_dir, solutions):
    cache = os.path.join(build_dir, "CMakeCache.txt")
    if not os.path.isfile(cache) or not os.path.isfile(os.path.join(build_dir, "build.ninja")):
        return False
    with open(cache, encoding="utf-8", errors="replace") as f:
        text = f.read()
    return "WB_LIVE:BOOL=ON" in text and f"WB_SOLUTIONS:BOOL={'ON' if solutions else 'OFF'}" in text


def run(argv, quiet, env):
    """Runs a build command; its output shown when it fails (or always, not quiet)."""
    p = subprocess.run(argv, cwd=ROOT, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, errors="replace")
    if p.returncode != 0 or not quiet:
        sys.stdout.write(p.stdout)
    return p.returncode


def build(lab, sides, build_dir, jobs=2, quiet=True):
    """Configures (once) and builds <lab>[-solution]-live for each side; returns
    {side: path of the module's .js}. Raises BuildError."""
    if not have_emscripten():
        raise BuildError(MISSING)
    env = environment()
    solutions = "solution" in sides
    if not configured(build_dir, solutions):
        argv = ["emcmake", "cmake", "-S", ROOT, "-B", build_dir, "-G", "Ninja", "-DWB_LIVE=ON",
                "-DCMAKE_BUILD_TYPE=Release", f"-DWB_SOLUTIONS={'ON' if solutions else 'OFF'}"]
        if run(argv, quiet, env) != 0:
            raise BuildError(f"configuring {build_dir} failed (its messages are above)", 1)
    targets = [f"{lab}{'' if s == 'student' else '-' + s}-live" for s in sides]
    argv = ["cmake", "--build", build_dir, "-j", str(jobs), "--target"] + targets
    if run(argv, quiet, env) != 0:
        raise BuildError("the build failed: em++'s messages are above (the same code builds "
                         "natively: cmake --build --preset default says the same)", 1)
    return {s: os.path.join(build_dir, "bin", t + ".js") for s, t in zip(sides, targets)}
