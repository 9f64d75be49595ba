"""Shared pieces of the report: reading result files, number formatting, Markdown tables.

Ratios in the report are ratios of medians (slower median / faster median), computed here from
the benchmarks' `median_ms` fields, so every table uses one rule. The programs print no tables:
every table is rendered here. Where a detail table shows the programs' own "paired" ratios
(`speedup_over_base`, `time_ratio_vs_a`: medians of per-round ratios) it says so; they can
differ from the ratio of medians by a few percent.
"""

import json
import math
import os
from dataclasses import dataclass, field


class InputError(Exception):
    """A result file that exists but cannot be used (invalid JSON, missing fields)."""


@dataclass
class Comparison:
    """One measured ratio for the summary charts: who, on which case, how many times faster."""

    group: str  # technique ("ERT + ESS (slice)") or comparison ("slice vs VTK GPU")
    case: str  # "engine/tf2/256"
    value: float  # > 1: the accelerated path / our mapper is faster


@dataclass
class Section:
    """What one benchmark contributes to the report."""

    key: str  # composite | cropping | octree | raycast | shearwarp
    title: str
    markdown: str = ""
    speedups: list = field(default_factory=list)  # Comparison: technique vs unaccelerated path
    peers: list = field(default_factory=list)  # Comparison: our mapper vs VTK's / VolPack
    charts: list = field(default_factory=list)  # (file name, alt text)
    gl_renderer: str = ""
    problem: str = ""  # why the section has no data ("" when it has)


@dataclass
class Context:
    """Where the report is written: charts go to charts_dir, links are relative to md_dir."""

    md_dir: str
    charts_dir: str
    quick: bool = False

    def link(self, path):
        return os.path.relpath(path, self.md_dir).replace(os.sep, "/")

    def chart_path(self, name):
        return os.path.join(self.charts_dir, name)


def load_json(path):
    """The parsed file, None when it does not exist; InputError when it is not usable JSON."""
    if not os.path.exists(path):
        return None
    try:
        with open(path, encoding="utf-8") as stream:
            data = json.load(stream)
    except json.JSONDecodeError as error:
        raise InputError(f"{path} is not valid JSON (line {error.lineno}, column {error.colno}: "
                         f"{error.msg})") from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{path} cannot be read: {error}") from None
    if not isinstance(data, dict):
        raise InputError(f"{path} holds a JSON {type(data).__name__}, not an object")
    return data


def field_of(mapping, *names, where="", default=KeyError):
    """mapping[names[0]][names[1]]...; InputError naming the path when a level is missing."""
    value = mapping
    for depth, name in enumerate(names):
        container = isinstance(value, dict) and name in value
        index = isinstance(value, list) and isinstance(name, int) and \
            -len(value) <= name < len(value)
        if not (container or index):
            if default is not KeyError:
                return default
            path = ".".join(str(n) for n in names[: depth + 1])
            raise InputError(f"{where}: field '{path}' is missing")
        value = value[name]
    return value


def records(mapping, name, where):
    """mapping[name] as a list of objects (the benchmarks' "cases", "datasets", "configs")."""
    items = field_of(mapping, name, where=where)
    if not isinstance(items, list) or not all(isinstance(item, dict) for item in items):
        raise InputError(f"{where}: field '{name}' must be a list of objects")
    return items


def number(value):
    """A float, or NaN for null / non-numbers (the programs write null for non-finite values)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return math.nan
    return float(value)


def ratio(slower_ms, faster_ms):
    """slower / faster: how many times faster the second is; NaN when either is not positive."""
    a, b = number(slower_ms), number(faster_ms)
    if not (a > 0 and b > 0):
        return math.nan
    return a / b


def median(values):
    finite = sorted(v for v in (number(x) for x in values) if math.isfinite(v))
    if not finite:
        return math.nan
    n = len(finite)
    return finite[n // 2] if n % 2 else (finite[n // 2 - 1] + finite[n // 2]) / 2


def finite(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


def fmt_ms(value):
    value = number(value)
    if not math.isfinite(value):
        return "-"
    if value >= 100:
        return f"{value:.0f}"
    if value >= 10:
        return f"{value:.1f}"
    if value >= 1:
        return f"{value:.2f}"
    return f"{value:.3f}"


def fmt_x(value):
    """A speed-up: two decimals in the usual 0.1-100 range, whole above, 3 digits below."""
    if not finite(value):
        return "-"
    if abs(value) >= 100:
        return f"{value:.0f}x"
    if abs(value) >= 0.1:
        return f"{value:.2f}x"
    return f"{value:.3g}x"


def fmt_pct(value, digits=1):
    return f"{value:.{digits}f}%" if finite(value) else "-"


def fmt_num(value, digits=2):
    value = number(value)
    return f"{value:.{digits}f}" if math.isfinite(value) else "-"


def value_range(values, fmt=fmt_x):
    """'a-b' of the finite values (or the single value); '-' when there is none."""
    good = [v for v in values if finite(v)]
    if not good:
        return "-"
    low, high = min(good), max(good)
    return fmt(low) if fmt(low) == fmt(high) else f"{fmt(low).rstrip('x')}-{fmt(high)}"


def table(header, rows, align=None):
    """A Markdown table; `align` is a string of 'l' / 'r' per column (default: first left)."""
    align = align or "l" + "r" * (len(header) - 1)
    marks = {"l": "---", "r": "---:", "c": ":---:"}
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join(marks[a] for a in align) + "|"]
    for row in rows:
        cells = [str(c).replace("|", "\\|") for c in row]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def details(summary, header, rows, align=None):
    """A collapsed block holding a table: the per-configuration numbers behind a section's
    main table (what the benchmark programs measure beside it). "" without rows."""
    if not rows:
        return ""
    return (f"\n<details><summary>{summary}</summary>\n\n" + table(header, rows, align) +
            "\n</details>\n")


def fmt_count(value):
    """A large count in millions ("12.35M"); "-" when unknown."""
    value = number(value)
    return f"{value / 1e6:.2f}M" if math.isfinite(value) else "-"


def note(text):
    return f"> **Note:** {text}\n"


def by_id(mapping, name, key, where):
    """{item[key]: item} of the list of objects mapping[name], with a clear error otherwise."""
    result = {}
    for item in records(mapping, name, where):
        if key not in item:
            raise InputError(f"{where}: an entry of '{name}' has no '{key}'")
        result.setdefault(item[key], item)
    return result
