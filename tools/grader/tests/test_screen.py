"""Screening (tools/grader/screen.py): the tokenizer and the rules checked on a student file's
text before anything is built. Screening is defence in depth, never the wall; these tests
guard against the screening reading the text differently from the compiler (then a denied
name slips through, or honest code is refused)."""
import os

import pytest

from grader import screen
from grader.screen import Refused, Screen, tokenize

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def kinds(text):
    return [(k, t) for k, t, _, _ in tokenize(text)]


def test_splices_join_identifiers_and_continue_comments():
    """Defect: a backslash-newline read differently from the compiler: `sys\\<newline>tem`
    is one identifier to g++, and a // comment continued by a splice hides the next line."""
    assert ("id", "system") in kinds("sys\\\ntem(x);")
    toks = kinds("// comment \\\nsystem(x);\nint y;")
    assert ("id", "system") not in toks and ("id", "y") in toks


@pytest.mark.parametrize("splice", ["\\\r\n", "\\ \n", "\\\t \r\n", "\\\f\n"])
def test_every_splice_gcc_reads_joins_like_a_plain_one(splice):
    """Defect (red team, session 7): a backslash, a CR and a newline (a Windows line end), or
    a backslash and spaces before the newline, is a splice to g++ (it only warns), but ended
    the screening's identifier there: `__has_<splice>include` passed as two harmless names
    while g++ read the refused `__has_include`. Line numbers keep counting the joined lines."""
    toks = tokenize(f"#if __has_{splice}include(\"x\")\n#endif\nsys{splice}tem(1);\nint y;")
    assert [t for k, t, _, _ in toks if k == "id"][:2] == ["if", "__has_include"]
    assert ("id", "system", 4) in [(k, t, line) for k, t, line, _ in toks]
    assert next(line for k, t, line, _ in toks if t == "y") == 6
    with pytest.raises(Refused) as e:
        lab_screen()._directives("f.cpp", f"#if __has_{splice}include(\"/x\")\n#endif\n")
    assert "__has_include" in str(e.value)


def test_the_screen_preprocesses_in_the_folder_the_build_compiles_in(tmp_path, monkeypatch):
    """Defect (red team, session 7): the screening's preprocessor ran in the grader's folder,
    the build's compiler in the build's: a path through /proc/self/cwd named a different file
    in each, so the text screened was not the text compiled."""
    build, src, seen = tmp_path / "build", tmp_path / "explicit_euler.cpp", []
    build.mkdir()

    def run_collect(cmd, timeout, cap, cwd=None):
        seen.append(cwd)
        return 0, b"", b""
    monkeypatch.setattr(screen, "run_collect", run_collect)
    cmd = ["g++", "-std=c++17", "-c", str(src), "-o", "x.o"]
    lab_screen().check("explicit_euler.cpp", b"int f();\n", (str(src), cmd, str(build)))
    assert seen == [str(build)]


def test_raw_strings_are_verbatim_and_tracked_over_lines():
    """Defect: a raw string's content read as code (a false refusal) or a line count that
    drifts after it (the refusal names the wrong line)."""
    toks = tokenize('auto s = R"x(system("a")\n)x";\nexit(0);')
    assert [t for k, t, _, _ in toks if k == "raw"] == ['R"x(system("a")\n)x"']
    assert next(line for k, t, line, _ in toks if t == "exit") == 3


def test_numbers_with_digit_separators_and_exponents():
    """Defect: 1'000 or 1e-5 split into several tokens (a quote opening a bogus char literal
    refuses honest code)."""
    assert kinds("x = 1'000'000 + 1.5e-5 + 0x1p+3;") == [
        ("id", "x"), ("punct", "="), ("num", "1'000'000"), ("punct", "+"),
        ("num", "1.5e-5"), ("punct", "+"), ("num", "0x1p+3"), ("punct", ";")]


def test_directives_are_hash_tokens_only_at_line_start():
    """Defect: a # in the middle of a line taken as a directive, or %: (the digraph) missed."""
    toks = tokenize("#include <cmath>\nint a = b # c;\n%:define X 1\n")
    assert [(k, t) for k, t, _, _ in toks if k == "hash"] == [("hash", "#"), ("hash", "%:")]


@pytest.mark.parametrize("text", ['char* s = "abc;\n', "/* never closed", "char c = 'a;\n",
                                  'auto s = R"x(never closed'])
def test_unterminated_literals_and_comments_are_refused(text):
    """Defect: an unterminated literal swallowed to the end of the file, hiding what follows
    from the screening while the compiler reads it differently."""
    with pytest.raises(Refused):
        tokenize(text, "f.cpp")


def lab_screen():
    return Screen(REPO, "euler")


@pytest.mark.parametrize("text,rule", [
    ("#pragma GCC optimize(\"O0\")\n", "#pragma"),
    ("#line 10 \"other.cpp\"\n", "#line"),
    ("#include <fstream>\n", "not on the allow-list"),
    ("#include MACRO\n", "must name a header literally"),
    ("int a ??= 1;\n", "trigraphs"),
    ('auto s = R"(\n#include <fstream>\n)";\n', "raw string literal"),
])
def test_directive_rules_refuse_with_the_line_and_rule(text, rule):
    """Defect: a directive the compiler acts on (#pragma, #line, an include off the
    allow-list) accepted, or refused without naming the rule."""
    with pytest.raises(Refused) as e:
        lab_screen()._directives("explicit_euler.cpp", text)
    assert rule in str(e.value) and "explicit_euler.cpp:" in str(e.value)


