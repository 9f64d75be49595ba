"""Puts BENCHMARKS.md together from the results folder written by scripts/bench.sh.

A benchmark whose JSON is missing or unusable gets a note in its section (and, when unusable, a
message on stderr and exit status 1); every other section is still written.
"""

import glob
import math
import os
import sys

from . import (bricking, charts, composite, cropping, gallery, machine, memory, octree, raycast,
               shearwarp)
from .common import (Context, InputError, Section, finite, fmt_x, load_json, note, table,
                     value_range)

# Report order follows the papers: 000 slice composite, 001 ray casting, 002 octree, 003
# shear-warp, 004 cropping.
MODULES = [composite, raycast, octree, shearwarp, cropping]
# Sections written only when their JSON is in the results (bench.sh does not run them).
OPTIONAL_MODULES = [memory, bricking]
# Which program writes which file (for the notes about missing results).
PROGRAMS = {
    "composite": "accelvolume_benchmark_composite",
    "raycast": "accelvolume_benchmark_raycast",
    "octree": "accelvolume_benchmark_octree",
    "shearwarp": "accelvolume_benchmark_shearwarp",
    "cropping": "accelvolume_benchmark_cropping",
    "memory": "accelvolume_benchmark_memory",
    "bricking": "accelvolume_benchmark_bricking",
}


def read_runs(path):
    """Rows of runs.tsv (name, exit, seconds, command); [] when absent."""
    runs = []
    if not os.path.exists(path):
        return runs
    with open(path, encoding="utf-8") as stream:
        for line in stream:
            parts = line.rstrip("\n").split("\t")
            if len(parts) >= 4 and not line.startswith("#"):
                runs.append(dict(zip(["name", "exit", "seconds", "command"], parts)))
    return runs


def _clear_pngs(folder):
    """Old charts / thumbnails would otherwise outlive a rerun with fewer cases."""
    os.makedirs(folder, exist_ok=True)
    for path in glob.glob(os.path.join(folder, "*.png")):
        os.remove(path)


def _section(module, results_dir, ctx, runs, errors):
    key = module.FILE[: -len(".json")]
    path = os.path.join(results_dir, module.FILE)
    run = next((r for r in runs if r["name"] == key), None)
    try:
        data = load_json(path)
        if data is None:
            why = f"not run: `results/{module.FILE}` is missing"
            if run and run["exit"] != "0":
                why += f" ({PROGRAMS[key]} exited with status {run['exit']}; see " \
                       f"`results/{key}.log`)"
            return Section(key, module.TITLE, problem=why)
        section = module.build(data, ctx)
    except InputError as error:
        errors.append(str(error))
        return Section(key, module.TITLE, problem=f"could not read the results: {error}")
    except (KeyError, TypeError, AttributeError, ValueError, IndexError) as error:
        # Well-formed JSON of an unexpected shape (another program version, a hand edit).
        message = f"{path}: unexpected content ({type(error).__name__}: {error})"
        errors.append(message)
        return Section(key, module.TITLE, problem=f"could not read the results: {message}")
    if run and run["exit"] != "0":
        section.markdown = note(f"{PROGRAMS[key]} exited with status {run['exit']} (see "
                                f"`results/{key}.log`); the table shows what it wrote.") + \
            "\n" + section.markdown
    return section


def _summary(sections, ctx):
    speedups = [c for s in sections for c in s.speedups]
    peers = [c for s in sections for c in s.peers]
    paper_ranges = {}
    for module in MODULES:
        paper_ranges.update(getattr(module, "PAPER_RANGES", {}))
    text = ""
    groups = list(dict.fromkeys(c.group for c in speedups))
    rows = []
    for group in groups:
        values = [c.value for c in speedups if c.group == group and finite(c.value)]
        paper = paper_ranges.get(group)
        rows.append([group, len(values), fmt_x(_geometric_median(values)), value_range(values),
                     value_range(list(paper)) if paper else "-"])
    if rows:
        text += ("Speed-up of each technique over the unaccelerated path of the same mapper "
                 "(ratio of median frame or build times; median and range over the cases):\n\n")
        text += table(["Technique", "Cases", "Median", "Range", "Paper"], rows, "lrrrr")
        chart = ctx.chart_path("speedups_by_technique.png")
        if charts.technique_chart(chart, "Speed-up per technique (all benchmarks)", speedups,
                                  paper_ranges):
            text += f"\n![Speed-up per technique]({ctx.link(chart)})\n"
    peer_groups = list(dict.fromkeys(c.group for c in peers))
    rows = []
    for group in peer_groups:
        values = [c.value for c in peers if c.group == group and finite(c.value)]
        rows.append([group, len(values), fmt_x(_geometric_median(values)), value_range(values)])
    if rows:
        text += ("\nOur mappers against VTK's and VolPack on the same volume, transfer function, "
                 "view and image size (their time / ours: > 1 means ours is faster):\n\n")
        text += table(["Comparison", "Cases", "Median", "Range"], rows, "lrrr")
        chart = ctx.chart_path("ours_vs_vtk_volpack.png")
        if charts.peers_chart(chart, "Our mappers vs VTK's mappers and VolPack", peers):
            text += f"\n![Ours vs VTK and VolPack]({ctx.link(chart)})\n"
    return text or note("no benchmark results to summarize.")


