"""Screening of submitted student files before anything is built (defence in depth: the
verdict never depends on it). The allow-list and deny-list live here, at the top.

Trust: reads untrusted text; runs the preprocessor on it (never the code)."""
import os
import re
import tempfile

from .procs import run_collect
from .project import lab_deps

# ------------------------------------------------------------------ screening
#
# THE ALLOW-LIST AND THE DENY-LIST (an instructor extends them here, and only
# here; docs/grading.md "Screening" explains them). Every submitted student
# file is checked before anything is built: a file that breaks a rule is
# refused, and its lab scores 0 with a message naming the line and the rule.

# Standard headers a student file may include with <...>. Numeric and
# container headers only: no I/O, no processes, no threads, no clocks.
ALLOWED_STD_HEADERS = {
    "cmath", "vector", "array", "algorithm", "numeric", "limits", "utility", "cstddef",
    "cstdint", "unordered_map", "map", "functional", "tuple", "cassert", "stdexcept",
    "string", "memory", "optional", "climits", "cfloat", "type_traits", "initializer_list",
    "iterator", "set", "unordered_set", "deque", "queue", "complex", "cstdlib",
}
# Besides those: <Eigen/...> (any Eigen module), "wb/<name>.h" (the framework's
# public headers), and "<name>.h" of the lab's own folder and of the labs it
# depends on (wb_lab(<lab> DEPS ...) in CMakeLists.txt), with "..." or <...>.
ALLOWED_HEADER_PREFIXES = ("Eigen/",)
# Preprocessor directives a student file may use. Not #line (it would make the
# preprocessed text lie about which file a line came from), not #pragma (GCC
# pragmas change how code is compiled), not #include_next, #import, #embed.
ALLOWED_DIRECTIVES = {"include", "define", "undef", "if", "ifdef", "ifndef", "elif", "else",
                      "endif", "error", "warning", ""}
# Identifiers refused in a student file, by what they would give access to.
# Checked AFTER preprocessing (a macro cannot hide one) on the tokens that come
# from the student file itself (not from the headers it includes).
DENIED_IDENTIFIERS = {
    "processes": "fork vfork clone clone3 execl execlp execle execv execvp execvpe execve fexecve "
                 "posix_spawn posix_spawnp system popen pclose wait waitpid waitid wait3 wait4 "
                 "kill killpg raise abort exit _exit _Exit quick_exit atexit at_quick_exit "
                 "setsid setpgid setpgrp daemon ptrace prctl syscall getpid getppid unshare "
                 "setns getenv secure_getenv setenv putenv unsetenv environ",
    "signals and jumps": "signal sigaction sigprocmask sigqueue sigsetjmp siglongjmp setjmp "
                         "longjmp alarm pause",
    "threads and time": "thread jthread this_thread async future promise packaged_task "
                        "sleep usleep nanosleep sleep_for sleep_until",
    "files and I/O": "open openat openat2 creat close read write pread pwrite readv writev lseek "
                     "dup dup2 dup3 pipe pipe2 fcntl ioctl mmap munmap mprotect mremap fopen "
                     "freopen fdopen fclose fflush fread fwrite fputs fputc putc putchar puts "
                     "printf fprintf vprintf vfprintf dprintf fgets fgetc getc getchar gets "
                     "scanf fscanf perror tmpfile tmpnam mkstemp mkdtemp unlink unlinkat rename "
                     "renameat link linkat symlink symlinkat readlink truncate ftruncate mkdir "
                     "rmdir chdir fchdir chmod chown opendir readdir scandir stat lstat fstat "
                     "access getcwd realpath fsync sendfile splice memfd_create stdin stdout "
                     "stderr FILE cin cout cerr clog wcin wcout wcerr wclog ofstream ifstream "
                     "fstream filebuf basic_ofstream basic_ifstream basic_fstream basic_filebuf "
                     "filesystem rdbuf",
    "network": "socket connect bind listen accept send recv sendto recvfrom getaddrinfo",
    "dynamic loading": "dlopen dlmopen dlsym dlvsym dlclose dladdr",
    "linkage and machine code": "asm __asm__ __asm extern main __attribute__ __attribute "
                                "__declspec gnu _Pragma",
    "the test framework": "Catch TEST_CASE TEST_CASE_METHOD SCENARIO REQUIRE CHECK SECTION "
                          "SUCCEED FAIL",
}
# Prefixes refused the same way (mangled names, reserved names, Catch's macros).
DENIED_PREFIXES = {"_Z": "mangled names", "pthread_": "threads and time",
                   "CATCH_": "the test framework", "INTERNAL_CATCH": "the test framework"}
