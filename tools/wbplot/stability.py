"""Regions of absolute stability |R(z)| <= 1 in the complex plane z = h lambda."""
import math

import numpy as np  # ships with matplotlib
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from .common import InputError, integrator_style, new_figure, save_figure

# Amplification factors of the explicit one-step methods on y' = lambda y.
AMPLIFICATION = {
    "explicit-euler": ("1 + z", lambda z: 1 + z),
    "midpoint": ("1 + z + z²/2", lambda z: 1 + z + z * z / 2),
    "trapezoid": ("1 + z + z²/2", lambda z: 1 + z + z * z / 2),
    "rk4": ("1 + z + z²/2 + z³/6 + z⁴/24",
            lambda z: 1 + z + z * z / 2 + z ** 3 / 6 + z ** 4 / 24),
}
METHODS = ["explicit-euler", "symplectic-euler", "midpoint", "trapezoid", "rk4"]


VIEW_MAX = 8.0  # marks farther than this from 0 are shown by an arrow at the edge


def _to_edge(z, re_lo, re_hi, im_hi):
    """The point where the ray from 0 towards z leaves the view (a little inside it)."""
    ts = []
    if z.real < 0:
        ts.append(re_lo / z.real)
    if z.real > 0:
        ts.append(re_hi / z.real)
    if z.imag != 0:
        ts.append(im_hi / abs(z.imag))
    return z * min(ts) * 0.96


def oscillator_points(hw, zeta=None):
    """z = h lambda for the eigenvalues of x'' + 2 zeta w x' + w^2 x = 0."""
    if zeta is None or zeta == 0:
        return [complex(0, hw), complex(0, -hw)]
    if zeta < 1:
        s = math.sqrt(1 - zeta * zeta)
        return [hw * complex(-zeta, s), hw * complex(-zeta, -s)]
    s = math.sqrt(zeta * zeta - 1)
    return [complex(hw * (-zeta + s), 0), complex(hw * (-zeta - s), 0)]


def _at_marks(R, pts):
    """'|R| at the scene: ...' for the marks in the upper half-plane (one per h w)."""
    ups = [z for z in pts if z.imag >= 0]
    if not ups:
        return ""
    def one(z):
        d = abs(R(z)) - 1
        return f"{d:+.2e} " + ("(grows)" if d > 0 else "(decays)" if d < 0 else "(neutral)")
    return "\n    |R| - 1 at the scene = " + ", ".join(one(z) for z in ups)


