"""Section of accelvolume_benchmark_raycast: the CPU ray caster with no leaping, distance-map or
octree empty-space leaping, each without and with semi-transparent cell leaping, against VTK's
fixed-point ray caster (Lim, Kim and Shin 2009, Table 2)."""

from . import charts
from .common import (Comparison, Section, by_id, details, field_of, finite, fmt_count, fmt_ms,
                     fmt_num, fmt_pct, fmt_x, number, ratio, records, table, value_range)

FILE = "raycast.json"
TITLE = "CPU ray casting: empty-space and semi-transparent cell leaping (Lim, Kim and Shin 2009)"

OCTREE = "raycast: octree leaping"
DMAP = "raycast: distance-map leaping"
CELL_ALONE = "raycast: cell leaping alone"
CELL_DMAP = "raycast: cell leaping + distance map"
CELL_OCTREE = "raycast: cell leaping + octree"
PEER = "raycast (dist. map) vs VTK fixed-point ray caster"


def _gain_as_speedup(percent):
    """A time saving of `percent` % as a speed-up: 1 / (1 - p)."""
    return 1.0 / (1.0 - percent / 100.0)


# Lim, Kim and Shin 2009, Table 2: cell leaping saves 18.8-24.1% over distance-map leaping alone and
# 16.8-21.7% over octree leaping alone.
PAPER_RANGES = {
    CELL_DMAP: (_gain_as_speedup(18.8), _gain_as_speedup(24.1)),
    CELL_OCTREE: (_gain_as_speedup(16.8), _gain_as_speedup(21.7)),
}
PAPER = ("Lim, Kim and Shin 2009, Table 2 (Athlon 64 X2, 512^2 perspective, 512x512x322..512 volumes): "
         "semi-transparent cell leaping saves 18.8-24.1% of the time on top of distance-map "
         "leaping and 16.8-21.7% on top of octree leaping, with pixel-identical images.")


# Lim, Kim and Shin 2009, Table 2: cell-leaping gain in % over distance-map and octree leaping alone,
# by the paper's volume closest to ours (no teeth volume here).
PAPER_ROWS = {
    "cthead": ("head", 18.8, 16.8),
    "aneurism": ("cerebral arteries", 23.0, 19.6),
    "cta_avm": ("cerebral arteries", 23.0, 19.6),
    "engine": ("engine", 20.5, 18.9),
    "boston_teapot": ("teapot", 22.0, 20.1),
    "bonsai_hazeremoved": ("bonsai", 24.1, 21.7),
}


def _gain(off_ms, on_ms):
    """Time saved by cell leaping, (off - on) / off, in percent (negative: it costs time)."""
    speedup = ratio(off_ms, on_ms)
    return 100.0 * (1.0 - 1.0 / speedup) if finite(speedup) else float("nan")