def _geometric_median(values):
    values = sorted(values)
    if not values:
        return math.nan
    n = len(values)
    return values[n // 2] if n % 2 else math.sqrt(values[n // 2 - 1] * values[n // 2])


def _anchor(title):
    keep = "".join(ch for ch in title.lower() if ch.isalnum() or ch in " -")
    return keep.replace(" ", "-")


def generate(results_dir, markdown_path, assets_dir):
    """Writes the report; returns the list of unusable inputs (empty when all were fine)."""
    md_dir = os.path.dirname(os.path.abspath(markdown_path))
    charts_dir = os.path.join(assets_dir, "charts")
    gallery_dir = os.path.join(assets_dir, "gallery")
    _clear_pngs(charts_dir)
    _clear_pngs(gallery_dir)
    errors = []
    try:
        machine_info = load_json(os.path.join(results_dir, "machine.json"))
    except InputError as error:
        errors.append(str(error))
        machine_info = None
    quick = bool(machine_info and machine_info.get("mode") == "quick")
    ctx = Context(md_dir=md_dir, charts_dir=charts_dir, quick=quick)
    runs = read_runs(os.path.join(results_dir, "runs.tsv"))
    present = [m for m in OPTIONAL_MODULES if os.path.exists(os.path.join(results_dir, m.FILE))]
    sections = [_section(m, results_dir, ctx, runs, errors) for m in MODULES + present]

    results_link = ctx.link(results_dir)
    out = ["# AccelVolume benchmark report\n",
           "Generated by `scripts/bench.sh` (tables, charts and gallery from the benchmark "
           f"programs' JSON in [`{results_link}/`]({results_link}/)); regenerate the document "
           "from those files with `scripts/bench.sh --skip-run`. Do not edit by hand.\n"]
    if quick:
        out.append(note("this is a **quick** run (`--quick`: one small case per benchmark, one "
                        "or two frames, small images). It checks that everything runs; its "
                        "timings are not meaningful."))
    problems = [(s.title, s.problem) for s in sections if s.problem]
    if problems:
        out.append("\n**Missing or unreadable results:**\n")
        out += [f"- {title}: {problem}" for title, problem in problems]
        out.append("")
    out.append("\n## Contents\n")
    out.append("- [Machine](#machine)\n- [Summary](#summary)")
    out += [f"- [{s.title}](#{_anchor(s.title)})" for s in sections]
    out.append("- [Gallery](#gallery)\n- [How the numbers are made](#how-the-numbers-are-made)\n")
    renderers = {s.gl_renderer for s in sections if s.gl_renderer}
    out.append("## Machine\n")
    out.append(machine.section(machine_info, renderers, runs))
    out.append("## Summary\n")
    out.append(_summary(sections, ctx))
    for section in sections:
        out.append(f"## {section.title}\n")
        out.append(note(section.problem) if section.problem else section.markdown)
    out.append("## Gallery\n")
    shearwarp_data = _quiet_load(os.path.join(results_dir, shearwarp.FILE))
    cropping_data = _quiet_load(os.path.join(results_dir, cropping.FILE))
    gallery_text, gallery_problems = gallery.build(ctx, results_dir, gallery_dir,
                                                   shearwarp_data, cropping_data)
    out += [note(p) for p in gallery_problems]
    out.append(gallery_text or note("no gallery images."))
    out.append("\n## How the numbers are made\n")
    out.append(
        "- Every ratio is computed here from the medians in the JSON files (slower median / "
        "faster median), the same way in every table; the \"paired\" ratios in the detail "
        "tables are the programs' medians of per-round ratios, which can differ by a few "
        "percent. The programs print no tables: they write JSON, and every table is rendered "
        "here.\n"
        "- Timings are only as good as the machine was quiet: on the shared 2-core machine "
        "the project is developed on, repeated runs varied by 10-40% (docs/benchmarks/). The "
        "Runs table gives each program's exact command line.\n"
        "- OpenGL timings on Mesa llvmpipe are CPU rasterization, not a GPU: the ratios between "
        "GPU-style techniques hold, absolute frame rates do not.\n"
        "- The papers' numbers are from their own hardware (2005-2009 GPUs, a MasPar MP-2) and "
        "volumes; they are given for context, not as a like-for-like comparison.\n")
    with open(markdown_path, "w", encoding="utf-8") as stream:
        stream.write("\n".join(out).rstrip() + "\n")
    return errors


def _quiet_load(path):
    """For the gallery's captions only: a problem with the file is reported by its section."""
    try:
        return load_json(path)
    except InputError:
        return None


def main(results_dir, markdown_path, assets_dir):
    errors = generate(results_dir, markdown_path, assets_dir)
    print(f"benchmark_report: wrote {markdown_path}")
    for error in errors:
        print(f"benchmark_report: error: {error}", file=sys.stderr)
    return 1 if errors else 0
