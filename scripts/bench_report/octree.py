"""Section of accelvolume_benchmark_octree: min-max octree builds (reference, Morton-order CPU on
one and all threads, OpenGL compute "GPU") against a one-thread read of the volume, and the
rebuild's share of a frame of a time-varying volume (Lim and Shin 2009)."""

from . import charts
from .common import (Comparison, Section, details, fmt_ms, fmt_num, fmt_pct, fmt_x, median,
                     number, ratio, records, table, value_range)

FILE = "octree.json"
TITLE = "Min-max octree build: CPU and GPU builders (Lim and Shin 2009)"
CPU_VS_REFERENCE = "octree build: CPU (all threads) vs reference"
GPU_VS_CPU = "octree build: GPU vs CPU (all threads)"
# Lim and Shin 2009 reports the GPU build about 38% (256^3) and 49% (512^3) faster than its CPU build
# (the table is garbled in the extracted text).
PAPER_RANGES = {GPU_VS_CPU: (1.38, 1.49)}
PAPER = ("Lim and Shin 2009 (CUDA): the GPU build of 256^3 and 512^3 volumes about 38% and 49% faster "
         "than the CPU build (table garbled in the source text); rendering with the octree "
         "26-31% faster than plain GPU ray casting (see the composite section's octree ESS).")


def _builds(dataset, where):
    """(reference, cpu on 1 thread, cpu on the most threads, gpu) build records or None."""
    builds = records(dataset, "builds", where)
    reference = next((b for b in builds if b.get("builder") == "reference"), None)
    cpus = sorted((b for b in builds if b.get("builder") == "cpu"),
                  key=lambda b: number(b.get("threads")))
    gpu = next((b for b in builds if b.get("builder") == "gpu"), None)
    one = next((b for b in cpus if b.get("threads") == 1), None)
    return reference, one, (cpus[-1] if cpus else None), gpu


def _ms(build):
    return build.get("median_ms") if build else None


def build(data, ctx):
    section = Section("octree", TITLE, gl_renderer=data.get("gl_renderer", ""))
    datasets = records(data, "datasets", FILE)
    threads = data.get("threads", "?")
    rows, names = [], []
    series = {"read floor": [], "reference": [], "CPU 1 thread": [],
              f"CPU {threads} threads": [], "GPU": []}
    phantom_text = ""
    for index, dataset in enumerate(datasets):
        where = f"{FILE} datasets[{index}]"
        name = dataset.get("name", "?")
        reference, one, most, gpu = _builds(dataset, where)
        floor = dataset.get("read_floor_ms")
        cpu_vs_ref = ratio(_ms(reference), _ms(most))
        gpu_vs_cpu = ratio(_ms(most), _ms(gpu))
        classify = dataset.get("classify_ms", {})
        rows.append([name, dataset.get("volume", "?"), fmt_ms(floor), fmt_ms(_ms(reference)),
                     fmt_ms(_ms(one)), fmt_ms(_ms(most)), fmt_ms(_ms(gpu)), fmt_x(cpu_vs_ref),
                     fmt_num(ratio(_ms(most), floor)), fmt_x(gpu_vs_cpu),
                     fmt_ms(classify.get("median") if isinstance(classify, dict) else None),
                     fmt_pct(100 * number(dataset.get("transparent_leaf_fraction")))])
        section.speedups.append(Comparison(CPU_VS_REFERENCE, name, cpu_vs_ref))
        section.speedups.append(Comparison(GPU_VS_CPU, name, gpu_vs_cpu))
        names.append(name)
        for key, value in zip(series, [floor, _ms(reference), _ms(one), _ms(most), _ms(gpu)]):
            series[key].append(number(value))
        frames = dataset.get("frames")
        if isinstance(frames, dict):
            phantom_text += (f"\nTime-varying volume **{name}** ({dataset.get('volume', '?')}): "
                             f"the octree rebuild takes "
                             f"{fmt_pct(number(frames.get('rebuild_percent_of_frame')), 2)} of a "
                             "frame (data update + rebuild + slice-mapper MIP at 512x512).\n")

    gpu_note = data.get("gpu_note")
    text = (f"`accelvolume_benchmark_octree`: leaf {data.get('leaf', '?')}, median of "
            f"{data.get('repeat', '?')} builds, {threads} threads "
            f"({data.get('smp_backend', '?')}); "
            "read floor = one thread summing every byte. \"x\" columns: reference ms / CPU ms, "
            "CPU ms / read-floor ms (1 = as fast as reading the data), CPU ms / GPU ms.\n\n")
    header = ["Dataset", "Volume", "Read floor ms", "Reference ms", "CPU 1t ms",
              f"CPU {threads}t ms", "GPU ms", "CPU vs ref.", "CPU / floor", "GPU vs CPU",
              "Re-classify ms", "Transparent leaves"]
    text += table(header, rows, "ll" + "r" * (len(header) - 2))
    text += phantom_text
    if gpu_note:
        text += f"\nGPU builder: {gpu_note}\n"
    if rows:
        text += ("\nCPU (all threads) vs reference: " +
                 value_range([c.value for c in section.speedups if c.group == CPU_VS_REFERENCE]) +
                 "; GPU vs CPU: " +
                 value_range([c.value for c in section.speedups if c.group == GPU_VS_CPU]) +
                 f" (GPU = OpenGL compute on {data.get('gl_renderer', '?')}).\n")
    text += _details(datasets)
    text += f"\n{PAPER}\n"
    chart = ctx.chart_path("octree_builds.png")
    if charts.grouped_bars(chart, "Min-max octree build time per builder", names,
                           list(series.items()), "ms"):
        section.charts.append(chart)
        text += f"\n![Octree build times]({ctx.link(chart)})\n"
    section.markdown = text
    return section