def build(data, ctx):
    machine = data.get("machine", {})
    section = Section("raycast", TITLE, gl_renderer=machine.get("gl_renderer", ""))
    settings = data.get("settings", {})
    cases = records(data, "cases", FILE)
    rows, categories = [], []
    series = {"no leaping": [], "octree": [], "distance map": [], "VTK fixed-point": []}
    for index, case in enumerate(cases):
        where = f"{FILE} cases[{index}]"
        configs = by_id(case, "configs", "id", where)
        ms = {cid: configs.get(cid, {}).get("median_ms") for cid in
              ("none_off", "none_cell", "dmap_off", "dmap_cell", "octree_off", "octree_cell",
               "vtk_fixed")}
        field_of(configs, "none_off", "median_ms", where=where + " configs")
        label = f"{case.get('dataset', '?')}/{case.get('tf', '?')}"
        if "projection" in case:  # one case per projection and thread count
            label += f" {case.get('projection')} {case.get('threads', '?')}t"
        comparisons = {
            OCTREE: ratio(ms["none_off"], ms["octree_off"]),
            DMAP: ratio(ms["none_off"], ms["dmap_off"]),
            CELL_ALONE: ratio(ms["none_off"], ms["none_cell"]),
            CELL_DMAP: ratio(ms["dmap_off"], ms["dmap_cell"]),
            CELL_OCTREE: ratio(ms["octree_off"], ms["octree_cell"]),
        }
        for name, value in comparisons.items():
            section.speedups.append(Comparison(name, label, value))
        ours_vs_vtk = ratio(ms["vtk_fixed"], ms["dmap_off"])
        section.peers.append(Comparison(PEER, label, ours_vs_vtk))
        gains = " / ".join(fmt_pct(_gain(ms[f"{m}_off"], ms[f"{m}_cell"]))
                           for m in ("none", "octree", "dmap"))
        identical = case.get("identical")
        rms_ours = case.get("ours_vs_reference", {}).get("rms")
        rms_vtk = case.get("vtk_vs_reference", {}).get("rms")
        rows.append([case.get("dataset", "?"), label.split("/", 1)[1], fmt_ms(ms["none_off"]),
                     f"{fmt_ms(ms['octree_off'])} ({fmt_x(comparisons[OCTREE])})",
                     f"{fmt_ms(ms['dmap_off'])} ({fmt_x(comparisons[DMAP])})", gains,
                     fmt_ms(ms["vtk_fixed"]), fmt_x(ours_vs_vtk),
                     "yes" if identical is True else "**no**" if identical is False else "?",
                     f"{fmt_num(rms_ours)} / {fmt_num(rms_vtk)}"])
        categories.append(label)
        for key, cid in zip(series, ("none_off", "octree_off", "dmap_off", "vtk_fixed")):
            series[key].append(number(ms[cid]))

    projections = settings.get("projections", [settings.get("projection", "perspective")])
    text = (f"`accelvolume_benchmark_raycast`: shaded composite, {settings.get('size', '?')}^2 "
            f"{' and '.join(map(str, projections))}, {settings.get('threads', '?')} threads for "
            "every mapper, sample "
            "distance = smallest voxel spacing, median of "
            f"{settings.get('frames', '?')} frames. Leaping speed-ups over no leaping in "
            "brackets; cell-leaping gain = time saved by turning it on within each leap mode; "
            "\"ours\" = distance map without cell leaping (the default); RMS in grey levels "
            "against our ray caster sampled "
            f"{settings.get('reference_factor', '?')}x more finely.\n\n")
    header = ["Dataset", "TF", "No leap ms", "Octree ms", "Dist. map ms",
              "Cell gain none / octree / dmap", "VTK fixed ms", "Ours vs VTK",
              "Identical images", "RMS ours / VTK"]
    text += table(header, rows, "ll" + "r" * (len(header) - 2))
    if rows:
        text += ("\nDistance-map leaping " + value_range(
            [c.value for c in section.speedups if c.group == DMAP]) + " over no leaping, octree "
            + value_range([c.value for c in section.speedups if c.group == OCTREE]) +
            "; ours vs VTK's fixed-point ray caster " +
            value_range([c.value for c in section.peers]) + ".\n")
    text += _details(cases)
    text += f"\n{PAPER}\n"
    chart = ctx.chart_path("raycast_ms.png")
    if charts.grouped_bars(chart, "CPU ray casting: ms per frame", categories,
                           list(series.items()), "ms per frame"):
        section.charts.append(chart)
        text += f"\n![Ray casting times per case]({ctx.link(chart)})\n"
    section.markdown = text
    return section


def _details(cases):
    """Table 2 of the paper beside ours, and every configuration's counters and prepare times."""
    paper, rows = [], []
    for case in cases:
        label = f"{case.get('dataset', '?')}/{case.get('tf', '?')}"
        gains = case.get("cell_gain_percent", {})
        gains = gains if isinstance(gains, dict) else {}
        volume, dmap, octree = PAPER_ROWS.get(case.get("dataset"), ("-", None, None))
        paper.append([f"Table 2 {label}", volume, fmt_pct(number(gains.get("dmap"))),
                      fmt_pct(dmap), fmt_pct(number(gains.get("octree"))), fmt_pct(octree)])
        for config in case.get("configs", []):
            counts = config.get("per_frame", {})
            counts = counts if isinstance(counts, dict) else {}
            rows.append([f"{label}: {config.get('id', '?')}", fmt_ms(config.get("median_ms")),
                         fmt_x(number(config.get("speedup_over_none_off"))),
                         fmt_x(number(config.get("speedup_over_vtk"))),
                         fmt_count(counts.get("samples")), fmt_count(counts.get("leaped_space")),
                         fmt_count(counts.get("leaped_cell_table")),
                         fmt_count(counts.get("in_transparent_cells")),
                         f"{fmt_ms(config.get('first_frame_ms'))} / "
                         f"{fmt_ms(config.get('tf_change_frame_ms'))}",
                         f"{fmt_ms(config.get('first_prepare_ms'))} / "
                         f"{fmt_ms(config.get('tf_change_prepare_ms'))}",
                         fmt_num(config.get("median_cores"))])
    return (details("Table 2 of the paper beside ours (cell-leaping gain)",
                    ["Case", "Paper volume", "Ours over dist. map", "Paper", "Ours over octree",
                     "Paper"], paper, "llrrrr") +
            details("Every configuration (per-frame means of the counters)",
                    ["Case: configuration", "ms", "x none", "x VTK", "Samples", "Space-leaped",
                     "Cell-leaped", "In empty cells", "1st / TF frame ms", "1st / TF prepare ms",
                     "Cores"], rows, "l" + "r" * 10))
