"""The smart mapper's matrix: our three mappers (slice, CPU ray caster, shear-warp) and the smart
mapper's pick on the same volume, transfer function, view, image size and thread count, so that
vtkAccelVolumeSmartMapper's rule follows measurements (issue 17). Whole frames through the CLI
(`accelvolume render`: render + readback), medians over the turned frames, one process per cell.

    python3 Benchmarks/mapper_choice.py [--cli build/bin/accelvolume] [--data ../shared/data]
        [--datasets engine,cthead,bonsai_hazeremoved] [--tfs tf1,tf2] [--sizes 256,512]
        [--frames 5] [--threads 0] [--gl egl] [--json mapper_choice.json]

Shear-warp renders parallel views only: perspective rows leave it out. Prints a table (with the
fastest mapper per row and what the smart mapper picked) and writes JSON.
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

MAPPERS = ("slice", "raycast", "shearwarp", "smart")


def find_volume(data, name):
    files = sorted(glob.glob(os.path.join(data, name + "_[0-9]*x[0-9]*x[0-9]*_*.raw*")))
    if not files:
        sys.exit("mapper_choice: no volume named %s in %s" % (name, data))
    return files[0]


def spacing_of(data, name):
    try:
        with open(os.path.join(data, "datasets.json")) as handle:
            entries = json.load(handle)
    except OSError:
        return None
    for entry in entries.get("datasets", entries) if isinstance(entries, dict) else entries:
        if isinstance(entry, dict) and entry.get("name") == name:
            return entry.get("spacing")
    return None


def render(args, mapper, volume, spacing, tf, size, parallel):
    with tempfile.TemporaryDirectory() as folder:
        stats = os.path.join(folder, "stats.json")
        command = [args.cli, "render", "--mapper", mapper, "--input", volume, "--blend",
                   "composite", "--tf", tf, "--shade", "on", "--size", str(size), str(size),
                   "--frames", str(args.frames), "--gl", args.gl, "--stats", stats,
                   "--out", os.path.join(folder, "frame.png"),
                   "--parallel" if parallel else "--perspective"]
        if spacing:
            command += ["--spacing"] + [str(s) for s in spacing]
        if mapper != "slice":
            command += ["--threads", str(args.threads)]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            return None, result.stderr.strip().splitlines()[-1:] or ["failed"]
        with open(stats) as handle:
            data = json.load(handle)
    smart = data.get("smart") or {}
    return {"median_ms": data["ms_per_frame"]["median"], "min_ms": data["ms_per_frame"]["min"],
            "max_ms": data["ms_per_frame"]["max"], "picked": smart.get("mode"),
            "reason": smart.get("reason"), "gl_renderer": data.get("gl_renderer")}, None


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", default=os.path.join(root, "build", "bin", "accelvolume"))
    parser.add_argument("--data", default=os.environ.get("ACCELVOLUME_DATA_DIR",
                                                         os.path.join(root, "..", "shared", "data")))
    parser.add_argument("--datasets", default="engine,cthead,bonsai_hazeremoved")
    parser.add_argument("--tfs", default="tf1,tf2")
    parser.add_argument("--sizes", default="256,512")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--threads", type=int, default=0, help="CPU mappers' threads (0: all)")
    parser.add_argument("--gl", default="egl")
    parser.add_argument("--json", default="mapper_choice.json")
    args = parser.parse_args()
    if args.threads == 0:
        args.threads = os.cpu_count() or 1
    rows = []
    print("%-20s %-4s %5s %-11s %10s %10s %10s %10s  %-10s %-10s" % (
        "volume", "tf", "size", "projection", "slice ms", "raycast", "shearwarp", "smart",
        "fastest", "smart took"))
    for name in args.datasets.split(","):
        volume = find_volume(args.data, name)
        spacing = spacing_of(args.data, name)
        for tf in args.tfs.split(","):
            for size in [int(s) for s in args.sizes.split(",")]:
                for parallel in (True, False):
                    row = {"dataset": name, "tf": tf, "size": size,
                           "projection": "parallel" if parallel else "perspective",
                           "threads": args.threads, "mappers": {}}
                    for mapper in MAPPERS:
                        if mapper == "shearwarp" and not parallel:
                            continue
                        result, error = render(args, mapper, volume, spacing, tf, size, parallel)
                        row["mappers"][mapper] = result if result else {"error": error}
                    timed = {m: r["median_ms"] for m, r in row["mappers"].items()
                             if m != "smart" and "median_ms" in r}
                    row["fastest"] = min(timed, key=timed.get) if timed else None
                    smart = row["mappers"].get("smart", {})
                    row["smart_picked"] = smart.get("picked")
                    rows.append(row)

                    def cell(m):
                        r = row["mappers"].get(m)
                        return "-" if not r else ("%.1f" % r["median_ms"] if "median_ms" in r
                                                  else "fail")
                    print("%-20s %-4s %5d %-11s %10s %10s %10s %10s  %-10s %-10s" % (
                        name, tf, size, row["projection"], cell("slice"), cell("raycast"),
                        cell("shearwarp"), cell("smart"), row["fastest"], row["smart_picked"]))
                    sys.stdout.flush()
    renderer = next((r["mappers"][m].get("gl_renderer") for r in rows for m in r["mappers"]
                     if r["mappers"][m].get("gl_renderer")), None)
    with open(args.json, "w") as handle:
        json.dump({"benchmark": "mapper choice", "gl_renderer": renderer, "threads": args.threads,
                   "frames": args.frames, "cases": rows}, handle, indent=1)
    print("results written to %s" % args.json)


if __name__ == "__main__":
    main()
