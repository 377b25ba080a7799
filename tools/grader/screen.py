"""Screening of submitted student files before anything is built (defence in depth: the
verdict never depends on it). The allow-list and deny-list live here, at the top.

Trust: reads untrusted text; runs the preprocessor on it (never the code)."""
import itertools
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
                        "sleep usleep nanosleep sleep_for sleep_until clock_gettime "
                        "clock_getres clock_nanosleep gettimeofday timespec_get sched_yield",
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
                     "filesystem rdbuf fopen64 freopen64 tmpfile64 setvbuf setbuf setbuffer "
                     "setlinebuf fileno getc_unlocked getchar_unlocked putc_unlocked "
                     "putchar_unlocked fgetc_unlocked fputc_unlocked fgets_unlocked "
                     "fputs_unlocked fread_unlocked fwrite_unlocked fflush_unlocked",
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
# Identifiers refused in the raw text, before preprocessing: what the preprocessor evaluates
# against the file system (whether a file exists). The screening and the build must read
# exactly the same files; a condition on a file's existence (the worker binary, an object of
# an earlier build) could be false when screening and true when compiling. Token pasting
# (## or %:%:) is refused too, so that no such name can be assembled from pieces.
DENIED_RAW_IDENTIFIERS = {"__has_include", "__has_include_next"}
# Text refused inside a string literal (paths to other processes, devices, the
# grader's own folders).
DENIED_IN_STRINGS = ["/proc", "/dev/", "/sys/", "/autograder", "/tmp"]
SCREEN_TIMEOUT = 60  # s, preprocessing one student file
SCREEN_OUTPUT_CAP = 64 * 1024 * 1024  # bytes of preprocessed text (a macro bomb is refused)

_DENIED = {w: why for why, words in DENIED_IDENTIFIERS.items() for w in words.split()}
# The compiler's pseudo-files of a preprocessed text's prelude (GCC's and clang's spellings).
PRELUDE = ('"<built-in>"', '"<command-line>"', '"<command line>"')

class Refused(Exception):
    """A student file that breaks a screening rule (the message names line and rule)."""


_ID_START = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_$")
_ID_CHAR = _ID_START | set("0123456789")
_RAW_PREFIXES = {"R", "u8R", "uR", "UR", "LR"}
_STR_PREFIXES = {"u8", "u", "U", "L"}
_TRIGRAPH = re.compile(r"\?\?[=/'()!<>-]")
# A line splice as g++ reads it: a backslash, any horizontal white space (a CR of a CR LF line
# end among it; g++ only warns), then the newline. Every place that reads a splice uses this.
_SPLICE = re.compile(r"\\[ \t\f\v\r]*\n")


