#!/usr/bin/env python3
"""SliceComposite: shaded composite with vtkAccelVolumeSliceMapper and its two exact
accelerations: early ray termination (a mark pass every few slices stops opaque pixels) and
empty-space skipping with a min-max octree (slices clipped to the non-empty octree boxes).

    SliceComposite.py [output.png] [--check]
"""
import _accelvolume_example as ex  # first: imports accelvolume before VTK's OpenGL modules
import accelvolume
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

NAME = "SliceComposite"
args = ex.parse_arguments(NAME)
image = ex.make_volume(64)

mapper = accelvolume.vtkAccelVolumeSliceMapper()
mapper.SetInputData(image)
mapper.SetBlendModeToComposite()
mapper.EarlyRayTerminationOn()            # default on: mark pass every 16 slices
mapper.SetEarlyRayTerminationInterval(8)  # test more often: the blobs are opaque fast
mapper.SetEarlyRayTerminationThreshold(0.99)
# SKIP_BOTH = octree culling of whole empty blocks + per-fragment skipping of shading.
mapper.SetEmptySpaceSkipping(accelvolume.vtkAccelVolumeSliceMapper.SKIP_BOTH)
mapper.SetOctreeLeafSize(8)

opacity = vtkPiecewiseFunction()  # below 40 fully transparent: most of the box is skipped
for x, y in ((0, 0.0), (40, 0.0), (120, 0.6), (255, 0.9)):
    opacity.AddPoint(x, y)
color = vtkColorTransferFunction()
color.AddRGBPoint(40, 0.8, 0.3, 0.2)
color.AddRGBPoint(150, 0.9, 0.8, 0.4)
color.AddRGBPoint(255, 1.0, 1.0, 1.0)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()
prop.ShadeOn()  # Phong with VTK's light kit and these coefficients
prop.SetAmbient(0.2)
prop.SetDiffuse(0.7)
prop.SetSpecular(0.3)
prop.SetSpecularPower(20)

_, _, window = ex.make_scene(mapper, prop, 30, 20, 1.5)
ex.render(NAME, window, mapper)
note = ex.write_png(NAME, window, args.output, args.check)
print("%s: shaded composite, %d slices, %d termination passes, %.0f%% of octree leaves empty, "
      "%.0f%% of slice area kept, %.1f ms -> %s%s"
      % (NAME, mapper.GetLastNumberOfSlices(), mapper.GetLastNumberOfTerminationPasses(),
         100.0 * mapper.GetLastTransparentLeafFraction(),
         100.0 * mapper.GetLastProxyAreaFraction(), 1000.0 * mapper.GetLastRenderTime(),
         args.output, note))
