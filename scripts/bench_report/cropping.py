"""Section of accelvolume_benchmark_cropping: MIP of a cropped volume with the slice mapper, with
and without re-rendering the crop box's cut faces, with 1.5x / 2x slices, and VTK's GPU ray
caster; time and aliasing error against an 8x-slice reference (Hong, Kye and Shin 2007, Table 2)."""

from . import charts
from .common import (Comparison, Section, by_id, details, field_of, fmt_ms, fmt_num, fmt_pct,
                     fmt_x, number, ratio, records, table, value_range)

FILE = "cropping.json"
TITLE = "Slice mapper, cropped MIP: boundary re-rendering (Hong, Kye and Shin 2007)"

# Rows in this order; "ref" (8x slices) is the error reference, not a row.
CONFIGS = ["a", "b", "c", "d", "e"]
SHORT = {"a": "1x", "b": "1x + re-render", "c": "1.5x slices", "d": "2x slices", "e": "VTK GPU"}
TECHNIQUE = "cropping: re-rendering vs 2x slices"
PEER = "slice (re-render) vs VTK GPU ray caster, cropped MIP"
# Hong, Kye and Shin 2007, Table 2: 149.83 fps with re-rendering at 256 slices vs 73.85 fps with 512 slices.
PAPER_RANGES = {TECHNIQUE: (149.83 / 73.85, 149.83 / 73.85)}
PAPER = ("Hong, Kye and Shin 2007, Table 2 (Radeon 9800 Pro, 256x256x240 16-bit \"Big Head\"): 256 slices "
         "with re-rendering 149.83 fps, without 150.81 fps (0.7% cost); 400 slices 97.24 fps; "
         "512 slices 73.85 fps (so re-rendering is 2.03x faster than doubling the slices, "
         "which still aliases).")


def build(data, ctx):
    section = Section("cropping", TITLE, gl_renderer=data.get("gl_renderer", ""))
    datasets = records(data, "datasets", FILE)
    text_tables = ""
    names, time_series, band_series = [], {c: [] for c in CONFIGS}, {c: [] for c in CONFIGS}
    for index, dataset in enumerate(datasets):
        where = f"{FILE} datasets[{index}]"
        name = dataset.get("name", "?")
        configs = by_id(dataset, "configs", "id", where)
        base = field_of(configs, "a", "median_ms", where=where + " configs")
        rows = []
        for cid in CONFIGS:
            config = configs.get(cid)
            if config is None:
                rows.append([cid, "not measured", "-", "-", "-", "-", "-"])
                time_series[cid].append(float("nan"))
                band_series[cid].append(float("nan"))
                continue
            time_ratio = ratio(config.get("median_ms"), base)
            rows.append([f"({cid}) {config.get('label', '')}", fmt_ms(config.get("median_ms")),
                         fmt_x(time_ratio), fmt_num(config.get("band_rms_error")),
                         fmt_num(config.get("rms_error")),
                         fmt_num(config.get("cut_face_rms_error")),
                         fmt_pct(100 * number(config.get("above_threshold_fraction")), 2)])
            time_series[cid].append(time_ratio)
            band_series[cid].append(number(config.get("band_rms_error")))
        rerender = configs.get("b", {}).get("median_ms")
        section.speedups.append(Comparison(
            TECHNIQUE, name, ratio(configs.get("d", {}).get("median_ms"), rerender)))
        section.peers.append(Comparison(PEER, name,
                                        ratio(configs.get("e", {}).get("median_ms"), rerender)))
        names.append(name)
        overhead = 100 * (ratio(rerender, base) - 1)
        text_tables += (f"\n**{name}** ({dataset.get('volume', '?')}, crop box "
                        f"{_crop_text(data)}): re-rendering costs {fmt_pct(overhead)} of the "
                        f"frame (ratio of medians; negative = noise).\n\n")
        text_tables += table(["Configuration", "ms", "Time vs (a)", "Band RMS", "Footprint RMS",
                              "Cut-face RMS", "Pixels > 2 levels"], rows, "lrrrrrr")
        text_tables += _details(name, dataset)

    size = data.get("size", ["?", "?"])
    text = (f"`accelvolume_benchmark_cropping`: MIP, {size[0]}x{size[1]}, oblique views, median "
            f"of {data.get('frames', '?')} frames. Errors in grey levels against the slice "
            "mapper with 8x slices and re-rendering: band = pixels within "
            f"{data.get('band_radius_px', '?')} px of the projected crop-box outline, footprint "
            "= the whole projected box, cut face = pixels the re-rendered faces change.\n")
    text += text_tables
    if section.speedups:
        text += ("\nRe-rendering vs 2x slices (time): " +
                 value_range([c.value for c in section.speedups]) +
                 " faster; vs VTK's GPU ray caster: " +
                 value_range([c.value for c in section.peers]) + " faster.\n")
    text += f"\n{PAPER}\n"
    chart_time = ctx.chart_path("cropping_time.png")
    chart_band = ctx.chart_path("cropping_band_error.png")
    if charts.grouped_bars(chart_time, "Cropped MIP: frame time relative to (a) 1x slices",
                           names, [(SHORT[c], time_series[c]) for c in CONFIGS],
                           "time / time of (a)", reference_line=1.0):
        section.charts.append(chart_time)
        text += f"\n![Cropping: time per configuration]({ctx.link(chart_time)})\n"
    if charts.grouped_bars(chart_band, "Cropped MIP: aliasing along the cut (band RMS)",
                           names, [(SHORT[c], band_series[c]) for c in CONFIGS],
                           "grey levels RMS", log=False):
        section.charts.append(chart_band)
        text += f"\n![Cropping: boundary-band error per configuration]({ctx.link(chart_band)})\n"
    section.markdown = text
    return section


