"""Drop-in modes benchmark: the slice mapper against vtkGPUVolumeRayCastMapper on the modes issue
16 added (multi-component scalars in every blend mode, the depth pass), next to the one-component
composite frame both already had. Same volume, functions, camera, sample distance and image;
whole frames (render + RGBA readback), medians and ranges over repeated frames, one run.

    PYTHONPATH=build/lib/python3/dist-packages ACCELVOLUME_GL=egl \
        python3 Benchmarks/drop_in_modes.py [--size 512] [--frames 7] [--json out.json]

Multi-component volumes are made from a real one (ACCELVOLUME_DATA_DIR or ../shared/data):
component 0 the volume, component 1 a Gaussian-smoothed copy, 2-3 its inverse and their maximum;
RGBA = a colour map of the volume with the volume as alpha. Prints a table and writes JSON.
"""
import accelvolume  # first: registers the headless windows before VTK's OpenGL modules
import argparse
import gzip
import json
import os
import statistics
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkImagingGeneral import vtkImageGaussianSmooth
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty)
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (OpenGL factories)
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.environ.get("ACCELVOLUME_DATA_DIR", os.path.join(HERE, "..", "..", "shared", "data"))
VOLUMES = {  # file, dims: engine is a tuning volume of the project, the MRI head is not
    "engine": ("engine_256x256x128_uint8.raw.gz", (256, 256, 128)),
    "mri_head": ("mri_t1_head_188x256x190_uint8.raw.gz", (188, 256, 190)),
}
COMPOSITE, MAXIMUM, MINIMUM, AVERAGE, ADDITIVE = 0, 1, 2, 3, 4
CASES = [  # name, components, independent, blend, depth pass
    ("1 component composite", 1, True, COMPOSITE, False),
    ("1 component composite, depth pass", 1, True, COMPOSITE, True),
    ("2 independent composite", 2, True, COMPOSITE, False),
    ("RGBA composite", 4, False, COMPOSITE, False),
    ("2 independent MIP", 2, True, MAXIMUM, False),
    ("RGBA MIP", 4, False, MAXIMUM, False),
    ("RGBA MinIP", 4, False, MINIMUM, False),
    ("4 independent average", 4, True, AVERAGE, False),
    ("2 independent raysum", 2, True, ADDITIVE, False),
]


def load(name):
    file, dims = VOLUMES[name]
    with gzip.open(os.path.join(DATA, file), "rb") as f:
        values = np.frombuffer(f.read(), dtype=np.uint8).astype(np.float32)
    return values, dims


def make_image(values, dims, components, independent):
    image = vtkImageData()
    image.SetDimensions(*dims)
    if components == 1:
        columns = [values]
    else:
        base = vtkImageData()
        base.SetDimensions(*dims)
        base.GetPointData().SetScalars(numpy_to_vtk(values, deep=1))
        smooth = vtkImageGaussianSmooth()
        smooth.SetInputData(base)
        smooth.SetStandardDeviations(2.0, 2.0, 2.0)
        smooth.Update()
        smoothed = np.array(smooth.GetOutput().GetPointData().GetScalars()).astype(np.float32)
        if independent:
            columns = [values, smoothed, 255.0 - values, np.maximum(values, smoothed)]
        else:  # RGBA: a warm colour map of the value, the value as alpha
            t = values / 255.0
            columns = [255.0 * np.sqrt(t), 255.0 * t * t, 255.0 * (1.0 - t) * t * 2.0, values]
        columns = columns[:components]
    data = np.stack(columns, axis=1).astype(np.uint8)
    array = numpy_to_vtk(data.reshape(-1, components), deep=1)
    image.GetPointData().SetScalars(array)
    return image


def make_property(components, independent, blend):
    prop = vtkVolumeProperty()
    prop.SetIndependentComponents(independent)
    prop.SetInterpolationTypeToLinear()
    for c in range(components if independent else 1):
        colour = vtkColorTransferFunction()
        colour.AddRGBPoint(0, 0.1 + 0.2 * c, 0.2, 0.9 - 0.2 * c)
        colour.AddRGBPoint(255, 1.0, 0.9 - 0.2 * c, 0.6)
        opacity = vtkPiecewiseFunction()
        if blend == MINIMUM:
            opacity.AddPoint(0, 0.8)
            opacity.AddPoint(180, 0.05)
        else:
            opacity.AddPoint(40, 0.0)
            opacity.AddPoint(255, 0.6)
        prop.SetColor(c, colour)
        prop.SetScalarOpacity(c, opacity)
    prop.SetShade(blend == COMPOSITE and components == 1)
    return prop


def frame_times(mapper, image, prop, size, frames, depth_pass):
    mapper.SetInputData(image)
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetSampleDistance(1.0)
    if depth_pass:
        mapper.SetUseDepthPass(1)
        mapper.GetDepthPassContourValues().SetValue(0, 90.0)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Azimuth(30)
    camera.Elevation(20)
    renderer.ResetCamera()
    pixels = vtkUnsignedCharArray()
    window.Render()  # first frame: uploads and shader builds, not timed
    window.GetRGBACharPixelData(0, 0, size - 1, size - 1, 0, pixels)
    times = []
    for _ in range(frames):
        start = time.perf_counter()
        window.Render()
        window.GetRGBACharPixelData(0, 0, size - 1, size - 1, 0, pixels)
        times.append(1000.0 * (time.perf_counter() - start))
    window.Finalize()
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--frames", type=int, default=7)
    parser.add_argument("--json", default="drop_in_modes.json")
    args = parser.parse_args()
    results = []
    print("%-10s %-36s %22s %22s %8s" % ("volume", "case", "VTK GPU ms (range)",
                                         "slice ms (range)", "VTK/ours"))
    for volume_name in VOLUMES:
        values, dims = load(volume_name)
        for name, components, independent, blend, depth_pass in CASES:
            image = make_image(values, dims, components, independent)
            row = {"volume": volume_name, "case": name, "size": args.size}
            for key, cls in (("vtk_gpu", vtkOpenGLGPUVolumeRayCastMapper),
                             ("slice", accelvolume.vtkAccelVolumeSliceMapper)):
                mapper = cls()
                mapper.SetBlendMode(blend)
                times = frame_times(mapper, image, make_property(components, independent, blend),
                                    args.size, args.frames, depth_pass)
                row[key] = {"median_ms": statistics.median(times), "min_ms": min(times),
                            "max_ms": max(times)}
            row["speedup"] = row["vtk_gpu"]["median_ms"] / row["slice"]["median_ms"]
            results.append(row)
            print("%-10s %-36s %8.1f (%5.1f-%5.1f) %8.1f (%5.1f-%5.1f) %7.2fx"
                  % (volume_name, name, row["vtk_gpu"]["median_ms"], row["vtk_gpu"]["min_ms"],
                     row["vtk_gpu"]["max_ms"], row["slice"]["median_ms"], row["slice"]["min_ms"],
                     row["slice"]["max_ms"], row["speedup"]), flush=True)
    speedups = [r["speedup"] for r in results]
    print("median VTK/ours %.2fx (range %.2f-%.2fx) over %d cases"
          % (statistics.median(speedups), min(speedups), max(speedups), len(speedups)))
    with open(args.json, "w") as f:
        json.dump({"renderer": "see GL_RENDERER of the run", "frames": args.frames,
                   "results": results}, f, indent=1)


if __name__ == "__main__":
    main()
