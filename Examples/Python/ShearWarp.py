#!/usr/bin/env python3
"""ShearWarp: vtkAccelVolumeShearWarpMapper, Lacroute & Levoy's shear-warp factorization on the
CPU: the classified volume is run-length encoded, slices are sheared and composited front to
back with skip links over opaque pixels, then warped into the view. Parallel cameras only.
Three turning frames: the later ones reuse the encoding and balance the threads' bands.

    ShearWarp.py [output.png] [--check]
"""
import _accelvolume_example as ex  # first: imports accelvolume before VTK's OpenGL modules
import accelvolume
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

NAME = "ShearWarp"
args = ex.parse_arguments(NAME)
image = ex.make_volume(64)

Mapper = accelvolume.vtkAccelVolumeShearWarpMapper
mapper = Mapper()
mapper.SetInputData(image)
mapper.SetBlendModeToComposite()
mapper.RunLengthEncodingOn()    # default: store and visit only contributing voxels
mapper.EarlyRayTerminationOn()  # default: skip links jump over saturated pixels
mapper.LoadBalancingOn()        # default: bands sized by the previous frame's costs
mapper.SetNumberOfThreads(0)    # 0 = every core this process may use
mapper.SetShadingMode(Mapper.SHADING_LOOKUP_TABLE)

opacity = vtkPiecewiseFunction()  # transparent voxels are not even stored
for x, y in ((0, 0.0), (50, 0.0), (150, 0.5), (255, 0.9)):
    opacity.AddPoint(x, y)
color = vtkColorTransferFunction()
color.AddRGBPoint(50, 0.4, 0.4, 0.9)
color.AddRGBPoint(150, 0.9, 0.5, 0.3)
color.AddRGBPoint(255, 1.0, 1.0, 1.0)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()
prop.ShadeOn()

# shear-warp renders parallel projections only
_, renderer, window = ex.make_scene(mapper, prop, 0, 20, 1.5, parallel=True)
ex.render(NAME, window, mapper, frames=3, camera=renderer.GetActiveCamera())  # Azimuth(15) before each frame
note = ex.write_png(NAME, window, args.output, args.check)
print("%s: shaded composite, parallel, %d bands, last frame %.1f ms, imbalance %.2f, principal "
      "axis %d, %d voxels stored, %d encoded bytes, %d pixel visits skipped -> %s%s"
      % (NAME, mapper.GetLastNumberOfBands(), 1000.0 * mapper.GetLastRenderTime(),
         mapper.GetLastImbalance(), mapper.GetLastPrincipalAxis(),
         mapper.GetLastNumberOfStoredVoxels(), mapper.GetEncodedBytes(),
         mapper.GetLastNumberOfSkippedPixels(), args.output, note))
