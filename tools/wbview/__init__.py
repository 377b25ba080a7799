"""The interactive viewer of a run (tools/view) and its browser test (tools/view-check)."""
import os
import time


def say_written(prog, out, t0, what):
    """The last lines of tools/view and tools/view --live: the page written (its size, the
    time since t0, what it holds) and the address to open it at."""
    size = os.path.getsize(out) / 1e6
    print(f"{prog}: wrote {out} ({size:.1f} MB, {time.monotonic() - t0:.1f} s): {what}")
    print(f"{prog}: open it in a browser, e.g. file://{os.path.abspath(out)}")
