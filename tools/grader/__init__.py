"""tools/grade split into layers: submission, screen, build, sandbox, verdict, results (docs/grading.md)."""
