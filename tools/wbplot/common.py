"""Reading CSV files with clear errors, fixed figure style, atomic PNG writes."""
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

from .errors import InputError  # noqa: E402,F401  (the tools raise it as common.InputError)


# One look for every figure: readable at handout size (about 16 cm wide).
STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 10,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "legend.fontsize": 8.5,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.6,
    "lines.linewidth": 1.4,
    "font.family": "DejaVu Sans",
    "svg.hashsalt": "wb",
    "path.simplify": True,
}


def apply_style():
    matplotlib.rcdefaults()
    matplotlib.rcParams.update(STYLE)


def read_csv(path, required, what="CSV"):
    """Reads a CSV file into a list of dict rows (strings).

    Raises InputError naming the file when it is missing, empty, or lacks one
    of the `required` columns.
    """
    if not os.path.exists(path):
        raise InputError(f"{path}: no such file (expected a {what})")
    if os.path.isdir(path):
        raise InputError(f"{path}: is a folder, expected a {what} file")
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if header is None:
                raise InputError(f"{path}: empty file, expected a {what} with header "
                                 + ",".join(required))
            header = [h.strip() for h in header]
            missing = [c for c in required if c not in header]
            if missing:
                raise InputError(f"{path}: missing column '{missing[0]}' (header is "
                                 f"'{','.join(header)}', expected columns "
                                 f"{','.join(required)})")
            rows = []
            for lineno, rec in enumerate(reader, start=2):
                if not rec or (len(rec) == 1 and not rec[0].strip()):
                    continue
                if len(rec) != len(header):
                    raise InputError(f"{path}:{lineno}: {len(rec)} fields, expected "
                                     f"{len(header)} (header '{','.join(header)}')")
                rows.append(dict(zip(header, rec)))
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: not a text CSV file ({e.reason})") from None
    except csv.Error as e:
        raise InputError(f"{path}: not a valid CSV file ({e})") from None
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    if not rows:
        raise InputError(f"{path}: no data rows after the header, expected at least one")
    return rows


def number(path, row_index, row, column):
    """The float in `column` of a row; 'inf', 'nan' and '' (as nan) are accepted."""
    s = row[column].strip()
    if s == "" or s.lower() in ("nan", "null", "none"):
        return math.nan
    try:
        return float(s)
    except ValueError:
        raise InputError(f"{path}: row {row_index + 2}, column '{column}': got '{s}', "
                         "expected a number") from None


def column(path, rows, name):
    return [number(path, i, r, name) for i, r in enumerate(rows)]


def finite(x):
    return x is not None and math.isfinite(x)


def parse_list(text, flag, conv=str):
    """A comma-separated flag value, each item converted by `conv`."""
    items = [s.strip() for s in text.split(",")]
    if any(s == "" for s in items):
        raise InputError(f"{flag}: got '{text}', expected a comma-separated list without "
                         "empty items")
    out = []
    for s in items:
        try:
            out.append(conv(s))
        except ValueError:
            raise InputError(f"{flag}: item '{s}' in '{text}' is not a valid "
                             f"{getattr(conv, '__name__', 'value')}") from None
    return out


def parse_label_map(text, flag, conv, expected):
    """A flag's LABEL=VALUE,... items as {label: conv(value)}; `expected` names the
    form in the error (for example "LABEL=STEP"). None or "" gives {}."""
    out = {}
    for item in parse_list(text, flag) if text else []:
        name, _, value = item.partition("=")
        try:
            out[name] = conv(value)
        except ValueError:
            raise InputError(f"{flag}: item '{item}': expected {expected}") from None
    return out


def new_figure(*args, **kwargs):
    apply_style()
    return plt.subplots(*args, **kwargs)


def save_figure(fig, path):
    """Writes the figure as PNG to a temporary name beside `path`, then renames it.

    PNG metadata carries no software version or date, so the same data gives the
    same bytes on the same matplotlib.
    """
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        plt.close(fig)
        raise InputError(f"{path}: folder {folder} does not exist")
    tmp = os.path.join(folder, f".{os.path.basename(path)}.tmp-{os.getpid()}")
    finish_frame(fig, path)
    try:
        fig.savefig(tmp, format="png", metadata={"Software": None}, bbox_inches="tight",
                    pad_inches=0.08)
        os.replace(tmp, path)
    except OSError as e:
        raise InputError(f"{path}: cannot write ({e.strerror})") from None
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def summary_line(stdout):
    """The JSON summary a run prints on the last non-empty line of its standard output
    (docs/run-contract.md, "The summary line") as a dict, or None when there is none (no
    output, not JSON, or JSON that is not an object)."""
    import json
    lines = [s for s in stdout.splitlines() if s.strip()]
    try:
        j = json.loads(lines[-1]) if lines else None
    except ValueError:
        return None
    return j if isinstance(j, dict) else None


def finish_frame(fig, path, inside=False):
    """What every saved figure and every animation frame gets: the stub mark when the run's
    summary says the run is a stub's (runinfo), and its facts for the report's checks
    (figfacts). The animations call it once per grabbed frame (inside=True: no tight
    bounding box there, so the mark sits inside the frame)."""
    from . import figfacts, runinfo
    runinfo.stamp(fig, inside=inside)
    figfacts.note(fig, path)


def save_animation(fig, draw, frames, out, fps, dpi):
    """Writes the animation of `draw(k)` over `frames` as a GIF to a temporary name beside
    `out`, then renames it (the forces and collisions labs' animations); closes the figure."""
    import matplotlib.animation as animation
    anim = animation.FuncAnimation(fig, draw, frames=frames, blit=False)
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        raise InputError(f"{out}: folder {folder} does not exist")
    tmp = os.path.join(folder, f".{os.path.basename(out)}.tmp-{os.getpid()}.gif")
    try:
        anim.save(tmp, writer=animation.PillowWriter(fps=fps), dpi=dpi)
        os.replace(tmp, out)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)


def write_text_atomic(path, text):
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise InputError(f"{path}: folder {folder} does not exist")
    tmp = os.path.join(folder, f".{os.path.basename(path)}.tmp-{os.getpid()}")
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except OSError as e:
        raise InputError(f"{path}: cannot write ({e.strerror})") from None
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


# Integrators keep one colour and marker in every figure. Every integrator a lab lists has
# its own (the implicit lab draws twelve on one axes: colours by sorted order once gave
# baraff-witkin-fast explicit Euler's red and implicit-trapezoid semi-implicit Euler's blue).
KNOWN_INTEGRATORS = ["explicit-euler", "symplectic-euler", "midpoint", "trapezoid", "rk4",
                     "verlet", "implicit-euler", "backward-euler", "backward-euler-fast",
                     "baraff-witkin", "baraff-witkin-fast", "implicit-trapezoid",
                     "backward-euler-1", "implicit-gyroscopic", "explicit-gyroscopic"]
_COLORS = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
           "#17becf", "#393b79", "#bcbd22", "#843c39", "#7f7f7f", "#637939", "#17becf",
           "#d62728", "#e7969c", "#6b6ecf", "#b5cf6b"]
_MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*", "<", ">", "d", "h", "p", "o", "s", "8",
            "H", "+"]


def integrator_style(name, others=()):
    """(colour, marker) for an integrator: fixed for known names, else by sorted order."""
    if name in KNOWN_INTEGRATORS:
        i = KNOWN_INTEGRATORS.index(name)
    else:
        extra = sorted(n for n in set(others) | {name} if n not in KNOWN_INTEGRATORS)
        i = len(KNOWN_INTEGRATORS) + extra.index(name)
    return _COLORS[i % len(_COLORS)], _MARKERS[i % len(_MARKERS)]