def tokenize(text, name="", first_line=1):
    """The C++ tokens of `text` as (kind, text, line, at_line_start): kind is "id", "num",
    "str" (also char literals), "raw" (raw string literals), "punct" or "hash" (a # or %:
    that starts a logical line, i.e. a directive). Linear, one pass, as the compiler reads:
    line splices, // comments continued by a splice, raw strings spanning lines (verbatim, no
    splices or escapes), pp-numbers with digit separators (1'000), string and user-defined
    literal prefixes and suffixes. Raises Refused on an unterminated comment or literal."""
    out, i, n, line, start = [], 0, len(text), first_line, True

    def splice(k):
        """Index past any line splices at k (and the lines they join)."""
        nonlocal line
        m = _SPLICE.match(text, k)
        while m:
            k, line = m.end(), line + 1
            m = _SPLICE.match(text, k)
        return k

    def quoted(k, q, what):
        """Index past the literal whose opening quote is at k."""
        nonlocal line
        k += 1
        while True:
            k = splice(k)
            if k >= n or text[k] == "\n":
                raise Refused(f"{name}:{line}: an unterminated {what} literal")
            if text[k] == "\\":
                k = splice(k + 1) + 1
            elif text[k] == q:
                return k + 1
            else:
                k += 1

    def suffix(k):  # a user-defined literal suffix
        while k < n and text[k] in _ID_CHAR:
            k += 1
        return k

    while i < n:
        c = text[i]
        if c == "\\" and _SPLICE.match(text, i):
            i = splice(i)
            continue
        if c == "\n":
            line, start, i = line + 1, True, i + 1
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        tl = line
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                j = splice(i) if text[i] == "\\" else i
                i = j if j != i else i + 1
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            if j < 0:
                raise Refused(f"{name}:{line}: an unterminated /* comment")
            line += text.count("\n", i, j)
            i = j + 2
            continue
        if c in _ID_START:
            j = i
            while j < n and (text[j] in _ID_CHAR or _SPLICE.match(text, j)):
                j = splice(j) if text[j] == "\\" else j + 1
            word = _SPLICE.sub("", text[i:j])
            if word in _RAW_PREFIXES and j < n and text[j] == '"':
                m = re.match(r'"([^()\\\s]{0,16})\(', text[j:j + 20])
                if not m:
                    raise Refused(f"{name}:{line}: a raw string literal with a bad delimiter")
                end = text.find(")" + m.group(1) + '"', j + m.end())
                if end < 0:
                    raise Refused(f"{name}:{line}: an unterminated raw string literal")
                k = suffix(end + len(m.group(1)) + 2)
                out.append(("raw", text[i:k], tl, start))
                line += text.count("\n", i, k)
                i, start = k, False
                continue
            if word in _STR_PREFIXES and j < n and text[j] in "\"'":
                k = suffix(quoted(j, text[j], "string" if text[j] == '"' else "character"))
                out.append(("str", text[i:k], tl, start))
                i, start = k, False
                continue
            out.append(("id", word, tl, start))
            i, start = j, False
            continue
        if c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
            j = i + 1
            while j < n:
                if text[j] in _ID_CHAR or text[j] == ".":
                    j += 1
                elif text[j] == "\'" and j + 1 < n and text[j + 1] in _ID_CHAR:
                    j += 2
                elif text[j] in "+-" and text[j - 1] in "eEpP":
                    j += 1
                elif _SPLICE.match(text, j):
                    j = splice(j)
                else:
                    break
            out.append(("num", text[i:j], tl, start))
            i, start = j, False
            continue
        if c in "\"'":
            k = suffix(quoted(i, c, "string" if c == '"' else "character"))
            out.append(("str", text[i:k], tl, start))
            i, start = k, False
            continue
        if c == "#" or text.startswith("%:", i):
            width = 1 if c == "#" else 2
            out.append(("hash" if start else "punct", text[i:i + width], tl, start))
            i, start = i + width, False
            continue
        out.append(("punct", c, tl, start))
        i, start = i + 1, False
    return out


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

    def check(self, name, data, build=None):
        """Raises Refused naming the line and the rule; returns None if the file may be built.
        build: (path, compiler command, folder) of the file in the scratch build: the file is
        written there and preprocessed with exactly the build's command (flags, dialect, the
        force-included precompiled header), in the folder the build runs it in (a path through
        /proc/self/cwd names the same file), so that the text screened is the text compiled."""
        if b"\0" in data:
            raise Refused(f"{name}: not a text file (it contains NUL bytes)")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as e:
            raise Refused(f"{name}: not UTF-8 text (byte {e.start})")
        self._directives(name, text)
        self._preprocessed(name, data, build)

    def _directives(self, name, text):
        m = _TRIGRAPH.search(text)
        if m:
            raise Refused(f"{name}:{text.count(chr(10), 0, m.start()) + 1}: trigraphs (??x) are "
                          "not allowed in student code")
        toks = tokenize(text, name)
        for kind, tok, no, _ in toks:
            if kind == "raw" and re.search(r"\n\s*(#|%:)", tok):
                raise Refused(f"{name}:{no}: a raw string literal with a line that starts with "
                              "# (it would look like a directive to the screening)")
        for k, (kind, tok, no, _) in enumerate(toks):
            if kind == "id" and tok in DENIED_RAW_IDENTIFIERS:
                raise Refused(f"{name}:{no}: {tok} is not allowed in student code (it asks the "
                              "preprocessor whether a file exists: what the screening reads must "
                              "be what the build reads)")
            if (kind == "punct" and tok in ("#", "%:") and k + 1 < len(toks) and
                    toks[k + 1][0] == "punct" and toks[k + 1][1] in ("#", "%:")):
                raise Refused(f"{name}:{no}: token pasting (##) is not allowed in student code "
                              "(it can assemble names the screening refuses)")
            if kind != "hash":
                continue
            rest = list(itertools.takewhile(lambda t: not t[3], toks[k + 1:]))  # logical line
            first = rest[0] if rest else ("id", "", no, False)
            word = first[1] if first[0] == "id" else ("line" if first[0] == "num" else first[1])
            if word not in ALLOWED_DIRECTIVES:
                raise Refused(f"{name}:{no}: #{word[:10]} is not allowed in student code "
                              f"(allowed: {', '.join('#' + d for d in sorted(ALLOWED_DIRECTIVES) if d)})")
            if word == "include":
                args = rest[1:]
                inc = None
                if len(args) == 1 and args[0][0] == "str" and args[0][1].startswith('"'):
                    inc = args[0][1][1:-1]
                elif len(args) >= 3 and args[0][1] == "<" and args[-1][1] == ">":
                    inc = "".join(t[1] for t in args[1:-1])
                if not inc:
                    raise Refused(f"{name}:{no}: #include must name a header literally, as "
                                  '"header.h" or <header>')
                if not self.allowed_include(inc):
                    raise Refused(f"{name}:{no}: #include {inc}: not on the allow-list (the lab's "
                                  "headers, wb/*.h, <Eigen/...> and the numeric and container "
                                  "headers of the standard library, docs/grading.md)")

    def _preprocessed(self, name, data, build=None):
        with tempfile.TemporaryDirectory(prefix="wb-screen-") as tmp:
            cwd = tmp
            if build:  # the build's own command, -c/-o replaced by -E, in the build's folder
                path, cmd, cwd = build
                cwd = cwd or tmp
                try:
                    with open(path, "rb") as f:
                        same = f.read() == data
                except OSError:
                    same = False
                if not same:  # (rewriting it would make the build recompile it)
                    with open(path, "wb") as f:
                        f.write(data)
                cmd = preprocess_command(cmd, path)
            else:  # no build folder yet: as the Release build compiles it
                path = os.path.join(tmp, name)
                with open(path, "wb") as f:
                    f.write(data)
                cmd = ["g++", "-E", "-std=c++17", "-O3", "-DNDEBUG"]
                for d in self.lab_dirs:
                    cmd += ["-I", d]
                cmd += ["-I", os.path.join(self.repo, "framework", "include"), "-isystem",
                        self.eigen, path]
            rc, out, err = run_collect(cmd, SCREEN_TIMEOUT, SCREEN_OUTPUT_CAP, cwd=cwd)
            if rc is None:
                raise Refused(f"{name}: preprocessing took longer than {SCREEN_TIMEOUT} s")
            if rc == -1:
                raise Refused(f"{name}: preprocesses to more than "
                              f"{SCREEN_OUTPUT_CAP // (1024 * 1024)} MiB of text")
            if rc != 0:
                msg = err.decode("utf-8", "replace").replace(os.path.dirname(path) + "/", "")
                raise Refused(f"{name}: the preprocessor refused it:\n" +
                              "\n".join(msg.strip().splitlines()[-20:]))
            self._tokens(name, path, out.decode("utf-8", "replace"))

    def _tokens(self, name, path, text):
        """Checks the tokens that come from the student file itself in the preprocessed text.
        The linemarkers (# N "file" flags) say where each line came from; a marker that
        leaves the student file other than by entering an #include (flag 1), or comes back
        to a file other than the one that included (flag 2), is a #line in disguise."""
        stack, line, segments, seg, started = [], 0, [], None, False
        content = False  # a line of the student file itself seen yet
        quoted = '"' + path + '"'
        for raw in text.split("\n"):
            m = re.match(r'^# (\d+) ("(?:\\.|[^"\\])*")((?: \d)*)\s*$', raw)
            if m:
                target, flags = m.group(2), m.group(3).split()
                current = stack[-1] if stack else None
                if "1" in flags:
                    # clang's prelude enters <built-in> from the file (flag 1) before its first
                    # line; nothing a file can write enters a pseudo-file.
                    if current == quoted and not (target in PRELUDE and not content):
                        self._direct_include(name, line - 1, target[1:-1])
                    stack.append(target)
                elif "2" in flags:
                    if len(stack) < 2 or stack[-2] != target:
                        raise Refused(f"{name}:{line}: the preprocessor's line markers do not "
                                      "nest (a #line directive?)")
                    stack.pop()
                elif not stack:
                    stack.append(target)
                elif target != current:
                    # GCC's prelude switches between the file, <built-in> and <command-line>
                    # until the file's line 1; after that a switch is a #line directive.
                    if started:
                        raise Refused(f"{name}:{line}: a line marker switches files inside the "
                                      "student file (a #line directive?)")
                    stack[-1] = target
                if len(stack) == 1 and stack[0] == quoted and int(m.group(1)) >= 1 and \
                        not flags:
                    started = True
                line, seg = int(m.group(1)), None
                continue
            if stack and stack[-1] == quoted:
                content = True
                if raw.lstrip().startswith("#"):
                    raise Refused(f"{name}:{line}: #pragma is not allowed in student code")
                if seg is None:
                    seg = [line, []]
                    segments.append(seg)
                seg[1].append(raw)
            else:
                seg = None
            line += 1
        for first, lines in segments:
            for kind, tok, no, _ in tokenize("\n".join(lines), name, first):
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




def preprocess_command(cmd, path):
    """A compile command (compile_commands.json) turned into the same preprocessing: every
    flag kept (dialect, optimisation, definitions, include paths, -include of the precompiled
    header's text), dependency-file flags, -c and -o dropped, -E added."""
    out, k = [], 0
    while k < len(cmd):
        a = cmd[k]
        if a in ("-o", "-MF", "-MT", "-MQ"):
            k += 2
            continue
        if a in ("-c", "-MD", "-MMD") or a == path:
            k += 1
            continue
        out.append(a)
        k += 1
    return out + ["-E", path]
