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

# The pack README's plot commands for a lab's run when its plug-in names none (PACK_PLOTS):
# the particle figures of out/run.csv and out/run-stats.csv, with the run's summary
# (out/run-summary.json, the run's stdout) so that a stub's run says so on the figure.
GENERIC_PLOTS = [("tools/plot trace out/run.csv --summary out/run-summary.json -o out/run.png",
                  "trajectories of your run"),
                 ("tools/plot stats out/run-stats.csv --summary out/run-summary.json "
                  "--scene {scene} -o out/run-energy.png", "energy and momentum against time")]