def _crop_text(data):
    crop = data.get("crop_fraction")
    if isinstance(crop, list) and len(crop) == 2:
        return f"{crop[0]:g}..{crop[1]:g} of every axis"
    return "?"


def _details(name, dataset):
    """Every configuration of one dataset as the program measured it, and the claims checked."""
    rows = []
    for config in dataset.get("configs", []):
        rows.append([f"{name}: {config.get('id', '?')}", config.get("slices", "-"),
                     fmt_ms(config.get("median_ms")), fmt_num(config.get("fps")),
                     fmt_ms(config.get("min_ms")), fmt_x(number(config.get("time_ratio_vs_a"))),
                     fmt_num(config.get("rms_error")), fmt_num(config.get("max_error"), 0),
                     fmt_x(number(config.get("error_ratio_vs_a"))),
                     fmt_num(config.get("band_max_error"), 0),
                     fmt_x(number(config.get("band_error_ratio_vs_a"))),
                     fmt_x(number(config.get("cut_face_error_ratio_vs_a")))])
    pixels = ", ".join(f"{key.replace('_pixels', '').replace('_', '-')} "
                       f"{'+'.join(str(v) for v in dataset.get(key, []))}"
                       for key in ("footprint_pixels", "band_pixels", "cut_face_pixels"))
    claims = "; ".join(f"{where}: {'holds' if dataset.get(key) else 'does not hold'}"
                       for where, key in (("band", "rerender_beats_2x_in_band"),
                                          ("cut faces", "rerender_beats_2x_on_cut_faces"),
                                          ("footprint", "rerender_beats_2x_in_footprint")))
    text = details(f"{name}: every configuration (time x = median of per-round ratios to (a); "
                   f"pixels over 2 views: {pixels})",
                   ["Dataset: configuration", "Slices", "ms", "fps", "Min ms", "Time x",
                    "Footprint RMS", "Max", "Error x", "Band max", "Band x", "Cut-face x"],
                   rows, "l" + "r" * 11)
    overhead = number(dataset.get("rerender_overhead_percent"))
    return text + (f"\nRe-rendering leaves less boundary error than doubling the slices "
                   f"({claims}); overhead from paired rounds {fmt_pct(overhead)}.\n"
                   if rows else "")
