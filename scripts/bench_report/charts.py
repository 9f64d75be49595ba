"""Charts of the report, drawn by matplotlib (Debian's python3-matplotlib) with the Agg backend.

Small PNGs (about 700 px wide, palette-optimized by Pillow) keep the report light. A logarithmic
axis is used when the plotted values span more than a factor of LOG_SPAN, so that 1.1x and 50x
are both readable.
"""

import io
import math

import matplotlib

matplotlib.use("Agg")  # no display: the report is generated headless
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402
from PIL import Image  # noqa: E402  (Pillow: a dependency of python3-matplotlib)

from .common import finite  # noqa: E402

LOG_SPAN = 20.0
DPI = 90
COLORS = ["#4878d0", "#ee854a", "#6acc64", "#d65f5f", "#956cb4", "#8c613c", "#dc7ec0", "#797979"]


def _use_log(values):
    good = [v for v in values if finite(v) and v > 0]
    return len(good) > 1 and max(good) / min(good) > LOG_SPAN


def _save(figure, path):
    # bbox_inches="tight" keeps the legends placed outside the axes. A 256-colour palette (no
    # dithering: flat chart colours stay flat) makes the PNG 2-3x smaller than RGB.
    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=DPI, bbox_inches="tight", pad_inches=0.1, format="png")
    plt.close(figure)
    buffer.seek(0)
    with Image.open(buffer) as image:
        palette = image.convert("RGB").quantize(colors=256, dither=Image.Dither.NONE)
        palette.save(path, optimize=True)


def _log_axis(axis, values):
    """Logarithmic axis labelled 0.5, 1, 2, 5, 10, ... rather than 10^0, 10^1 (only the powers of
    ten when the values span more than 1000x, where 1-2-5 labels would collide)."""
    good = [v for v in values if finite(v) and v > 0] + [1.0]
    span = max(good) / min(good)
    subs = (1.0,) if span > 1000 else (1.0, 2.0, 5.0) if span > 10 else (1.0, 1.5, 2.0, 3.0, 5.0,
                                                                           7.0)
    axis.set_major_locator(LogLocator(base=10, subs=subs))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def _legend_right(axes):
    axes.legend(fontsize=7, frameon=False, loc="upper left", bbox_to_anchor=(1.01, 1.0))


def grouped_bars(path, title, categories, series, ylabel, reference_line=None, log=None):
    """Vertical grouped bars: one group per category, one bar per (label, values) series.

    NaN values leave a gap. `reference_line` draws a horizontal line (e.g. 1.0 for ratios).
    Returns False (and draws nothing) when there is no finite value at all.
    """
    values = [v for _, vs in series for v in vs]
    if not any(finite(v) and v > 0 for v in values):
        return False
    log = _use_log(values) if log is None else log
    width = max(4.5, min(9.0, 1.2 + 0.3 * len(categories) * len(series)))
    figure, axes = plt.subplots(figsize=(width, 3.6))
    bar = 0.8 / max(1, len(series))
    for k, (label, vs) in enumerate(series):
        xs = [i - 0.4 + bar * (k + 0.5) for i in range(len(categories))]
        heights = [v if finite(v) and v > 0 else 0 for v in vs]
        axes.bar(xs, heights, bar, label=label, color=COLORS[k % len(COLORS)])
    if reference_line is not None:
        axes.axhline(reference_line, color="black", linewidth=0.8, linestyle="--")
    if log:
        axes.set_yscale("log")
        _log_axis(axes.yaxis, values)
    axes.set_xticks(range(len(categories)))
    axes.set_xticklabels(categories, rotation=30 if len(categories) > 4 else 0, ha="right"
                         if len(categories) > 4 else "center", fontsize=8)
    axes.set_ylabel(ylabel + (" (log scale)" if log else ""))
    axes.set_title(title, fontsize=10)
    axes.grid(axis="y", alpha=0.3)
    _legend_right(axes)
    _save(figure, path)
    return True