def plot_stability(out, methods=None, marks=(), zeta=None, title=None):
    methods = list(methods or METHODS)
    for m in methods:
        if m not in METHODS:
            raise InputError(f"--methods: unknown method '{m}', expected some of "
                             + ",".join(METHODS))
    for hw in marks:
        if not (math.isfinite(hw) and hw > 0):
            raise InputError(f"--mark: got {hw}, expected h*omega as a number > 0")
    if zeta is not None and not (math.isfinite(zeta) and zeta >= 0):
        raise InputError(f"--damping: got {zeta}, expected a damping ratio zeta >= 0")

    pts = [z for hw in marks for z in oscillator_points(hw, zeta)]
    # The view holds the regions and the marks up to |z| = VIEW_MAX, about square.
    shown = [z for z in pts if abs(z) <= VIEW_MAX]
    re_lo = min([-3.2] + [z.real * 1.15 for z in shown])
    im_hi = max([3.1] + [abs(z.imag) * 1.15 for z in shown])
    re_hi = 1.2
    re_lo = min(re_lo, re_hi - 2 * im_hi / 1.35)
    im_hi = max(im_hi, (re_hi - re_lo) / 2 / 1.1)
    w = 5.6
    fig, ax = new_figure(figsize=(w, w * 2 * im_hi / (re_hi - re_lo)))
    n = 801
    xr = np.linspace(re_lo, re_hi, n)
    yi = np.linspace(-im_hi, im_hi, n)
    X, Y = np.meshgrid(xr, yi)
    Z = X + 1j * Y

    handles = []
    drawn = {}
    # Largest region first so the smaller ones stay visible on top.
    for m in [m for m in ("rk4", "midpoint", "trapezoid", "explicit-euler") if m in methods]:
        formula, R = AMPLIFICATION[m]
        same = [k for k in drawn if AMPLIFICATION[k][0] == formula]
        if same:
            # Midpoint and trapezoid share R(z): one region, one legend entry.
            drawn[same[0]].set_label(f"{same[0]} and {m} (same region): R = {formula}"
                                     f"{_at_marks(R, pts)}")
            continue
        color, _ = integrator_style(m)
        mag = np.abs(R(Z))
        ax.contourf(X, Y, mag, levels=[0, 1], colors=[color], alpha=0.18)
        ax.contour(X, Y, mag, levels=[1], colors=[color], linewidths=1.6)
        patch = Patch(facecolor=color, edgecolor=color, alpha=0.45,
                      label=f"{m}: R = {formula}{_at_marks(R, pts)}")
        drawn[m] = patch
        handles.append(patch)
    if "symplectic-euler" in methods:
        color, _ = integrator_style("symplectic-euler")
        ax.plot([0, 0], [-2, 2], color=color, lw=5, alpha=0.75, solid_capstyle="butt", zorder=4)
        ax.plot([0, 0], [-2, 2], ls="", marker="o", mfc="white", mec=color, ms=6, zorder=5)
        verdict = ""
        if marks and not zeta:
            verdict = "\n    the scene: " + ", ".join(
                f"{'bounded' if hw < 2 else 'unbounded'}" for hw in marks)
        handles.append(Line2D([], [], color=color, lw=5, alpha=0.75,
                              label="symplectic-euler, undamped oscillator only: bounded for "
                                    f"|hω| < 2\n(a segment of the imaginary axis, not a "
                                    f"region: no scalar R(z))"
                                    f"{verdict}"))
    ax.axhline(0, color="0.2", lw=0.7)
    ax.axvline(0, color="0.2", lw=0.7)
    if pts:
        ax.plot([z.real for z in shown], [z.imag for z in shown], ls="", marker="*", ms=13,
                color="black", mfc="gold", zorder=6)
        for hw in marks:
            z = oscillator_points(hw, zeta)[0]
            text = f"hω = {hw:.3g}"
            if abs(z) > VIEW_MAX:
                # Off the chart: an arrow at the edge, pointing at where it lies.
                zc = _to_edge(z, re_lo, re_hi, im_hi)
                ax.annotate("", (zc.real, zc.imag), xytext=(zc.real - 0.9 * z.real / abs(z),
                                                            zc.imag - 0.9 * z.imag / abs(z)),
                            arrowprops=dict(arrowstyle="->", lw=1.6), zorder=7)
                text += f"\nz = {z.real:.3g} ± {abs(z.imag):.3g}i, off the chart"
                z = zc - 0.9 * z / abs(z)
            ax.annotate(text, (z.real, z.imag), xytext=(8, 6),
                        textcoords="offset points", fontsize=9, zorder=7,
                        bbox=dict(fc="white", ec="none", alpha=0.8))
        what = "±i·hω" if not zeta else f"hω(-ζ ± i√(1-ζ²)), ζ = {zeta:.3g}"
        if zeta and zeta >= 1:
            what = f"hω(-ζ ± √(ζ²-1)), ζ = {zeta:.3g}"
        handles.append(Line2D([], [], ls="", marker="*", ms=13, color="black", mfc="gold",
                              label=f"the scene: z = {what}"))
    ax.set_xlim(re_lo, re_hi)
    ax.set_ylim(-im_hi, im_hi)
    ax.set_aspect("equal")
    ax.set_xlabel("Re z  (z = h λ, dimensionless)")
    ax.set_ylabel("Im z")
    ax.set_title(title or "Regions of absolute stability |R(z)| ≤ 1")
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.09), fontsize=8,
              frameon=False)
    fig.tight_layout()
    save_figure(fig, out)
