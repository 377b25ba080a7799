"""A quantity that stays constant to rounding is drawn as constant, with its value.

Left to itself, matplotlib fits a view to whatever a series does, so the 1e-18 rad/s of
rounding in a hinged door's off-axis angular velocity fills the axes like a motion, and a
constant energy becomes "1e-13 + 4.905" with noise across the panel. These helpers decide,
from the values and the quantity's own scale, what is constant to rounding, say so in the
legend ("= 0 to rounding", "= 4.905 to rounding") and give such an axes a view that shows
a flat line. figcheck.py checks every figure of the report for axes zoomed into rounding.
"""
import math

ROUNDING_REL = 1e-9   # a spread below this fraction of the quantity's scale is rounding
ROUNDING_ABS = 1e-12  # SI units: below this, a quantity of these labs is 0 to rounding


def _finite(values):
    return [v for v in values if v is not None and math.isfinite(v)]


def is_constant(values, scale=0.0):
    """True when the finite values differ by no more than rounding of `scale` (or of their
    own size, whichever is larger)."""
    v = _finite(values)
    if not v:
        return False
    big = max([abs(scale) if math.isfinite(scale) else 0.0] + [abs(x) for x in v])
    return max(v) - min(v) <= ROUNDING_REL * big + ROUNDING_ABS


def value_of(values, scale=0.0):
    """The value a constant series is drawn at: 0 when it is 0 to rounding of `scale`
    (a momentum of 8e-10 beside 4 kg m/s is 0, not a value to print)."""
    v = _finite(values)
    mid = (max(v) + min(v)) / 2 if v else 0.0
    big = abs(scale) if math.isfinite(scale) else 0.0
    return 0.0 if abs(mid) <= ROUNDING_REL * big + ROUNDING_ABS else mid


def label(values, unit="", scale=0.0):
    """' = 0 (to rounding)' or ' = 4.905 J (constant to rounding)'."""
    x = value_of(values, scale)
    u = f" {unit}" if unit else ""
    return f" = 0{u} (to rounding)" if x == 0.0 else f" = {x:.6g}{u} (constant to rounding)"


def flat_view(ax, series, axis="y", scale=0.0):
    """When every series drawn on `ax` is constant to rounding: a view around their values
    wide enough to show them as flat lines (10 % of the largest value, or ±1 around 0), and
    no offset on the ticks. Returns True when it set the view."""
    values = [value_of(s, scale) for s in series if _finite(s)]
    if not values:
        return False
    lo, hi = min(values), max(values)
    half = max(0.5 * (hi - lo), 0.1 * max(abs(lo), abs(hi)))
    if half == 0:
        half = 1.0
    mid = (lo + hi) / 2
    getattr(ax, f"set_{axis}lim")(mid - 1.2 * half, mid + 1.2 * half)
    return True


def plain_ticks(ax, axis="y"):
    """Tick labels written out, never as an offset ('1e-13 + 4.905') a reader must add."""
    try:
        ax.ticklabel_format(axis=axis, useOffset=False)
    except AttributeError:  # a log axis has no offset to drop
        pass
