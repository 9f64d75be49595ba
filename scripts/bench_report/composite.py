"""Section of accelvolume_benchmark_composite: the slice mapper's composite mode with early ray
termination (ERT) and empty-space skipping (ESS) against the plain slicer and VTK's GPU ray
caster (Lee 2005, Table V-3)."""

from . import charts
from .common import (Comparison, Section, by_id, details, field_of, fmt_ms, fmt_num, fmt_pct,
                     fmt_x, number, ratio, records, table, value_range)

FILE = "composite.json"
TITLE = "Slice mapper, composite: early ray termination and empty-space skipping (Lee 2005)"

# Technique -> (slice-mapper configuration id, summary-chart name). Ratios: base ms / config ms.
TECHNIQUES = [
    ("ert", "slice: early ray termination"),
    ("ess_fragment", "slice: ESS, fragment test"),
    ("ess_octree", "slice: ESS, min-max octree"),
    ("ert_both", "slice: ERT + ESS both (default)"),
]
PEER = "slice (default) vs VTK GPU ray caster, composite"
# Table V-3 of Lee 2005 (GeForce 6800GT): speed-ups over the plain slicer. The paper's ESS is the
# per-fragment two-pass test, the counterpart of our fragment ESS.
PAPER_RANGES = {
    "slice: early ray termination": (1.01, 1.66),
    "slice: ESS, fragment test": (1.90, 3.50),
    "slice: ERT + ESS both (default)": (2.38, 4.55),
}
PAPER = ("Lee 2005, Table V-3 (GeForce 6800GT; 256x256x225 CT head \"bighead\" and "
         "256x256x110 engine; 256^2 and 512^2): ERT 1.01-1.66x, ESS 1.90-3.50x, ERT+ESS "
         "2.38-4.55x over the plain slicer (best: bighead, tf2, 512^2, 4.48 -> 20.40 fps). "
         "The paper's hierarchical (octree) ESS was designed but not implemented.")


def build(data, ctx):
    section = Section("composite", TITLE, gl_renderer=data.get("gl_renderer", ""))
    cases = records(data, "cases", FILE)
    rows = []
    categories, series = [], {tid: [] for tid, _ in TECHNIQUES}
    vtk_series = []
    for index, case in enumerate(cases):
        where = f"{FILE} cases[{index}]"
        configs = by_id(case, "configs", "id", where)
        label = f"{case.get('dataset', '?')}/{case.get('tf', '?')}/{case.get('size', '?')}"
        base = field_of(configs, "base", "median_ms", where=where + " configs")
        speedups = {tid: ratio(base, configs.get(tid, {}).get("median_ms"))
                    for tid, _ in TECHNIQUES}
        vtk_ms = configs.get("vtk", {}).get("median_ms")
        ours_ms = configs.get("ert_both", {}).get("median_ms")
        ours_vs_vtk = ratio(vtk_ms, ours_ms)
        rows.append([case.get("dataset", "?"), case.get("tf", "?"), case.get("size", "?"),
                     fmt_ms(base)] + [fmt_x(speedups[tid]) for tid, _ in TECHNIQUES] +
                    [fmt_ms(ours_ms), fmt_ms(vtk_ms), fmt_x(ours_vs_vtk),
                     fmt_num(case.get("rms_ert_both_vs_base")),
                     fmt_num(case.get("rms_ours_vs_vtk"))])
        for tid, name in TECHNIQUES:
            section.speedups.append(Comparison(name, label, speedups[tid]))
            series[tid].append(speedups[tid])
        section.peers.append(Comparison(PEER, label, ours_vs_vtk))
        categories.append(label)
        vtk_series.append(ratio(base, vtk_ms))

    frames = data.get("frames", "?")
    large = data.get("large_frames", 0)
    view = data.get("view", {})
    text = (f"`accelvolume_benchmark_composite`: shaded composite, transfer functions tf1 "
            f"(semi-transparent) / tf2 (opaque) of `accelvolume render --tf`, view azimuth "
            f"{view.get('azimuth', '?')} elevation {view.get('elevation', '?')}, median of "
            f"{frames} frames" + (f" ({large} above 256^2)" if large else "") +
            ". Speed-ups are base ms / configuration ms; \"ours\" is the default (ERT + both "
            "ESS); RMS in grey levels (0..255) at the fixed view.\n\n")
    header = ["Dataset", "TF", "Size", "Base ms", "ERT", "ESS frag.", "ESS octree", "ERT+both",
              "Ours ms", "VTK GPU ms", "Ours vs VTK", "RMS vs base", "RMS vs VTK"]
    text += table(header, rows, "lll" + "r" * (len(header) - 3))
    if rows:
        text += ("\nRange over the cases: ERT " +
                 value_range([c.value for c in section.speedups if c.group == TECHNIQUES[0][1]]) +
                 ", fragment ESS " +
                 value_range([c.value for c in section.speedups if c.group == TECHNIQUES[1][1]]) +
                 ", octree ESS " +
                 value_range([c.value for c in section.speedups if c.group == TECHNIQUES[2][1]]) +
                 ", ERT + both " +
                 value_range([c.value for c in section.speedups if c.group == TECHNIQUES[3][1]]) +
                 "; ours vs VTK's GPU ray caster " +
                 value_range([c.value for c in section.peers]) + ".\n")
    text += _work_table(cases)
    text += _details(data, cases)
    text += f"\n{PAPER}\n"
    chart = ctx.chart_path("composite_speedups.png")
    named = [(name.split(": ", 1)[1], series[tid]) for tid, name in TECHNIQUES]
    if charts.grouped_bars(chart, "Slice mapper composite: speed-up over the plain slicer",
                           categories, named + [("VTK GPU ray caster", vtk_series)],
                           "speed-up (x)", reference_line=1.0):
        section.charts.append(chart)
        text += f"\n![Composite speed-ups per case]({ctx.link(chart)})\n"
    section.markdown = text
    return section


