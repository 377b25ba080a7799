"""What the compiled student objects may contain (defence in depth: the worker holds them,
and the test process never links them): global definitions only of the lab's own functions
(and of the library templates and header inlines they instantiate), and no code that runs
before main (.init_array, .ctors: global constructors, constructor attributes).

Trust: reads the objects the build made from student code (with nm and readelf)."""
import glob
import os
import re
import subprocess

LIBRARY_NAMESPACES = {"std", "Eigen", "__gnu_cxx", "wb"}
STRONG = set("TDBRGSCi")  # global, non-weak definitions (nm -P type letters)
WEAK = set("WVu")  # weak, and unique (the static variables of inline functions)
COMPILER_SYMBOLS = ("DW.ref.",)  # what the compiler itself emits (exception personality)
STARTUP_SECTIONS = re.compile(r"\s(\.init_array|\.ctors|\.preinit_array)\S*\s")


def first_component(sym):
    """The outermost name of a mangled C++ symbol: the namespace, class or function it belongs
    to ("std" for std::...), the name itself for a C symbol, None for what this does not read
    (operators such as operator new)."""
    if not sym.startswith("_Z"):
        return sym
    s = sym[2:]
    while s[:2] in ("TV", "TI", "TS", "GV", "TT", "TH", "TW", "GR"):
        s = s[2:]
    if s.startswith("Z"):  # an entity local to a function: the function
        s = s[1:]
    if s.startswith("N"):
        s = s[1:].lstrip("rVKRO")
    if s.startswith("St") or s[:2] in ("Sa", "Sb", "Ss", "Si", "So", "Sd"):
        return "std"
    m = re.match(r"(\d+)", s)
    if m:
        n = int(m.group(1))
        return s[len(m.group(1)):len(m.group(1)) + n]
    return None


def header_names(header_paths):
    """Names the lab's pristine headers declare: types, namespaces, functions (inline too)."""
    names = set()
    for p in header_paths:
        with open(p, encoding="utf-8") as f:
            text = re.sub(r"//[^\n]*|/\*.*?\*/", " ", f.read(), flags=re.S)
        names |= set(re.findall(r"\b(?:struct|class|namespace|enum)\s+(\w+)", text))
        names |= set(re.findall(r"\b(\w+)\s*\([^;{}]*\)\s*(?:const\s*)?[;{]", text))
    return names


def check_objects(object_dir, api, header_paths):
    """The first problem with the student objects under object_dir, or "". `api`: the lab's
    function names (the only strong global definitions allowed)."""
    allowed = LIBRARY_NAMESPACES | header_names(header_paths) | set(api)
    for obj in sorted(glob.glob(os.path.join(object_dir, "**", "*.o"), recursive=True)):
        shown = os.path.basename(obj)[:-2]
        out = subprocess.run(["readelf", "-SW", obj], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, timeout=60).stdout.decode("utf-8", "replace")
        m = STARTUP_SECTIONS.search(out)
        if m:
            return (f"{shown}: has code that runs before main ({m.group(1)}: a global object "
                    "with a constructor, or a constructor attribute); keep state inside "
                    "functions")
        out = subprocess.run(["nm", "-P", "-g", "--defined-only", obj], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, timeout=60).stdout.decode("utf-8", "replace")
        for line in out.splitlines():
            parts = line.split()
            if len(parts) < 2:
                continue
            sym, kind = parts[0], parts[1]
            if sym.startswith(COMPILER_SYMBOLS):
                continue
            first = first_component(sym)
            if kind in STRONG and first not in api:
                return (f"{shown}: defines '{demangle(sym)}' with external linkage: only the "
                        "lab's functions may be global (make helpers static or put them in an "
                        "anonymous namespace)")
            if kind in WEAK and first not in allowed:
                return (f"{shown}: defines '{demangle(sym)}' with external linkage (an inline "
                        "function or class of its own): make it static or put it in an "
                        "anonymous namespace")
    return ""


def demangle(sym):
    try:
        out = subprocess.run(["c++filt", sym], stdout=subprocess.PIPE, timeout=10).stdout
        return out.decode("utf-8", "replace").strip()[:200]
    except (OSError, subprocess.SubprocessError):
        return sym[:200]