def technique_chart(path, title, comparisons, paper_ranges):
    """One row per technique: the median speed-up as a bar, min..max as a whisker, every case as
    a dot, and the paper's reported range (if any) as a grey band. Log axis, line at 1x."""
    groups = []
    for c in comparisons:
        if c.group not in groups:
            groups.append(c.group)
    rows = []
    for group in groups:
        values = sorted(c.value for c in comparisons if c.group == group and finite(c.value)
                        and c.value > 0)
        if values:
            rows.append((group, values))
    if not rows:
        return False
    figure, axes = plt.subplots(figsize=(6.5, 0.9 + 0.34 * len(rows)))
    paper_labelled = False
    for y, (group, values) in enumerate(rows):
        # Geometric mean of the middle pair: the axis is logarithmic.
        med = values[len(values) // 2] if len(values) % 2 else \
            math.sqrt(values[len(values) // 2 - 1] * values[len(values) // 2])
        paper = paper_ranges.get(group)
        if paper:
            # Widened by 3% so that a single reported value still shows as a box.
            axes.fill_betweenx([y - 0.42, y + 0.42], paper[0] / 1.03, paper[1] * 1.03,
                               facecolor="none", edgecolor="#555555", hatch="///",
                               linewidth=0.8, zorder=4,
                               label=None if paper_labelled else "paper's range")
            paper_labelled = True
        # Bars grow from 1x: right = faster, left = slower than the unaccelerated path.
        axes.barh(y, med - 1.0, 0.5, left=1.0, color=COLORS[0] if med >= 1 else COLORS[3],
                  alpha=0.75, zorder=1)
        axes.plot([values[0], values[-1]], [y, y], color="black", linewidth=1, zorder=2)
        axes.plot(values, [y] * len(values), "o", color="black", markersize=3, zorder=3)
    axes.axvline(1.0, color="black", linewidth=0.8)
    axes.set_xscale("log")
    _log_axis(axes.xaxis, [v for _, values in rows for v in values])
    axes.set_yticks(range(len(rows)))
    axes.set_yticklabels([r[0] for r in rows], fontsize=8)
    axes.invert_yaxis()
    axes.set_xlabel("speed-up over the unaccelerated path (x, log scale); bar = median, "
                    "dots = cases", fontsize=8)
    axes.set_title(title, fontsize=10)
    axes.grid(axis="x", alpha=0.3)
    if paper_labelled:
        _legend_right(axes)
    _save(figure, path)
    return True


def peers_chart(path, title, comparisons):
    """Horizontal bars, one per case, coloured by comparison (slice vs VTK GPU, ...): how many
    times faster our mapper is than the other (log axis, line at 1x = parity)."""
    rows = [c for c in comparisons if finite(c.value) and c.value > 0]
    if not rows:
        return False
    groups = []
    for c in rows:
        if c.group not in groups:
            groups.append(c.group)
    ordered = [c for g in groups for c in rows if c.group == g]
    figure, axes = plt.subplots(figsize=(5.5, 1.0 + 0.2 * len(ordered)))
    labelled = set()
    for y, c in enumerate(ordered):
        k = groups.index(c.group)
        # From 1x (parity): right = ours faster, left = ours slower.
        axes.barh(y, c.value - 1.0, 0.7, left=1.0, color=COLORS[k % len(COLORS)],
                  label=None if c.group in labelled else c.group)
        labelled.add(c.group)
    axes.axvline(1.0, color="black", linewidth=0.8)
    axes.set_xscale("log")
    _log_axis(axes.xaxis, [c.value for c in ordered])
    axes.set_yticks(range(len(ordered)))
    axes.set_yticklabels([c.case for c in ordered], fontsize=7)
    axes.invert_yaxis()
    axes.set_xlabel("our mapper's speed-up over the other (x, log scale; > 1: ours faster)",
                    fontsize=8)
    axes.set_title(title, fontsize=10)
    axes.grid(axis="x", alpha=0.3)
    _legend_right(axes)
    _save(figure, path)
    return True