def _count(value):
    """A count in millions, '-' when the query was not available."""
    value = number(value)
    return "-" if value != value or value < 0 else f"{value / 1e6:.2f}M"


def _work_table(cases):
    """The no-op driver's CPU cost per frame and the hardware-independent counts."""
    rows = []
    for index, case in enumerate(cases):
        configs = by_id(case, "configs", "id", f"{FILE} cases[{index}]")
        ours, vtk = configs.get("ert_both", {}), configs.get("vtk", {})
        base, cpu = configs.get("base", {}), configs.get("cpu_slices", {})
        if ours.get("noop_ms") is None and ours.get("fragments_shaded") is None:
            continue
        rows.append([case.get("dataset", "?"), case.get("tf", "?"), case.get("size", "?"),
                     fmt_ms(ours.get("noop_ms")), fmt_ms(cpu.get("noop_ms")),
                     fmt_ms(base.get("noop_ms")), fmt_ms(vtk.get("noop_ms")),
                     fmt_x(ratio(ours.get("noop_ms"), vtk.get("noop_ms"))),
                     _count(ours.get("samples_fetched")), _count(vtk.get("samples_fetched")),
                     fmt_x(ratio(ours.get("samples_fetched"), vtk.get("samples_fetched"))),
                     _count(ours.get("bytes_blended")), _count(vtk.get("bytes_blended"))])
    if not rows:
        return ""
    header = ["Dataset", "TF", "Size", "No-op ours ms", "No-op CPU slices ms", "No-op base ms",
              "No-op VTK ms", "Ours / VTK CPU", "Ours samples", "VTK samples",
              "Ours / VTK samples", "Ours bytes blended", "VTK bytes blended"]
    return ("\nPer-frame CPU cost under Mesa's no-op driver (`GALLIUM_NOOP=1`, EGL: every draw "
            "dropped; `accelvolume render` children, median of `--noop-frames`) and the work of "
            "one frame at the fixed view: ours counted by GL queries (fragment-shader "
            "invocations = volume samples; fragments passing to blending x 32 bytes of the "
            "RGBA32F target), VTK's as covered pixels x samples along each ray's chord (no "
            "early termination: an upper bound) and one RGBA8 blend per pixel. On llvmpipe the "
            "invocation count does not fall with early termination (it counts fragments the "
            "depth test then rejects, and adds the termination passes); the blended count does.\n\n" +
            table(header, rows, "lll" + "r" * (len(header) - 3)))


def _details(data, cases):
    """The volumes, and every configuration of every case as the program measured it."""
    volumes = [[f"volume {d.get('name', '?')}", d.get("volume", "?"),
                " ".join(f"{number(v):g}" for v in d.get("spacing", [])),
                fmt_num(d.get("sample_distance"), 3),
                "..".join(f"{number(v):g}" for v in d.get("range", [])),
                fmt_num(d.get("load_seconds"))]
               for d in data.get("datasets", []) if isinstance(d, dict)]
    rows = []
    for case in cases:
        label = f"{case.get('dataset', '?')}/{case.get('tf', '?')}/{case.get('size', '?')}"
        for config in case.get("configs", []):
            leaves = number(config.get("transparent_leaf_fraction"))
            rows.append([f"{label}: {config.get('id', '?')}", config.get("label", "?"),
                         fmt_ms(config.get("median_ms")), fmt_num(config.get("fps")),
                         fmt_x(number(config.get("speedup_over_base"))),
                         fmt_ms(config.get("mapper_median_ms")), config.get("slices", "-"),
                         config.get("termination_passes", "-"),
                         fmt_pct(100 * leaves, 0) if leaves >= 0 else "-"])
    return (details("Volumes", ["Volume", "Dims and type", "Spacing", "Sample distance",
                                "Range", "Load s"], volumes, "llrrrr") +
            details("Every configuration (paired speed-up = median of per-round ratios)",
                    ["Case: configuration", "Label", "ms", "fps", "Paired speed-up",
                     "Mapper ms", "Slices", "ERT passes", "Transparent leaves"], rows,
                    "ll" + "r" * 7))
