"""Per-lab report plug-ins: tools/wbplot/labs/<lab>.py (see docs/report.md).

A plug-in module may define
    REPLACES_GENERIC = True   # the generic particle figures are not drawn for its scenes
    def scene_figures(ctx): ...  # draws the lab's own figures for one scene
ctx (tools/report's SceneContext) offers: ctx.lab, ctx.stem, ctx.doc (the scene JSON),
ctx.scene_path, ctx.exe (the solution executable), ctx.out_dir, ctx.integrators
[(name, order, description)], ctx.run(argv_tail, what, label=, save=, again=) -> summary
dict or None (again=True: a repeat of the last run, whose table row it replaces),
ctx.plot(args) -> bool (tools/plot in-process), ctx.figure(path, caption, plot_args),
ctx.table(title, markdown), ctx.path(name) -> a file in the lab's report folder.

It may also add tools/plot subcommands (so that a student plots their own run):
    def add_commands(sub): ...   # sub.add_parser("bodies", ...) on tools/plot's subparsers
    def run(args) -> bool: ...   # True when args.command is one of its own
"""
