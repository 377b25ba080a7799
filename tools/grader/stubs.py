"""Generates, from a lab's headers, the two halves of its worker: the client stubs the trusted
test process links instead of the lab's functions, and the worker's dispatcher that calls the
real ones; plus the field-by-field marshalling of the lab's structs (tools/grader/cpp/).

Trust: reads pristine headers only; the code it writes runs on both sides of the boundary.
The headers are parsed for what they hold today: free function declarations (not inline),
plain structs with data members, namespaces. Anything else at the top level is skipped;
a struct member this parser does not understand is an error (never silently not sent)."""
import os
import re

from .common import Defect

TYPE_WORDS = {"int", "long", "short", "double", "float", "char", "bool", "unsigned", "signed",
              "const", "auto", "void"}
TYPE_PREFIXES = {"const", "unsigned", "signed"}  # "const x": x is the type, not a name
FRAMEWORK_STRUCT_HEADERS = ["framework/include/wb/dynamics.h"]  # wb::Scratch
# A lab header names the classes it declares that are caches, not data, on a line of its own:
#   // grader: not data: UpperBlocks UpperBlocksJacobi
# (the implicit lab's CG view of A, kept in NewtonWorkspace: what A determines). Nothing of them
# crosses the process boundary, as for NewtonWorkspace::ldlt (wb_rpc.h): each side keeps its
# own, the worker's starts empty on every call, and the lab's code computes it again.
NOT_DATA = re.compile(r"^// grader: not data:((?:[ \t]+[A-Za-z_]\w*)+)[ \t]*$", re.M)


def not_data(path):
    """The classes a header marks as caches, not data (NOT_DATA)."""
    with open(path, encoding="utf-8") as f:
        return [name for m in NOT_DATA.finditer(f.read()) for name in m.group(1).split()]


