#!/usr/bin/env python3
"""The Python package `accelvolume` (VTK's own wrapping of VTK::RenderingAccelVolume).

Checks, with the Python VTK's bindings were built for (Debian: /usr/bin/python3) and
PYTHONPATH = the build tree's package folder + VTK's (ctest sets both, label "python"):
  1. `import accelvolume` gives the six public classes;
  2. importing it runs the module's auto-initialisation: its object factory makes a plain
     vtkRenderWindow() a vtkAccelVolumeHeadlessRenderWindow (ACCELVOLUME_GL=osmesa|egl);
  3. a small smooth volume (vtkRTAnalyticSource, 33^3) rendered headless, composite, parallel
     camera, by the CPU ray caster and by the shear-warp mapper is drawn (more than 1% of the
     pixels differ from the background) and the two pictures agree: mean |diff| per channel
     below MEAN_LIMIT and fewer than FRACTION_LIMIT of the channel values off by more than
     24/255 (the C++ agreement test's measure; shear-warp is not exact, see
     Testing/Cxx/TestAccelVolumeShearWarpAgreement.cxx for why).
Exit code 125 (ctest: skipped) when no headless backend is available.
"""
import os
import sys

import accelvolume
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkImagingCore import vtkImageShiftScale
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import (
    vtkColorTransferFunction,
    vtkRenderer,
    vtkRenderWindow,
    vtkVolume,
    vtkVolumeProperty,
    vtkWindowToImageFilter,
)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction

SIZE = 160
BACKGROUND = (0.1, 0.1, 0.2)
# Measured (llvmpipe, OSMesa and EGL alike, 2 cores): mean |diff| 0.00479, fraction over
# 24/255 0.00238; the volume covers about 0.38 (ray caster) and 0.41 (shear-warp, the bilinear
# warp's one-pixel fringe) of the window. The limits are 2.5x and 4x the measured values.
MEAN_LIMIT = 0.012
FRACTION_LIMIT = 0.01
DRAWN_LIMIT = 0.01

CLASSES = (
    "vtkAccelVolumeSliceMapper",
    "vtkAccelVolumeRayCastMapper",
    "vtkAccelVolumeShearWarpMapper",
    "vtkAccelVolumeSmartMapper",
    "vtkAccelVolumeMinMaxOctree",
    "vtkAccelVolumeHeadlessRenderWindow",
)


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)


def make_volume_data():
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-16, 16, -16, 16, -16, 16)
    # Values about 40..280; map them onto [0, 255] as unsigned char, the common case.
    shift = vtkImageShiftScale()
    shift.SetInputConnection(source.GetOutputPort())
    shift.SetShift(-40.0)
    shift.SetScale(255.0 / 240.0)
    shift.ClampOverflowOn()
    shift.SetOutputScalarTypeToUnsignedChar()
    shift.Update()
    return shift.GetOutput()


def render(window, mapper, image):
    mapper.SetInputData(image)
    mapper.SetBlendModeToComposite()
    colours = vtkColorTransferFunction()
    colours.AddRGBPoint(0.0, 0.0, 0.0, 0.0)
    colours.AddRGBPoint(100.0, 0.9, 0.4, 0.1)
    colours.AddRGBPoint(255.0, 1.0, 1.0, 0.8)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(0.0, 0.0)
    opacity.AddPoint(90.0, 0.0)
    opacity.AddPoint(255.0, 0.6)
    prop = vtkVolumeProperty()
    prop.SetColor(colours)
    prop.SetScalarOpacity(opacity)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtkRenderer()
    renderer.SetBackground(*BACKGROUND)
    renderer.AddVolume(volume)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    renderer.ResetCamera()
    camera.Azimuth(30.0)
    camera.Elevation(20.0)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    window.Render()

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    scalars = grab.GetOutput().GetPointData().GetScalars()
    if scalars.GetNumberOfComponents() != 3:
        fail("expected RGB pixels, got %d components" % scalars.GetNumberOfComponents())
    pixels = bytes(memoryview(scalars))
    window.RemoveRenderer(renderer)
    return pixels


def drawn_fraction(pixels):
    background = [round(255 * c) for c in BACKGROUND]
    drawn = 0
    count = len(pixels) // 3
    for i in range(count):
        p = pixels[3 * i : 3 * i + 3]
        if max(abs(p[c] - background[c]) for c in range(3)) > 8:
            drawn += 1
    return drawn / count


def main():
    missing = [name for name in CLASSES if not hasattr(accelvolume, name)]
    if missing:
        fail("accelvolume lacks " + ", ".join(missing))
    headless = accelvolume.vtkAccelVolumeHeadlessRenderWindow
    backend_name = os.environ.get("ACCELVOLUME_GL", "osmesa")
    backend = headless.ParseBackendName(backend_name)
    if not headless.IsBackendAvailable(backend):
        print("SKIPPED: headless backend %s is not available" % backend_name)
        sys.exit(125)

    # The module's factory, registered by its auto-initialisation when the package loads.
    window = vtkRenderWindow()
    if not window.IsA("vtkAccelVolumeHeadlessRenderWindow"):
        fail("vtkRenderWindow() gave %s: importing accelvolume did not register the module's "
             "object factory (auto-initialisation)" % window.GetClassName())
    window.SetSize(SIZE, SIZE)
    window.SetMultiSamples(0)
    window.OffScreenRenderingOn()

    image = make_volume_data()
    ray = accelvolume.vtkAccelVolumeRayCastMapper()
    ray.SetSampleDistance(0.25)
    ray_pixels = render(window, ray, image)
    shear = accelvolume.vtkAccelVolumeShearWarpMapper()
    shear_pixels = render(window, shear, image)
    print("window: %s, backend %s" % (window.GetClassName(),
                                       headless.GetBackendName(window.GetActiveBackend())))

    for name, pixels in (("ray caster", ray_pixels), ("shear-warp", shear_pixels)):
        fraction = drawn_fraction(pixels)
        print("%s: %.4f of the pixels drawn" % (name, fraction))
        if fraction <= DRAWN_LIMIT:
            fail("%s drew the volume on %.4f of the pixels (limit > %.2f)"
                 % (name, fraction, DRAWN_LIMIT))

    diffs = [abs(a - b) for a, b in zip(ray_pixels, shear_pixels)]
    mean = sum(diffs) / (255.0 * len(diffs))
    over = sum(1 for d in diffs if d > 24) / len(diffs)
    print("ray caster vs shear-warp: mean |diff| %.5f (limit %.3f), fraction over 24/255 %.5f "
          "(limit %.3f)" % (mean, MEAN_LIMIT, over, FRACTION_LIMIT))
    if mean >= MEAN_LIMIT or over >= FRACTION_LIMIT:
        fail("the ray caster's and the shear-warp mapper's pictures disagree")

    window.Finalize()
    print("PASSED")


if __name__ == "__main__":
    vtkObject.GlobalWarningDisplayOn()
    main()
