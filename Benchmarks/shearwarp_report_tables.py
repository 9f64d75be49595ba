#!/usr/bin/env python3
"""Markdown tables of docs/benchmarks/shearwarp-vs-volpack.md from the shear-warp benchmark's JSON.

    python3 Benchmarks/shearwarp_report_tables.py RESULTS.json [--mpi] [--model]

Prints one row per case (VolPack, our whole frame and engine, 1 and 2 threads, efficiency,
imbalance, the 16-core model, and with --mpi the MPI columns), the summary lines below it, and
with --model the scaling model's table over all cases. Ratios are the benchmark's own (medians of
paired per-frame ratios); the millisecond columns are medians.
"""
import argparse
import json
import statistics


def run(case, run_id, threads):
    for r in case["runs"]:
        if r["id"] == run_id and r["threads"] == threads:
            return r
    return None


def mpi_run(case, ranks):
    for r in case.get("mpi", []):
        if r["ranks"] == ranks:
            return r
    return None


def pct(x):
    return "%d%%" % round(100 * x)


def median_range(values, fmt):
    return "%s (%s-%s)" % (fmt % statistics.median(values), fmt % min(values), fmt % max(values))


def case_rows(cases, with_mpi):
    head = ["case", "VolPack ms", "ours frame ms (1t)", "frame ratio", "engine ms", "engine ratio",
            "composite ms", "2t frame ms", "2t frame ratio", "2-thread eff.", "imbal.",
            "model 16 cores (dyn.)"]
    if with_mpi:
        head += ["MPI 1r / 2r engine ms", "MPI eff."]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for c in cases:
        one, two = run(c, "balanced", 1), run(c, "balanced", c["threads"])
        model = c["scaling_model"].get("16", {})
        row = [c["key"], "%.1f" % c["volpack"]["median_ms"], "%.1f" % one["median_wall_ms"],
               "**%.2fx**" % c["volpack_ratio"], "%.1f" % one["median_engine_ms"],
               "%.2fx" % c["volpack_ratio_engine"], "%.1f" % one["median_composite_ms"],
               "%.1f" % two["median_wall_ms"], "%.2fx" % c["volpack_ratio_all_threads"],
               pct(c["efficiency"]), "%.3f" % c["imbalance"],
               "%.1fx (%.2f)" % (model.get("dynamic_speedup", float("nan")),
                                 model.get("dynamic_imbalance", float("nan")))]
        if with_mpi:
            r1, r2 = mpi_run(c, 1), mpi_run(c, 2)
            row += ["%.1f / %.1f" % (r1["median_engine_ms"], r2["median_engine_ms"]) if r1 and r2
                    else "-", pct(c["mpi_efficiency"]) if c.get("mpi_efficiency") is not None
                    else "-"]
        lines.append("| " + " | ".join(row) + " |")
    return lines


def summary(cases):
    frame = [c["volpack_ratio"] for c in cases]
    engine = [c["volpack_ratio_engine"] for c in cases]
    threads = [c["volpack_ratio_all_threads"] for c in cases]
    eff = [c["efficiency"] for c in cases]
    imb = [c["imbalance"] for c in cases]
    n = len(cases)
    return [
        "frame ratio (1 thread) median %s, %d of %d >= 1.5x; engine ratio median %s, %d of %d >= 1.5x;"
        " all threads frame ratio median %s; 2-thread efficiency median %d%% (%d-%d%%), %d of %d >= 90%%;"
        " imbalance median %.3f (max %.3f)" % (
            median_range(frame, "%.2fx"), sum(x >= 1.5 for x in frame), n,
            median_range(engine, "%.2fx"), sum(x >= 1.5 for x in engine), n,
            median_range(threads, "%.2fx"), round(100 * statistics.median(eff)),
            round(100 * min(eff)), round(100 * max(eff)), sum(x >= 0.9 for x in eff), n,
            statistics.median(imb), max(imb)),
        "image checks: %s" % ("all OK" if all(c["checks_ok"] for c in cases) else "FAILED in " +
                              ", ".join(c["key"] for c in cases if not c["checks_ok"])),
    ]


def model_table(cases):
    lines = ["| cores | static speed-up | static imbalance (max) | dynamic speed-up |"
             " dynamic imbalance (max) |", "|---|---|---|---|---|"]
    cores = sorted({int(k) for c in cases for k in c["scaling_model"]})
    for n in cores:
        models = [c["scaling_model"][str(n)] for c in cases if str(n) in c["scaling_model"]]
        s = [m["speedup"] for m in models]
        si = [m["imbalance"] for m in models]
        d = [m["dynamic_speedup"] for m in models]
        di = [m["dynamic_imbalance"] for m in models]
        lines.append("| %d | %s | %.2f (%.2f) | %s | %.2f (%.2f) |" % (
            n, median_range(s, "%.1fx"), statistics.median(si), max(si), median_range(d, "%.1fx"),
            statistics.median(di), max(di)))
    mpi = [c["mpi_efficiency"] for c in cases if c.get("mpi_efficiency") is not None]
    if mpi:
        lines += ["", "MPI efficiency median %d%% (%d-%d%%)" % (
            round(100 * statistics.median(mpi)), round(100 * min(mpi)), round(100 * max(mpi)))]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json")
    parser.add_argument("--mpi", action="store_true", help="MPI columns")
    parser.add_argument("--model", action="store_true", help="the scaling model's table")
    args = parser.parse_args()
    with open(args.json) as f:
        cases = json.load(f)["cases"]
    print("\n".join(case_rows(cases, args.mpi) + [""] + summary(cases)))
    if args.model:
        print("\n" + "\n".join(model_table(cases)))


if __name__ == "__main__":
    main()
