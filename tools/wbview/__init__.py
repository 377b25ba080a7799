"""The interactive viewer of a run (tools/view) and its browser test (tools/view-check)."""