def _details(datasets):
    """Every build (throughput, ratios), the octrees, and the time-varying frames' breakdown."""
    builds, trees, frames = [], [], []
    for dataset in datasets:
        name = dataset.get("name", "?")
        reference, one, _, _ = _builds(dataset, FILE)
        for build in dataset.get("builds", []):
            builds.append([f"{name}: {build.get('builder', '?')} {build.get('threads', '?')}t",
                           fmt_ms(build.get("median_ms")), len(build.get("ms", [])),
                           "yes" if build.get("reduced_repeats") else "no",
                           fmt_num(1e-6 * number(dataset.get("bytes")) /
                                   number(build.get("median_ms"))),
                           fmt_x(ratio(_ms(reference), build.get("median_ms"))),
                           fmt_num(ratio(build.get("median_ms"), dataset.get("read_floor_ms")))])
        classify = dataset.get("classify_ms", {})
        classify = classify if isinstance(classify, dict) else {}
        trees.append([f"octree {name}", dataset.get("nodes", "?"), dataset.get("depth", "?"),
                      fmt_ms(classify.get("median")),
                      fmt_ms(min((number(v) for v in classify.get("all", [])), default=None)),
                      fmt_x(ratio(_ms(reference), _ms(one))), fmt_num(dataset.get("load_s"))])
        f = dataset.get("frames")
        if isinstance(f, dict):
            frames.append([f"frames {name}", len(f.get("frame_ms", [])),
                           fmt_ms(median(f.get("copy_ms", []))),
                           fmt_ms(median(f.get("rebuild_ms", []))),
                           fmt_ms(median(f.get("render_ms", []))),
                           fmt_ms(median(f.get("frame_ms", []))),
                           fmt_pct(number(f.get("rebuild_percent_of_frame"))),
                           fmt_ms(median(f.get("generate_ms", [])))])
    return (details("Every build", ["Dataset: builder", "Median ms", "Builds", "Fewer repeats",
                                    "GB/s", "vs reference", "/ read floor"], builds) +
            details("Octrees", ["Octree", "Nodes", "Depth", "Re-classify median ms",
                                "Re-classify min ms", "CPU 1t vs reference", "Load s"], trees) +
            details("Time-varying frames (medians; generation is outside the frame)",
                    ["Volume", "Frames", "Copy + Modified ms", "Rebuild ms",
                     "MIP render ms", "Frame ms", "Rebuild share", "Generate ms"], frames))
