#!/usr/bin/env python3
"""RayCast: shaded composite on the CPU with vtkAccelVolumeRayCastMapper (a drop-in for
vtkFixedPointVolumeRayCastMapper), leaping over empty space with a distance map: each cell
stores the chessboard distance to the nearest cell that may be visible, so a ray in empty space
jumps that far in one step. Every leap is exact: the image equals LEAP_NONE's.

    RayCast.py [output.png] [--check]
"""
import _accelvolume_example as ex  # first: imports accelvolume before VTK's OpenGL modules
import accelvolume
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

NAME = "RayCast"
args = ex.parse_arguments(NAME)
image = ex.make_volume(64)

mapper = accelvolume.vtkAccelVolumeRayCastMapper()
mapper.SetInputData(image)
mapper.SetBlendModeToComposite()
mapper.SetLeapMode(accelvolume.vtkAccelVolumeRayCastMapper.LEAP_DISTANCE_MAP)  # the default
mapper.SetSampleDistance(0.5)          # world units: half a voxel
mapper.SetNumberOfThreads(2)           # rays split over threads; the image never changes
mapper.AutoAdjustSampleDistancesOff()  # a still frame: full resolution

opacity = vtkPiecewiseFunction()  # empty below 50: the distance map leaps over it
for x, y in ((0, 0.0), (50, 0.0), (140, 0.5), (255, 0.9)):
    opacity.AddPoint(x, y)
color = vtkColorTransferFunction()
color.AddRGBPoint(50, 0.3, 0.7, 0.3)
color.AddRGBPoint(160, 0.9, 0.6, 0.3)
color.AddRGBPoint(255, 1.0, 1.0, 1.0)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()
prop.ShadeOn()
prop.SetAmbient(0.2)
prop.SetDiffuse(0.7)
prop.SetSpecular(0.2)

# Rays are cast on the CPU; the image is shown as a textured quad, so an OpenGL window is still
# needed: a headless one through the module's factory.
_, _, window = ex.make_scene(mapper, prop, 30, 20, 1.5)
ex.render(NAME, window, mapper)
note = ex.write_png(NAME, window, args.output, args.check)
samples = mapper.GetLastNumberOfSamples()
leaped = mapper.GetLastSamplesLeapedByDistanceMap()
print("%s: shaded composite, %d rays, %d samples taken, %d leaped by the distance map (%.0f%%), "
      "%d rays terminated early, %.1f ms -> %s%s"
      % (NAME, mapper.GetLastNumberOfRays(), samples, leaped,
         100.0 * leaped / max(samples + leaped, 1), mapper.GetLastNumberOfTerminatedRays(),
         1000.0 * mapper.GetLastRenderTime(), args.output, note))
