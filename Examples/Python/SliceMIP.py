#!/usr/bin/env python3
"""SliceMIP: maximum intensity projection with vtkAccelVolumeSliceMapper (view-aligned slices
on the GPU), cropped to a sub-volume, with the cut faces re-rendered so the oblique crop planes
show no slice aliasing even with few slices.

    SliceMIP.py [output.png] [--check]
"""
import _accelvolume_example as ex  # first: imports accelvolume before VTK's OpenGL modules
import accelvolume
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

NAME = "SliceMIP"
args = ex.parse_arguments(NAME)
image = ex.make_volume(64)  # spacing 1, origin 0: world = voxel index

mapper = accelvolume.vtkAccelVolumeSliceMapper()
mapper.SetInputData(image)
mapper.SetBlendModeToMaximumIntensity()
# Keep the middle of the volume (world coordinates); the crop cuts through the blobs.
mapper.CroppingOn()
mapper.SetCroppingRegionPlanes(10, 54, 6, 50, 12, 44)
mapper.SetCroppingRegionFlagsToSubVolume()
mapper.BoundaryRerenderingOn()  # the default; set here because it is what this shows
mapper.SetNumberOfSlices(32)    # deliberately coarse: the faces keep the crop exact

color = vtkColorTransferFunction()  # MIP: a grey ramp, fully opaque
color.AddRGBPoint(0, 0.0, 0.0, 0.0)
color.AddRGBPoint(255, 1.0, 1.0, 1.0)
opacity = vtkPiecewiseFunction()
opacity.AddPoint(0, 1.0)
opacity.AddPoint(255, 1.0)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()

# oblique, so the crop faces are not axis aligned
_, _, window = ex.make_scene(mapper, prop, 30, 20, 1.5)
ex.render(NAME, window, mapper)
note = ex.write_png(NAME, window, args.output, args.check)
print("%s: MIP of a 64^3 volume cropped to a sub-volume, %d slices, %d cut faces re-rendered, "
      "%.1f ms -> %s%s" % (NAME, mapper.GetLastNumberOfSlices(),
                           mapper.GetLastNumberOfBoundaryFaces(),
                           1000.0 * mapper.GetLastRenderTime(), args.output, note))