# Reserved identifiers (__x, _X) are refused except these, which standard
# macros (assert, NAN, INFINITY, HUGE_VAL) expand to.
ALLOWED_RESERVED = {"__assert_fail", "__extension__", "__PRETTY_FUNCTION__", "__func__",
                    "__FUNCTION__", "__builtin_nan", "__builtin_nanf", "__builtin_nanl",
                    "__builtin_inf", "__builtin_inff", "__builtin_infl", "__builtin_huge_val",
                    "__builtin_huge_valf", "__builtin_huge_vall", "__builtin_expect",
                    "__null", "__cplusplus", "__LINE__", "__FILE__"}
# Text refused inside a string literal (paths to other processes, devices, the
# grader's own folders).
DENIED_IN_STRINGS = ["/proc", "/dev/", "/sys/", "/autograder", "/tmp"]
SCREEN_TIMEOUT = 60  # s, preprocessing one student file
SCREEN_OUTPUT_CAP = 64 * 1024 * 1024  # bytes of preprocessed text (a macro bomb is refused)

_DENIED = {w: why for why, words in DENIED_IDENTIFIERS.items() for w in words.split()}
_TOKEN = re.compile(r"""
    (?P<raw>(?:u8|[uUL])?R"(?P<delim>[^()\\ \t\n]{0,16})\((?:.|\n)*?\)(?P=delim)")
  | (?P<str>(?:u8|[uUL])?"(?:\\.|[^"\\\n])*")
  | (?P<chr>(?:u8|[uUL])?'(?:\\.|[^'\\\n])*')
  | (?P<num>\.?\d(?:[eEpP][+-]|[\w.'])*)
  | (?P<id>[A-Za-z_$][\w$]*)
  | (?P<other>\S)
""", re.X)


class Refused(Exception):
    """A student file that breaks a screening rule (the message names line and rule)."""


def _strip_comments(text):
    """The source with comments replaced by a space and backslash-newlines joined,
    keeping line numbers (each removed newline is put back at the end of its line)."""
    out, i, n, pending = [], 0, len(text), 0
    while i < n:
        c = text[i]
        if c == "\\" and text.startswith("\n", i + 1):
            pending += 1
            i += 2
            continue
        if c == "\n":
            out.append("\n" * (1 + pending))
            pending = 0
            i += 1
            continue
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 2 if text.startswith("\\\n", i) else 1
            out.append(" ")
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            pending += text.count("\n", i, j)
            out.append(" ")
            i = j
            continue
        m = _TOKEN.match(text, i) if c in "\"'RuUL" else None
        if m and (m.group("raw") or m.group("str") or m.group("chr")):
            tok = m.group(0)
            pending += tok.count("\n")
            out.append(tok.replace("\n", " "))
            i = m.end()
            continue
        out.append(c)
        i += 1
    return "".join(out)


