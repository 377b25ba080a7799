#!/usr/bin/env bash
# Gradescope image set-up: installs the Debian packages, then builds the
# pristine project once so that each submission only recompiles its own files.
set -euo pipefail
root=${AUTOGRADER_ROOT:-/autograder}  # overridable to try it outside Gradescope
cd "$root/source"
bash tools/setup
# The secret the held-out inputs' seeds are derived from (with each submission's files): made
# here, on the image, readable by root only; never in the zip, never seen by a submission.
# A TA replays a grading with the seed its results print (tools/grade --seed).
if [ ! -s "$root/heldout.key" ]; then
  (umask 077 && head -c 32 /dev/urandom > "$root/heldout.key.tmp" && mv "$root/heldout.key.tmp" "$root/heldout.key")
fi
# Grading the skeletons fills the scratch build run_autograder reuses (the
# score, 0, is thrown away).
/usr/bin/python3 tools/grade labs --build-dir "$root/grade-build" --jobs "$(nproc)" >/dev/null
