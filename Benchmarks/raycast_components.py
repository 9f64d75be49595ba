"""Multi-component ray-cast benchmark: our CPU ray caster (default leaping, and with leaping off)
against vtkFixedPointVolumeRayCastMapper on multi-component scalars (issue 16), next to the
one-component composite frame. Same volume, functions, camera, sample distance, image sample
distance 1 and thread count; whole frames (render + RGBA readback), medians and ranges over
repeated frames, one run. The volumes and functions are drop_in_modes.py's.

    PYTHONPATH=build/lib/python3/dist-packages ACCELVOLUME_GL=egl \
        python3 Benchmarks/raycast_components.py [--size 512] [--frames 5] [--threads 0] \
        [--json out.json]

Prints a table and writes JSON. The fixed-point mapper combines components by its own rules
(the pictures differ; TestAccelVolumeVsGPURayCastFeatures compares ours with VTK's GPU mapper).
"""
import accelvolume  # first: registers the headless windows before VTK's OpenGL modules
import argparse
import json
import statistics

import drop_in_modes as modes
from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper

CASES = [case for case in modes.CASES if not case[4]]  # no depth pass on the CPU mappers


def make_mapper(key, threads):
    if key == "vtk_fixed":
        mapper = vtkFixedPointVolumeRayCastMapper()
        mapper.SetImageSampleDistance(1.0)
        mapper.SetAutoAdjustSampleDistances(0)
        if threads > 0:
            mapper.SetNumberOfThreads(threads)
        return mapper
    mapper = accelvolume.vtkAccelVolumeRayCastMapper()
    mapper.SetImageSampleDistance(1.0)
    if threads > 0:
        mapper.SetNumberOfThreads(threads)
    if key == "ours_no_leap":
        mapper.SetLeapMode(accelvolume.vtkAccelVolumeRayCastMapper.LEAP_NONE)
        mapper.SetCellLeaping(0)
    return mapper


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--threads", type=int, default=0, help="0: every core")
    parser.add_argument("--json", default="raycast_components.json")
    args = parser.parse_args()
    keys = ("vtk_fixed", "ours_no_leap", "ours")
    results = []
    print("%-10s %-28s %20s %20s %20s %9s %9s" % ("volume", "case", "VTK fixed ms", "ours, no leap",
                                                  "ours ms", "VTK/ours", "leap gain"))
    for volume_name in modes.VOLUMES:
        values, dims = modes.load(volume_name)
        for name, components, independent, blend, _ in CASES:
            image = modes.make_image(values, dims, components, independent)
            row = {"volume": volume_name, "case": name, "size": args.size,
                   "threads": args.threads}
            for key in keys:
                if key == "vtk_fixed" and blend == modes.AVERAGE:
                    row[key] = None  # the fixed-point mapper has no average intensity mode
                    continue
                mapper = make_mapper(key, args.threads)
                mapper.SetBlendMode(blend)
                times = modes.frame_times(mapper, image,
                                          modes.make_property(components, independent, blend),
                                          args.size, args.frames, False)
                row[key] = {"median_ms": statistics.median(times), "min_ms": min(times),
                            "max_ms": max(times)}
            row["speedup"] = (row["vtk_fixed"]["median_ms"] / row["ours"]["median_ms"]
                              if row["vtk_fixed"] else None)
            row["leap_gain"] = row["ours_no_leap"]["median_ms"] / row["ours"]["median_ms"]
            results.append(row)
            cells = ["%7.1f (%5.1f-%5.1f)" % (row[k]["median_ms"], row[k]["min_ms"],
                                              row[k]["max_ms"]) if row[k] else "n/a"
                     for k in keys]
            speedup = "%8.2fx" % row["speedup"] if row["speedup"] else "      n/a"
            print("%-10s %-28s %20s %20s %20s %s %8.2fx" % (volume_name, name, *cells, speedup,
                                                            row["leap_gain"]), flush=True)
    speedups = [r["speedup"] for r in results if r["speedup"]]
    gains = [r["leap_gain"] for r in results]
    print("median VTK/ours %.2fx (range %.2f-%.2fx), leaping %.2fx (%.2f-%.2fx) over %d cases"
          % (statistics.median(speedups), min(speedups), max(speedups), statistics.median(gains),
             min(gains), max(gains), len(speedups)))
    with open(args.json, "w") as f:
        json.dump({"frames": args.frames, "threads": args.threads, "results": results}, f,
                  indent=1)


if __name__ == "__main__":
    main()