def test_allowed_includes():
    """Defect: the allow-list too tight (the lab's own headers, wb/*.h, Eigen refused) or too
    loose (a path with .. or an unlisted standard header accepted)."""
    s = lab_screen()
    assert s.allowed_include("explicit_euler.h") and s.allowed_include("Eigen/Dense")
    assert s.allowed_include("cmath") and not s.allowed_include("fstream")
    assert not s.allowed_include("Eigen/../../etc/passwd")


HEADER = os.path.join(REPO, "labs", "euler", "explicit_euler.h")  # on the allow-list


def preprocessed(path, body, header_body="int helper();"):
    """A text shaped like g++ -E's, with line markers: the student file includes a header."""
    return (f'# 0 "{path}"\n# 0 "<built-in>"\n# 0 "<command-line>"\n# 1 "{path}"\n'
            f'# 1 "{HEADER}" 1\n{header_body}\n# 2 "{path}" 2\n{body}\n')


def test_denied_names_only_in_the_student_files_own_tokens(tmp_path):
    """Defect: a denied identifier in an included (trusted) header refuses honest code, or one
    that a macro expands to inside the student file slips through."""
    s, path = lab_screen(), str(tmp_path / "f.cpp")
    s._tokens("f.cpp", path, preprocessed(path, "int f() { return 1; }", "int system(const char*);"))
    with pytest.raises(Refused) as e:
        s._tokens("f.cpp", path, preprocessed(path, "int f() { return system(0); }"))
    assert "'system'" in str(e.value) and "processes" in str(e.value)


@pytest.mark.parametrize("body,why", [("int __secret;", "reserved names"),
                                      ("auto p = \"/proc/self\";", "'/proc'"),
                                      ("int _Z3foov;", "mangled names")])
def test_reserved_names_and_paths_in_strings(tmp_path, body, why):
    """Defect: a reserved or mangled name (a way to reach internals) or a path to /proc in a
    string accepted."""
    path = str(tmp_path / "f.cpp")
    with pytest.raises(Refused) as e:
        lab_screen()._tokens("f.cpp", path, preprocessed(path, body))
    assert why in str(e.value)


def test_an_include_resolved_off_the_allow_list(tmp_path):
    """Defect: an allowed name that resolves to another file (a header of the same name
    earlier on the include path) is not checked where it really leads."""
    path = str(tmp_path / "f.cpp")
    text = preprocessed(path, "int a;").replace(HEADER, "/usr/include/fstream")
    with pytest.raises(Refused) as e:
        lab_screen()._tokens("f.cpp", path, text)
    assert "/usr/include/fstream" in str(e.value)


def test_line_marker_switching_files_is_a_disguised_line_directive(tmp_path):
    """Defect: a #line made by a macro (line markers that switch files inside the student
    file) lets later lines pass as a header's."""
    path = str(tmp_path / "f.cpp")
    text = preprocessed(path, "int a;") + '# 5 "/usr/include/other.h"\nint system;\n'
    with pytest.raises(Refused) as e:
        lab_screen()._tokens("f.cpp", path, text)
    assert "line marker" in str(e.value)


def test_preprocess_command_keeps_flags_and_drops_outputs():
    """Defect: the screening preprocesses with other flags than the build compiles with (the
    text screened is not the text compiled), or writes the build's object file."""
    cmd = ["g++", "-DX=1", "-O3", "-MD", "-MT", "a.o", "-MF", "a.d", "-o", "a.o", "-c", "/s/f.cpp"]
    assert screen.preprocess_command(cmd, "/s/f.cpp") == ["g++", "-DX=1", "-O3", "-E", "/s/f.cpp"]


def test_check_runs_the_preprocessor_on_a_macro_hidden_call(tmp_path):
    """Defect: a denied call hidden behind a macro (the text has no 'system', the compiled code
    has) is accepted. Token pasting, the way to build such a name, is refused on the text
    itself (issue 29: it can assemble names the screening refuses)."""
    code = b'#define CALL(f) f##tem\nvoid g() { CALL(sys)("ls"); }\n'
    with pytest.raises(Refused) as e:
        lab_screen().check("explicit_euler.cpp", code)
    assert "token pasting" in str(e.value)
    with pytest.raises(Refused):
        lab_screen().check("explicit_euler.cpp", b"int a;\0")


def test_clangs_prelude_is_not_an_include_of_the_student_file(tmp_path):
    """Defect (issue 44): with clang (macOS's compiler; tools/clang-check) every submission was
    refused, "an #include resolved to <built-in>": clang's -E enters <built-in> from the file
    (flag 1) before its first line, where GCC switches to it without a flag."""
    path = str(tmp_path / "f.cpp")
    text = (f'# 1 "{path}"\n# 1 "<built-in>" 1\n# 1 "<built-in>" 3\n# 404 "<built-in>" 3\n'
            f'# 1 "<command line>" 1\n# 1 "<built-in>" 2\n# 1 "{HEADER}" 1\nint helper();\n'
            f'# 2 "<built-in>" 2\n# 1 "{path}" 2\nint f() {{ return 1; }}\n')
    lab_screen()._tokens("f.cpp", path, text)
    with pytest.raises(Refused) as e:  # after the file's first line, it is an include again
        lab_screen()._tokens("f.cpp", path, text + '# 1 "<built-in>" 1\nint g;\n# 3 "' + path
                             + '" 2\n')
    assert "<built-in>" in str(e.value)
