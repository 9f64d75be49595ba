"""Section of accelvolume_benchmark_shearwarp: shear-warp without run-length encoding, with RLE and
skip links, with RLE and bands balanced by the previous frame, on 1 and all threads and on MPI
ranks, against Lacroute's VolPack (Kim 1998, Tables 2-3)."""

from . import charts
from .common import (Comparison, Section, details, fmt_count, fmt_ms, fmt_num, fmt_pct, fmt_x,
                     number, ratio, records, table, value_range)

FILE = "shearwarp.json"
TITLE = "Shear-warp: run-length encoding, balanced partition, threads, MPI, VolPack (Kim 1998)"

RLE = "shear-warp: RLE + skip links"
BALANCED = "shear-warp: RLE + balanced bands"
THREADS = "shear-warp: all threads vs 1"
MPI = "shear-warp: MPI ranks vs 1"
PEER = "shear-warp (3), 1 thread vs VolPack"
# Kim 1998, Table 2 (MasPar MP-2, 128^3 MRI brain): 1.6102 s without RLE, 0.7331 s with RLE,
# 0.3109 s with RLE + partition + balancing.
PAPER_RANGES = {RLE: (1.6102 / 0.7331, 1.6102 / 0.7331), BALANCED: (1.6102 / 0.3109,
                                                                    1.6102 / 0.3109)}
PAPER = ("Kim 1998 (MasPar MP-2, 4,096 processors, 90 frames turned 1 degree): 128^3 MRI brain "
         "1.61 s without RLE, 0.73 s with RLE (2.20x), 0.31 s with RLE + balanced partition "
         "(5.18x); 256x256x226 CT head 1.21 s. Lacroute's sequential shear-warp (VolPack's "
         "algorithm): 256x256x167 brain at 256^2 in 1.09 s on an SGI R4000.")


def _engine_ms(run):
    return run.get("median_engine_ms", run.get("median_ms")) if run else None


def _find(runs, run_id, threads=None, ranks=None):
    for run in runs:
        if run.get("id") == run_id and (threads is None or run.get("threads") == threads) and \
                (ranks is None or run.get("ranks") == ranks):
            return run
    return None


