#!/usr/bin/env python3
"""Downstream smoke test of the Python package `accelvolume`, outside the project.

Run by ../RunDownstream.cmake with PYTHONPATH = <prefix or build tree>/<package folder> +
VTK's vtkmodules folder, and ACCELVOLUME_EXPECT_DIR = the folder the package must come from.
Checks that:
  1. `import accelvolume` loads the package, its extension module and the module library
     from ACCELVOLUME_EXPECT_DIR's tree (never from the build tree when testing an install);
  2. the public classes are there and their settings round-trip;
  3. a plain vtkRenderWindow() is the headless window (the module's object factory);
  4. a small volume rendered by the slice mapper (OpenGL) and by the CPU ray caster is drawn
     and both pictures agree (mean |diff| per channel below MEAN_LIMIT).
Exit 0 on success, 1 with a FAILED line otherwise.
"""
import os
import sys

import accelvolume
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkCommonCore import VTK_UNSIGNED_CHAR
from vtkmodules.vtkRenderingCore import (
    vtkColorTransferFunction,
    vtkRenderer,
    vtkRenderWindow,
    vtkVolume,
    vtkVolumeProperty,
    vtkWindowToImageFilter,
)

SIZE = 96
# The same smooth blob by two different techniques (GPU slices vs CPU rays): measured mean
# |diff| 0.0005 per channel on llvmpipe (OSMesa and EGL); the bound is 6x that. A shifted
# camera, another transfer function or a missing volume gives 0.01 and more.
MEAN_LIMIT = 0.003
DRAWN_LIMIT = 0.05


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


def loaded_from(path, expect_dir):
    real = os.path.realpath(path)
    root = os.path.realpath(expect_dir)
    if not real.startswith(root + os.sep):
        fail("%s comes from outside %s" % (real, root))
    return real


def check_origin(expect_dir):
    package_file = loaded_from(accelvolume.__file__, expect_dir)
    extension = loaded_from(accelvolume.vtkRenderingAccelVolume.__file__, expect_dir)
    with open("/proc/self/maps") as maps:
        libraries = {line.split()[-1] for line in maps if "libvtkRenderingAccelVolume" in line}
    if len(libraries) != 1:
        fail("expected one libvtkRenderingAccelVolume loaded, found %s" % sorted(libraries))
    library = loaded_from(libraries.pop(), expect_dir)
    print("package:   " + package_file)
    print("extension: " + extension)
    print("library:   " + library)


def check_classes():
    for name in ("vtkAccelVolumeSliceMapper", "vtkAccelVolumeRayCastMapper",
                 "vtkAccelVolumeShearWarpMapper", "vtkAccelVolumeSmartMapper",
                 "vtkAccelVolumeMinMaxOctree", "vtkAccelVolumeHeadlessRenderWindow"):
        if not hasattr(accelvolume, name):
            fail("accelvolume has no " + name)
    mapper = accelvolume.vtkAccelVolumeRayCastMapper()
    mapper.SetLeapMode(accelvolume.vtkAccelVolumeRayCastMapper.LEAP_DISTANCE_MAP)
    mapper.SetNumberOfThreads(2)
    if (mapper.GetLeapMode() != accelvolume.vtkAccelVolumeRayCastMapper.LEAP_DISTANCE_MAP
            or mapper.GetNumberOfThreads() != 2):
        fail("vtkAccelVolumeRayCastMapper settings do not round-trip")


def make_blob():
    image = vtkImageData()
    n = 40
    image.SetDimensions(n, n, n)
    image.AllocateScalars(VTK_UNSIGNED_CHAR, 1)
    scalars = image.GetPointData().GetScalars()
    centre = (n - 1) / 2.0
    for k in range(n):
        for j in range(n):
            for i in range(n):
                r2 = ((i - centre) ** 2 + (j - centre) ** 2 + (k - centre) ** 2) / centre ** 2
                scalars.SetValue(i + n * (j + n * k), max(0, int(255 * (1.0 - r2))))
    return image


def render(mapper, image):
    window = vtkRenderWindow()
    if not isinstance(window, accelvolume.vtkAccelVolumeHeadlessRenderWindow):
        fail("vtkRenderWindow() is %s, not the headless window" % window.GetClassName())
    window.SetSize(SIZE, SIZE)
    window.SetMultiSamples(0)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    colours = vtkColorTransferFunction()
    colours.AddRGBPoint(0, 0.0, 0.0, 0.0)
    colours.AddRGBPoint(255, 1.0, 0.8, 0.5)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(0, 0.0)
    opacity.AddPoint(255, 0.3)
    prop = vtkVolumeProperty()
    prop.SetColor(colours)
    prop.SetScalarOpacity(opacity)
    prop.SetInterpolationTypeToLinear()
    mapper.SetInputData(image)
    mapper.SetBlendModeToComposite()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer.AddVolume(volume)
    renderer.GetActiveCamera().ParallelProjectionOn()
    renderer.ResetCamera()
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    pixels = grab.GetOutput().GetPointData().GetScalars()
    values = [pixels.GetValue(i) / 255.0 for i in range(pixels.GetNumberOfValues())]
    window.Finalize()
    return values


def main():
    expect_dir = os.environ.get("ACCELVOLUME_EXPECT_DIR")
    if not expect_dir:
        fail("set ACCELVOLUME_EXPECT_DIR to the tree the package must come from")
    check_origin(expect_dir)
    check_classes()
    image = make_blob()
    slices = render(accelvolume.vtkAccelVolumeSliceMapper(), image)
    rays = render(accelvolume.vtkAccelVolumeRayCastMapper(), image)
    drawn = sum(1 for v in rays if v > 0.02) / len(rays)
    mean = sum(abs(a - b) for a, b in zip(slices, rays)) / len(rays)
    print("drawn fraction %.3f, slice vs ray caster mean |diff| %.5f (limit %.3f)"
          % (drawn, mean, MEAN_LIMIT))
    if drawn < DRAWN_LIMIT:
        fail("the volume was not drawn (%.3f of the channel values lit)" % drawn)
    if mean > MEAN_LIMIT:
        fail("slice mapper and ray caster disagree: mean |diff| %.5f" % mean)
    print("Downstream Python check passed")


if __name__ == "__main__":
    main()