def _strip(text):
    """Comments and preprocessor lines removed (string literals do not occur in these headers)."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    return "\n".join("" if l.lstrip().startswith("#") else l for l in text.split("\n"))


def _match(text, i, open_c="{", close_c="}"):
    """Index just past the bracket closing the one at text[i]."""
    depth = 0
    for j in range(i, len(text)):
        if text[j] == open_c:
            depth += 1
        elif text[j] == close_c:
            depth -= 1
            if depth == 0:
                return j + 1
    raise Defect(f"unbalanced {open_c}{close_c} in a lab header")


def _split_top(s, sep=","):
    out, depth, cur = [], 0, ""
    for c in s:
        if c in "(<{[":
            depth += 1
        elif c in ")>}]":
            depth -= 1
        if c == sep and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += c
    if cur.strip():
        out.append(cur)
    return out


def _cut_init(decl):
    """'T name = 1' or 'T name{1}' -> 'T name'."""
    depth = 0
    for k, c in enumerate(decl):
        if c in "(<[":
            depth += 1
        elif c in ")>]":
            depth -= 1
        elif depth == 0 and c in "={":
            return decl[:k].strip()
    return decl.strip()


def _statements(body):
    """Top-level statements of a scope: (kind, head, block) with kind 'stmt' (ended by ';'),
    'block' (head followed by {...})."""
    out, i, head = [], 0, ""
    while i < len(body):
        c = body[i]
        if c == ";":
            if head.strip():
                out.append(("stmt", " ".join(head.split()), ""))
            head = ""
            i += 1
        elif c == "{":
            h = " ".join(head.split())
            is_init = ("=" in h.split("(")[0]) or (re.search(r"[\w>]\s*$", h) and "(" not in h
                                                   and not re.match(r"(struct|class|enum|namespace|union)\b", h))
            j = _match(body, i)
            if is_init:  # a brace initializer: part of the statement
                head += body[i:j]
                i = j
                continue
            out.append(("block", h, body[i + 1:j - 1]))
            head = ""
            i = j
            while i < len(body) and body[i] in " \t\n":
                i += 1
            if i < len(body) and body[i] == ";":
                i += 1
        else:
            head += c
            i += 1
    return out


class Header:
    def __init__(self):
        self.functions = []  # (namespace, return type, name, [(param text, name)])
        self.structs = []    # (qualified name, [field names])


def parse(path, structs_only=False):
    with open(path, encoding="utf-8") as f:
        text = _strip(f.read())
    h = Header()

    def scope(body, ns):
        for kind, head, block in _statements(body):
            m = re.match(r"namespace\s+(\w+)$", head)
            if kind == "block" and m:
                scope(block, ns + [m.group(1)])
            elif kind == "block" and re.match(r"(struct|class)\s+(\w+)$", head):
                name = head.split()[1]
                h.structs.append(("::".join(ns + [name]), _fields(block, name, path)))
            elif kind == "stmt" and not structs_only and "(" in head and not re.match(
                    r"(using|typedef|constexpr|static_assert|extern|template|inline|static)\b", head):
                h.functions.append(_function(head, ns, path))

    scope(text, [])
    return h


def _function(head, ns, path):
    head = re.sub(r"\[\[[^\]]*\]\]", "", head).strip()
    m = re.fullmatch(r"(.*?)\b([A-Za-z_]\w*)\s*\((.*)\)\s*(noexcept)?", head, re.S)
    if not m or not m.group(1).strip():
        raise Defect(f"{path}: cannot read the declaration '{head}'")
    params = []
    for k, p in enumerate(_split_top(m.group(3))):
        p = _cut_init(p.strip())
        if p in ("", "void"):
            continue
        pm = re.fullmatch(r"(.*[\s&*>])([A-Za-z_]\w*)", p)
        if pm and pm.group(2) not in TYPE_WORDS and pm.group(1).strip() not in TYPE_PREFIXES:
            params.append((p, pm.group(2)))
        else:
            params.append((f"{p} a{k}", f"a{k}"))
    return ns, m.group(1).strip(), m.group(2), params


def _fields(block, name, path):
    names = []
    for kind, head, _ in _statements(block):
        if kind == "block":
            if re.match(r"(enum|struct|class|union)\b", head) or "(" in head:
                continue  # a nested type or a member function
            raise Defect(f"{path}: struct {name}: cannot read '{head}'")
        if re.match(r"(enum|using|typedef|static|constexpr|friend|public|private|protected)\b",
                    head) or head.endswith(":"):
            continue
        decl = head
        if "(" in decl.split("=")[0].split("{")[0]:
            continue  # a member function declaration
        parts = _split_top(decl)
        for k, part in enumerate(parts):
            part = _cut_init(part)
            fm = re.search(r"([A-Za-z_]\w*)\s*$", part)
            if not fm or (k == 0 and not re.search(r"\S\s+[&*]*\s*[A-Za-z_]\w*\s*$", part)):
                raise Defect(f"{path}: struct {name}: cannot read the member '{head}'")
            names.append(fm.group(1))
    return names


def lab_headers(repo, lab):
    d = os.path.join(repo, "labs", lab)
    return [os.path.join(d, f) for f in sorted(os.listdir(d)) if f.endswith(".h")]


def kernel_headers(repo, lab):
    """tests/<lab>/kernels/*.h: loops of long tests, run in the worker as one call."""
    d = os.path.join(repo, "tests", lab, "kernels")
    return [os.path.join(d, f) for f in sorted(os.listdir(d)) if f.endswith(".h")] \
        if os.path.isdir(d) else []


def generate(repo, lab):
    """{file name: text} of <lab>_rpc.h, <lab>_client.cpp and <lab>_worker.cpp: the lab's
    functions and its tests' kernels (tests/<lab>/kernels/*.h)."""
    headers = lab_headers(repo, lab) + kernel_headers(repo, lab)
    functions, structs, caches = [], [], []
    for p in headers:
        h = parse(p)
        functions += h.functions
        structs += h.structs
        caches += not_data(p)
    # A cache is never sent: no marshalling of its fields (it need not be a plain struct).
    structs = [s for s in structs if s[0] not in caches]
    uses_scratch = any("Scratch" in t for f in functions for t, _ in f[3])
    if uses_scratch:
        for p in FRAMEWORK_STRUCT_HEADERS:
            structs += [s for s in parse(os.path.join(repo, p), structs_only=True).structs
                        if s[0] == "wb::Scratch"]
    includes = "".join(f'#include "{os.path.basename(p)}"\n' for p in headers)
    rpc = [f"// Generated by tools/grader/stubs.py from the headers of lab {lab}: do not edit.",
           "// The lab's structs, field by field (wb_rpc.h).", "#pragma once", includes.rstrip(),
           '#include "wb/dynamics.h"', '#include "wb_rpc.h"', "", "namespace wbrpc {"]
    for q in caches:  # caches, not data (NOT_DATA): nothing crosses
        rpc += [f"inline void put(Out&, const ::{q}&) {{}}", f"inline void get(In&, ::{q}&) {{}}"]
    for q, _ in structs:
        rpc += [f"inline void put(Out& o, const ::{q}& v);", f"inline void get(In& in, ::{q}& v);"]
    for q, fields in structs:  # the fewest bytes one of them takes (a vector's count is
        rpc += [f"template <> struct WireMin<::{q}> {{ static constexpr std::size_t value = " +  # checked against it)
                (" + ".join(f"WireMin<std::decay_t<decltype(::{q}::{f})>>::value" for f in fields)
                 or "1") + "; };"]
    for k, (q, fields) in enumerate(structs):
        mirror = " ".join(f"decltype(::{q}::{f}) {f};" for f in fields)
        rpc += [f"struct Mirror{k} {{ {mirror} }};",
                f"static_assert(sizeof(Mirror{k}) == sizeof(::{q}), \"::{q} has members that "
                f"tools/grader/stubs.py did not read: fix the parser\");",
                f"inline void put(Out& o, const ::{q}& v) {{ " +
                " ".join(f"put(o, v.{f});" for f in fields) + " }",
                f"inline void get(In& in, ::{q}& v) {{ " +
                " ".join(f"get(in, v.{f});" for f in fields) + " }"]
    rpc += ["}  // namespace wbrpc", ""]
    client = [f"// Generated by tools/grader/stubs.py: lab {lab}'s functions, called in the worker.",
              f'#include "{lab}_rpc.h"', '#include "client.h"', ""]
    worker = [f"// Generated by tools/grader/stubs.py: lab {lab}'s calls, dispatched in the worker.",
              f'#include "{lab}_rpc.h"', '#include "worker.h"', "",
              "void wbrpc::dispatch(std::int32_t id, In& in) {", "  switch (id) {"]
    for k, (ns, ret, name, params) in enumerate(functions):
        plist = ", ".join(p for p, _ in params)
        sig = f"{ret}({plist})"
        q = "::".join(ns + [name])
        opens = "".join(f"namespace {n} {{ " for n in ns)
        closes = "}" * len(ns)
        client += [f"{opens}{ret} {name}({plist}) {{",
                   f"  return wbrpc::Caller<{sig}>::call({k}, \"{name}\"" +
                   "".join(f", {n}" for _, n in params) + ");", f"}}{closes}", ""]
        worker += [f"    case {k}:", f"      serve(static_cast<{ret} (*)({plist})>(&::{q}), in);",
                   "      return;"]
    worker += ["  }", '  throw ProtocolError("an unknown function");', "}", ""]
    return {f"{lab}_rpc.h": "\n".join(rpc), f"{lab}_client.cpp": "\n".join(client),
            f"{lab}_worker.cpp": "\n".join(worker)}
