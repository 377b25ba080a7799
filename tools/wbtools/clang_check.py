"""Builds and tests every lab with clang++ and libc++, the compiler and library of macOS (issue 44).

The workbook is written on Debian with GCC and libstdc++; many students work on macOS (Apple's
clang and libc++). This stage proves, on every CI run, that the same files build and pass there:

  1. a build of every lab (skeletons, solutions, tests, the framework from source, no
     benchmarks: Debian's Google Benchmark is compiled for libstdc++) with clang++
     -stdlib=libc++ and -Werror: no warning from the project's own code under clang either;
  2. every graded test against the solutions, the physics checks and the bad-input cases
     (ctest -L "solution|badinput");
  3. every skeleton on every default scene warns it is a stub, no solution does
     (tools/pattern stubs on this build);
  4. the student pack's compiled-only replacements (tools/pack.d/compiled-only/, compiled by a
     pack whose prebuilt/ does not match its toolchain, as on a Mac) compile with clang;
  5. the grader with clang and libc++: the skeletons score 0, the solutions 100.

Exit status: 0 all passed, 1 a step failed (each says which), 2 clang or libc++ missing."""
import argparse
import os
import shutil
import subprocess
import sys
import time

from . import answers, pack

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FLAGS = "-stdlib=libc++"


def env_clang():
    """The environment a first configure reads its compiler and flags from (CXX, CXXFLAGS,
    LDFLAGS): clang++ with libc++, for this build and the grader's scratch build alike."""
    return dict(os.environ, CXX="clang++", CXXFLAGS=FLAGS, LDFLAGS=FLAGS)


def missing_toolchain():
    """One line naming what is missing to build with clang++ and libc++, or ""."""
    if not shutil.which("clang++"):
        return "clang++ is missing (Debian package clang; tools/setup --clang installs it)"
    p = subprocess.run(["clang++", "-stdlib=libc++", "-x", "c++", "-", "-o", os.devnull],
                       input=b"#include <vector>\nint main() { return std::vector<int>(1)[0]; }\n",
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if p.returncode != 0:
        return ("clang++ -stdlib=libc++ cannot build a program (Debian packages libc++-14-dev "
                "libc++abi-14-dev; tools/setup --clang installs them)")
    return ""


def configured_compiler(build):
    """The C++ compiler a build folder was configured with (CMakeCache.txt), or None."""
    try:
        with open(os.path.join(build, "CMakeCache.txt"), encoding="utf-8") as f:
            for line in f:
                if line.startswith("CMAKE_CXX_COMPILER:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


# Steps that go on after a failure (every failing step is listed at the end). Not
# newlab_check.Steps, which stops at the first failure (each step needs the one before) and
# runs a step in a process group of its own, to end it when stopped (docs/contributor.md,
# "Repeated code").
class Steps:
    def __init__(self):
        self.failed = []

    def run(self, what, cmd, env=None, cwd=ROOT):
        t0 = time.monotonic()
        print(f"clang-check: {what}\n+ {' '.join(cmd)}", flush=True)
        rc = subprocess.run(cmd, cwd=cwd, env=env).returncode
        print(f"clang-check: {'ok' if rc == 0 else f'FAILED (exit {rc})'}: {what} "
              f"({time.monotonic() - t0:.0f} s)", flush=True)
        if rc != 0:
            self.failed.append(what)
        return rc == 0


def compiled_only_compile(build):
    """Problems compiling each compiled-only replacement with the command clang compiled the
    real file with (tools/pack's own check, on this build's compile_commands.json)."""
    problems = []
    for rel in answers.COMPILED_ONLY:
        try:
            pack.check_compiles(build, os.path.join(ROOT, rel), os.path.join(answers.FALLBACKS, rel))
        except pack.PackError as e:
            problems.append(f"tools/pack.d/compiled-only/{rel}, with clang: {e}")
    return problems


def main():
    ap = argparse.ArgumentParser(prog="tools/clang-check", description=__doc__.split("\n\n")[0],
                                 epilog="\n\n".join(__doc__.split("\n\n")[1:]),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build-dir", default="build/clang",
                    help="the clang build (default build/clang); the grader's scratch build is "
                         "<build-dir>-grade")
    ap.add_argument("--no-grade", action="store_true", help="leave out step 5 (the grader)")
    ap.add_argument("--no-setup", action="store_true", help="install nothing first")
    try:
        args = ap.parse_args()
    except SystemExit as e:
        return 2 if e.code else 0
    why = missing_toolchain()
    if why:
        print(f"tools/clang-check: error: {why}", file=sys.stderr)
        return 2
    build = os.path.abspath(os.path.join(ROOT, args.build_dir))
    env = env_clang()
    s = Steps()
    t0 = time.monotonic()
    configure = ["cmake", "-S", ROOT, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 "-DWB_WERROR=ON", "-DWB_BENCH=OFF", "-DWB_PREBUILT=OFF", "-DWB_TESTS=ON"]
    compiler = configured_compiler(build)
    if compiler is not None and "clang" not in os.path.basename(compiler):
        print(f"clang-check: {args.build_dir} was configured with {compiler}: starting it again",
              flush=True)
        shutil.rmtree(build)
    ok = (s.run("configure with clang++ -stdlib=libc++ and -Werror", configure, env)
          and s.run("build every lab, its solution and its tests (-Werror)",
                    ["cmake", "--build", build, "-j2"], env))
    if ok:
        s.run("every graded test against the solutions, the physics checks, bad input",
              ["ctest", "--test-dir", build, "-L", "solution|badinput", "--no-tests=error",
               "-j2", "--output-on-failure"], env)
        s.run("skeletons warn they are stubs, solutions do not (tools/pattern stubs)",
              [os.path.join(ROOT, "tools", "pattern"), "stubs", "--build-dir", build], env)
        t1 = time.monotonic()
        problems = compiled_only_compile(build)
        for p in problems:
            print(f"clang-check: {p}", flush=True)
        print(f"clang-check: {'ok' if not problems else 'FAILED'}: the pack's compiled-only "
              f"replacements compile with clang ({time.monotonic() - t1:.0f} s)", flush=True)
        if problems:
            s.failed.append("the pack's compiled-only replacements compile with clang")
    if not args.no_grade:
        grade = build + "-grade"
        s.run("the grader with clang and libc++: the skeletons score 0",
              [os.path.join(ROOT, "tools", "grade"), "labs", "--require-score", "0",
               "--build-dir", grade], env)
        s.run("the grader with clang and libc++: the solutions score 100",
              [os.path.join(ROOT, "tools", "grade"), "solutions", "--require-score", "100",
               "--build-dir", grade], env)
    print(f"clang-check: {'all passed' if not s.failed else f'{len(s.failed)} failed: ' + '; '.join(s.failed)}"
          f" in {time.monotonic() - t0:.0f} s", flush=True)
    return 1 if s.failed else 0


def run():
    """The entry tools/clang-check calls."""
    sys.exit(main())
