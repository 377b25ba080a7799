"""The workbook's tools, one module per command: tools/<name> is a thin entry that imports
tools/wbtools/<name>.py and calls its entry function (run(); in pattern.py entry(), its run()
being the helper that runs a program), which calls main() with the command line and exits
with its status. The grader's layers (tools/grader/), the figures (tools/wbplot/), the
viewer (tools/wbview/) and the diagnosis of a failing task (tools/diagnosis/) are packages of
their own.

  claims.py         tools/claims              handout claims against the runs
  fresh_machine.py  tools/fresh-machine       the README's commands on brand-new Debian roots
  goals.py          tools/goals               the constraint scenes' measured goals
  hostile.py        tools/gradescope/hostile  hostile submissions against the autograder zip
  mutants.py        tools/mutants             known-wrong code must lose points
  pack.py           tools/pack                the student pack (and the Gradescope zip)
  pattern.py        tools/pattern             the pattern every lab keeps
  report.py         tools/report              the main job: runs, figures, the report
  view_check.py     tools/view-check          the viewer's pages in a headless browser
  browser.py        (view_check.py's)         the headless browser it drives
  docrefs.py        (pattern.py's docrefs)    what the docs quote from the code exists there

Each package's unit tests are in its tests/ folder (python3 -m pytest tools; tools/check
runs them first); neither the student pack nor the Gradescope zip ships them.
"""