def build(data, ctx):
    machine = data.get("machine", {})
    section = Section("shearwarp", TITLE, gl_renderer=machine.get("gl_renderer", ""))
    settings = data.get("settings", {})
    cases = records(data, "cases", FILE)
    rows, categories = [], []
    series = {"(1) no RLE, 1t": [], "(2) RLE, 1t": [], "(3) balanced, 1t": [],
              "(3) balanced, all threads": [], "VolPack, 1t": []}
    for index, case in enumerate(cases):
        where = f"{FILE} cases[{index}]"
        runs = records(case, "runs", where)
        threads = case.get("threads", settings.get("threads", 1))
        label = f"{case.get('dataset', '?')}/{case.get('tf', '?')}/{case.get('size', '?')}" + \
            ("" if case.get("shade", True) else "/unshaded")
        ms = {(rid, t): _engine_ms(_find(runs, rid, t))
              for rid in ("dense", "rle", "balanced") for t in (1, threads)}
        volpack = case.get("volpack", {})
        volpack_ms = volpack.get("median_ms") if volpack.get("ran") else None
        mpi = records(case, "mpi", where) if case.get("mpi") else []
        mpi_one = _find(mpi, "balanced", ranks=1)
        mpi_most = max((r for r in mpi if number(r.get("ranks")) > 1),
                       key=lambda r: r.get("ranks"), default=None)
        comparisons = {
            RLE: ratio(ms[("dense", threads)], ms[("rle", threads)]),
            BALANCED: ratio(ms[("dense", threads)], ms[("balanced", threads)]),
            THREADS: ratio(ms[("balanced", 1)], ms[("balanced", threads)]) if threads > 1
            else float("nan"),
            MPI: ratio(_engine_ms(mpi_one), _engine_ms(mpi_most)),
        }
        for name, value in comparisons.items():
            section.speedups.append(Comparison(name, label, value))
        # Whole frame (ours shown in the window and read back) and engine alone, paired per frame.
        ours_vs_volpack = number(case.get("volpack_ratio"))
        engine_vs_volpack = number(case.get("volpack_ratio_engine", ratio(volpack_ms, ms[("balanced", 1)])))
        balanced_one = _find(runs, "balanced", 1)
        wall_one = balanced_one.get("median_wall_ms") if balanced_one else None
        section.peers.append(Comparison(PEER, label, ours_vs_volpack))
        efficiency = comparisons[THREADS] / threads if threads > 1 else float("nan")
        mpi_ranks = mpi_most.get("ranks") if mpi_most else 0
        mpi_efficiency = comparisons[MPI] / mpi_ranks if mpi_ranks else float("nan")
        rows.append([
            label,
            f"{fmt_ms(ms[('dense', 1)])} / {fmt_ms(ms[('dense', threads)])}",
            f"{fmt_ms(ms[('rle', 1)])} / {fmt_ms(ms[('rle', threads)])}",
            f"{fmt_ms(ms[('balanced', 1)])} / {fmt_ms(ms[('balanced', threads)])}",
            fmt_x(comparisons[RLE]), fmt_x(comparisons[BALANCED]),
            fmt_ms(wall_one),
            fmt_ms(volpack_ms) if volpack_ms else (volpack.get("note") or "not run"),
            fmt_x(ours_vs_volpack), fmt_x(engine_vs_volpack), fmt_pct(100 * efficiency, 0), fmt_num(case.get("imbalance"), 3),
            f"{fmt_ms(_engine_ms(mpi_one))} / {fmt_ms(_engine_ms(mpi_most))}"
            if mpi else (case.get("mpi_note") or "not run"),
            fmt_pct(100 * mpi_efficiency, 0),
            "ok" if case.get("checks_ok") is True else "**failed**"
            if case.get("checks_ok") is False else "?"])
        categories.append(label)
        for key, value in zip(series, [ms[("dense", 1)], ms[("rle", 1)], ms[("balanced", 1)],
                                       ms[("balanced", threads)], volpack_ms]):
            series[key].append(number(value))

    threads = settings.get("threads", "?")
    text = (f"`accelvolume_benchmark_shearwarp`: shaded composite, parallel camera turning "
            f"{settings.get('turn_degrees', '?')} degree per frame, median of "
            f"{settings.get('frames', '?')} frames of the engine time (encode + tables + "
            "composite + gather + CPU warp; no OpenGL display; the default warp runs on the GPU "
            "while drawing). Frame = the window's whole Render() with our image shown and one "
            "pixel read back (what a user waits for); VolPack's frame is its image in memory. "
            "The VolPack ratios are medians of paired per-frame ratios (frame: VolPack / our "
            "frame, engine: VolPack / our engine). Columns give 1 thread / "
            f"{threads} threads; (2) vs (1) and (3) vs (1) on {threads} threads; efficiency = "
            f"(3) 1-thread ms / ({threads} x (3) {threads}-thread ms); VolPack "
            f"({settings.get('volpack_mode', '?')}, classified volume, single-threaded) on the "
            "same volume, transfer function, view and image size; checks = byte-identity of "
            "thread counts, band splits and MPI ranks.\n\n")
    header = ["Case", "(1) no RLE ms", "(2) RLE+skip ms", "(3) +balance ms", "(2) vs (1)",
              "(3) vs (1)", "(3) 1t frame ms", "VolPack ms", "(3) 1t vs VolPack, frame",
              "engine", "Efficiency", "Imbalance",
              "MPI 1 / n ranks ms", "MPI eff.", "Checks"]
    text += table(header, rows, "l" + "r" * (len(header) - 1))
    if rows:
        text += ("\nRLE + skip links " + value_range(
            [c.value for c in section.speedups if c.group == RLE]) + " over no RLE, with "
            "balanced bands " + value_range(
                [c.value for c in section.speedups if c.group == BALANCED]) +
            "; ours (1 thread) vs VolPack " + value_range([c.value for c in section.peers]) +
            ".\n")
    text += _details(cases)
    text += f"\n{PAPER}\n"
    chart = ctx.chart_path("shearwarp_ms.png")
    if charts.grouped_bars(chart, "Shear-warp: engine ms per frame", categories,
                           list(series.items()), "ms per frame"):
        section.charts.append(chart)
        text += f"\n![Shear-warp times per case]({ctx.link(chart)})\n"
    section.markdown = text
    return section


def _details(cases):
    """Every run (threads, MPI ranks) with its time split, and every image check."""
    rows, checks = [], []
    for case in cases:
        key = case.get("key", "?")
        runs = [(run, f"{run.get('threads', '?')}t") for run in case.get("runs", [])]
        runs += [(run, f"MPI {run.get('ranks', '?')}r") for run in case.get("mpi", [])]
        for run, who in runs:
            rows.append([f"{key}: {run.get('id', '?')} {who}", fmt_ms(run.get("median_ms")),
                         fmt_ms(run.get("median_engine_ms")), fmt_ms(run.get("median_wall_ms")),
                         fmt_ms(run.get("median_composite_ms")), fmt_ms(run.get("median_warp_ms")),
                         fmt_ms(run.get("median_table_ms")), fmt_ms(run.get("median_gather_ms")),
                         fmt_num(run.get("mean_imbalance"), 3), fmt_num(run.get("median_cores")),
                         fmt_ms(run.get("first_frame_ms")), fmt_ms(run.get("encode_ms")),
                         fmt_count(run.get("voxels_per_frame")),
                         fmt_count(run.get("skipped_pixels_per_frame")), run.get("bands", "-")])
        for check in case.get("checks", []):
            ok = number(check.get("max_difference")) <= number(check.get("bound"))
            checks.append([f"{key}: {check.get('a', '?')} vs {check.get('b', '?')}",
                           check.get("bound", "?"), check.get("differing_pixels", "?"),
                           check.get("max_difference", "?"), "ok" if ok else "**failed**"])
    return (details("Every run (medians per frame)",
                    ["Case: run", "Render ms", "Engine ms", "Wall ms", "Composite ms", "Warp ms",
                     "Table ms", "Gather ms", "Imbalance", "Cores", "1st frame ms", "Encode ms",
                     "Voxels", "Skipped px", "Bands"], rows, "l" + "r" * 14) +
            details("Image checks (byte differences at the fixed view)",
                    ["Case: images", "Bound", "Differing pixels", "Max difference", "Result"],
                    checks, "lrrrr"))
