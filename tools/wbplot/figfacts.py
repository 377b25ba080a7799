"""Facts about the figures tools/plot draws, read by the report's own checks (figcheck.py).

While recording (tools/report turns it on around each tools/plot command), every PNG that
common.save_figure writes and every frame an animation grabs leaves here what a reader would
see of it: its words (titles, labels, legends, notes), and for each axes its scales and view
limits, and the drawings the figure tagged as bodies or as the scene's fixed geometry:

    tag(artist, "body", points)                          a body's outline or path
    tag(artist, "plane", points, point=o, normal=n)      a plane of the scene, as drawn
    tag(artist, "hinge", points, anchor=a, axis=u)       a hinge axis of the scene, as drawn

so that figcheck can tell whether the view fits the bodies and the fixed geometry is drawn
where the scene puts it. Recording costs a walk over the figure's artists per saved file
(and per animation frame): milliseconds.
"""
import contextlib
import math
import os

_RECORD = None  # {absolute path: facts} while recording, else None


@contextlib.contextmanager
def recording():
    """Collects the facts of every figure saved inside the block: {path: facts}."""
    global _RECORD
    outer, _RECORD = _RECORD, {}
    try:
        yield _RECORD
    finally:
        got, _RECORD = _RECORD, outer
        if outer is not None:
            outer.update(got)


def tag(artist, kind, points, **meta):
    """Marks a drawn artist as a body or a piece of the scene's fixed geometry (see above);
    returns it. `points` are the drawn coordinates (2 or 3 per point)."""
    artist._wb_tag = dict(meta, kind=kind, points=[tuple(float(c) for c in p) for p in points])
    return artist


def _texts(fig):
    out = [t.get_text() for t in fig.texts]
    sup = getattr(fig, "_suptitle", None)
    if sup is not None:
        out.append(sup.get_text())
    for ax in fig.axes:
        out += [ax.get_title(loc=loc) for loc in ("left", "center", "right")]
        out += [ax.get_xlabel(), ax.get_ylabel()]
        if hasattr(ax, "get_zlabel"):
            out.append(ax.get_zlabel())
        leg = ax.get_legend()
        if leg is not None:
            out += [t.get_text() for t in leg.get_texts()]
        out += [t.get_text() for t in ax.texts]
    return [t for t in out if t]


def _axes_facts(ax):
    is3d = hasattr(ax, "get_zlim")
    ax.apply_aspect()  # the position an equal-aspect axes will really take
    f = {"is3d": is3d, "xlim": tuple(ax.get_xlim()), "ylim": tuple(ax.get_ylim()),
         "xscale": ax.get_xscale(), "yscale": ax.get_yscale(),
         "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
         "position": tuple(ax.get_position().bounds),
         "drawn": len(ax.lines) + len(ax.collections) + len(ax.patches),
         "aspect": ax.get_aspect(), "tags": []}
    if is3d:
        f.update(zlim=tuple(ax.get_zlim()), zscale=ax.get_zscale(), zlabel=ax.get_zlabel(),
                 computed_zorder=getattr(ax, "computed_zorder", True))
    for art in list(ax.lines) + list(ax.collections) + list(ax.patches):
        t = getattr(art, "_wb_tag", None)
        if t is not None:
            f["tags"].append(dict(t, zorder=art.get_zorder(), visible=art.get_visible()))
    return f


def note(fig, path):
    """Records `fig` as saved to `path` (a PNG, or one more frame of a GIF)."""
    if _RECORD is None:
        return
    key = os.path.abspath(path)
    facts = _RECORD.setdefault(key, {"path": key, "texts": [], "frames": []})
    for t in _texts(fig):
        if t not in facts["texts"]:
            facts["texts"].append(t)
    w, h = fig.get_size_inches()
    facts["frames"].append({
        "size_in": (float(w), float(h)),
        "axes": [_axes_facts(ax) for ax in fig.axes
                 if ax.get_visible() and not hasattr(ax, "_colorbar")]})


def finite_points(points):
    return [p for p in points if all(math.isfinite(c) for c in p)]