class Screen:
    """Screens the student files of one lab (see the lists above)."""

    def __init__(self, repo, lab):
        self.repo, self.lab = repo, lab
        self.lab_dirs = [os.path.join(repo, "labs", l) for l in [lab] + lab_deps(repo, lab)]
        self.lab_headers = {}
        for d in self.lab_dirs:
            for f in sorted(os.listdir(d)) if os.path.isdir(d) else []:
                if f.endswith(".h"):
                    self.lab_headers.setdefault(f, os.path.join(d, f))
        wb_dir = os.path.join(repo, "framework", "include", "wb")
        self.wb_headers = {"wb/" + f: os.path.join(wb_dir, f)
                           for f in (sorted(os.listdir(wb_dir)) if os.path.isdir(wb_dir) else [])
                           if f.endswith(".h")}
        self.eigen = next((d for d in ("/usr/include/eigen3", "/usr/local/include/eigen3")
                           if os.path.isdir(os.path.join(d, "Eigen"))), "/usr/include/eigen3")

    def allowed_include(self, name):
        if name in self.lab_headers or name in self.wb_headers:
            return True
        return name in ALLOWED_STD_HEADERS or (name.startswith(ALLOWED_HEADER_PREFIXES) and
                                               re.fullmatch(r"[A-Za-z0-9_/]+", name) is not None
                                               and ".." not in name)

    def check(self, name, data):
        """Raises Refused naming the line and the rule; returns None if the file may be built."""
        if b"\0" in data:
            raise Refused(f"{name}: not a text file (it contains NUL bytes)")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as e:
            raise Refused(f"{name}: not UTF-8 text (byte {e.start})")
        self._directives(name, text)
        self._preprocessed(name, data)

    def _directives(self, name, text):
        for no, line in enumerate(_strip_comments(text).split("\n"), 1):
            s = line.strip()
            if s.startswith("%:"):
                s = "#" + s[2:]
            if not s.startswith("#"):
                continue
            rest = s[1:].strip()
            word = re.match(r"[A-Za-z_]*", rest).group(0)
            if rest[:1].isdigit():
                word = "line"
            if word not in ALLOWED_DIRECTIVES:
                raise Refused(f"{name}:{no}: #{word or rest[:10]} is not allowed in student code "
                              f"(allowed: {', '.join('#' + d for d in sorted(ALLOWED_DIRECTIVES) if d)})")
            if word == "include":
                m = re.fullmatch(r'include\s*(?:"([^"]+)"|<([^>]+)>)', rest)
                if not m:
                    raise Refused(f"{name}:{no}: #include must name a header literally, as "
                                  '"header.h" or <header>')
                inc = m.group(1) or m.group(2)
                if not self.allowed_include(inc):
                    raise Refused(f"{name}:{no}: #include {inc}: not on the allow-list (the lab's "
                                  "headers, wb/*.h, <Eigen/...> and the numeric and container "
                                  "headers of the standard library, docs/grading.md)")

    def _preprocessed(self, name, data):
        with tempfile.TemporaryDirectory(prefix="wb-screen-") as tmp:
            path = os.path.join(tmp, name)
            with open(path, "wb") as f:
                f.write(data)
            cmd = ["g++", "-E", "-std=gnu++17", "-DNDEBUG"]  # as the Release build compiles it
            for d in self.lab_dirs:
                cmd += ["-I", d]
            cmd += ["-I", os.path.join(self.repo, "framework", "include"), "-isystem", self.eigen,
                    path]
            rc, out, err = run_collect(cmd, SCREEN_TIMEOUT, SCREEN_OUTPUT_CAP)
            if rc is None:
                raise Refused(f"{name}: preprocessing took longer than {SCREEN_TIMEOUT} s")
            if rc == -1:
                raise Refused(f"{name}: preprocesses to more than "
                              f"{SCREEN_OUTPUT_CAP // (1024 * 1024)} MiB of text")
            if rc != 0:
                msg = err.decode("utf-8", "replace").replace(tmp + "/", "").strip().splitlines()
                raise Refused(f"{name}: the preprocessor refused it:\n" + "\n".join(msg[-20:]))
            self._tokens(name, path, out.decode("utf-8", "replace"))

    def _tokens(self, name, path, text):
        current, line, region = None, 0, []
        quoted = '"' + path + '"'
        for raw in text.split("\n"):
            m = re.match(r'^# (\d+) ("(?:\\.|[^"\\])*")((?: \d)*)\s*$', raw)
            if m:
                target, flags = m.group(2), m.group(3).split()
                if "1" in flags and current == quoted:
                    self._direct_include(name, line - 1, target[1:-1])
                current, line = target, int(m.group(1))
                continue
            if current == quoted:
                if raw.lstrip().startswith("#"):
                    raise Refused(f"{name}:{line}: #pragma is not allowed in student code")
                region.append((line, raw))
            line += 1
        for no, raw in region:
            for m in _TOKEN.finditer(raw):
                kind = m.lastgroup
                tok = m.group(0)
                if kind in ("raw", "str"):
                    for bad in DENIED_IN_STRINGS:
                        if bad in tok:
                            raise Refused(f"{name}:{no}: a string containing '{bad}' is not "
                                          "allowed in student code")
                elif kind == "id":
                    why = _DENIED.get(tok)
                    if why is None:
                        why = next((w for p, w in DENIED_PREFIXES.items() if tok.startswith(p)),
                                   None)
                    if why is None and (tok.startswith("__") or re.match(r"_[A-Z]", tok)) and \
                            tok not in ALLOWED_RESERVED:
                        why = "reserved names"
                    if why:
                        raise Refused(f"{name}:{no}: '{tok}' is not allowed in student code "
                                      f"({why}; the list: docs/grading.md, Screening)")

    def _direct_include(self, name, line, target):
        real = os.path.realpath(target)
        ok = any(real == os.path.realpath(p) for p in
                 list(self.lab_headers.values()) + list(self.wb_headers.values()))
        ok = ok or real.startswith(os.path.realpath(self.eigen) + "/Eigen/")
        ok = ok or (os.path.basename(real) in ALLOWED_STD_HEADERS and real.startswith("/usr/")
                    and "/include/" in real)
        if not ok:
            raise Refused(f"{name}:{line}: an #include resolved to {target}, which is not on the "
                          "allow-list")


