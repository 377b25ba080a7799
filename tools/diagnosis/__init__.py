"""The diagnosis of a failing task (docs/grading.md, "Diagnosis"): what a submission's functions
do on fixed probe inputs, against the catalogue of the solution's and each known mistake's
outputs on the same inputs.

  hints.py      matches a task's probe outputs with the catalogue: "not started", the mistake,
                the part of the computation, a counterexample (standard library only; shipped
                in the student pack and the Gradescope zip)
  probes.py     runs a failing task's probes through the grader's sandboxed worker and
                diagnoses each failing task of a graded lab (tools/grade)
  catalogue.py  records the catalogue (tests/mutants/<lab>/signatures.json) from the probes
                run on the solution, the skeleton and every mutant, and measures it: the
                leave-one-out figures, the mid-lab check (tools/mutants)

Imports go one way: catalogue and probes use hints and the grader; hints uses nothing of ours.
"""
