"""The worker's marshalling generated from a lab's headers (tools/grader/stubs.py, generate):
what crosses the process boundary between the trusted tests and the student's code. Guards
against a cache class (the implicit lab's UpperBlocks, a view of A kept in NewtonWorkspace)
read as a struct whose fields must cross, which stops every build of the lab's grader, and
against a marked class that is sent anyway."""
import os

from grader import stubs

HEADER = """#pragma once
#include <vector>
// grader: not data: View Helper
class View : public Base<View> {
 public:
  void compute(const std::vector<double>& a);
 private:
  std::vector<int> pattern_;
};
class Helper {
 private:
  std::vector<double> inv_;
};
struct Workspace {
  std::vector<double> dv;
  View view;
};
void step(Workspace& ws, double h);
"""


def _generate(tmp_path, header):
    lab = tmp_path / "labs" / "demo"
    lab.mkdir(parents=True)
    (lab / "demo.h").write_text(header, encoding="utf-8")
    return stubs.generate(str(tmp_path), "demo")["demo_rpc.h"]


def test_a_class_marked_not_data_is_never_sent(tmp_path):
    """Defect: a class the header marks as a cache (not data) is marshalled field by field (its
    private fields are not read, and the generated size check stops the build), or a struct
    holding it has no put/get for it."""
    rpc = _generate(tmp_path, HEADER)
    assert "inline void put(Out&, const ::View&) {}" in rpc
    assert "inline void get(In&, ::View&) {}" in rpc
    assert "inline void put(Out&, const ::Helper&) {}" in rpc
    assert "Mirror" not in "".join(l for l in rpc.splitlines() if "::View" in l or "::Helper" in l)
    # The struct that holds it still sends its data, and the cache through the no-op.
    assert "inline void put(Out& o, const ::Workspace& v) { put(o, v.dv); put(o, v.view); }" in rpc


def test_without_the_mark_a_class_is_a_struct_to_send(tmp_path):
    """Defect: the mark is read from somewhere else than its own line (a class not marked would
    silently not cross, and the student's code would see it empty)."""
    rpc = _generate(tmp_path, HEADER.replace("// grader: not data: View Helper\n",
                                             "// a comment about grader: not data: View\n"))
    assert "inline void put(Out&, const ::View&) {}" not in rpc
    assert "inline void put(Out& o, const ::Helper& v)" in rpc


def test_the_implicit_labs_view_of_A_is_marked():
    """Defect: the implicit lab's header loses its mark, and the grader's worker cannot be built
    (NewtonWorkspace holds an UpperBlocks)."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(__file__))))
    path = os.path.join(root, "labs", "implicit", "upper_blocks.h")
    if not os.path.exists(path):  # a pack without the implicit lab
        return
    assert stubs.not_data(path) == ["UpperBlocks", "UpperBlocksJacobi"]
