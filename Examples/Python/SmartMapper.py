#!/usr/bin/env python3
"""SmartMapper: vtkAccelVolumeSmartMapper picks one of the module's three mappers per frame
(slice on a hardware GPU, the exact CPU ray caster for still frames on software GL, shear-warp
for interactive parallel frames) and says which one it used and why. Renders a still frame and
then an interactive one (a high desired update rate) and prints both choices.

    SmartMapper.py [output.png] [--check]
"""
import _accelvolume_example as ex  # first: imports accelvolume before VTK's OpenGL modules
import accelvolume
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

NAME = "SmartMapper"
Mapper = accelvolume.vtkAccelVolumeSmartMapper
args = ex.parse_arguments(NAME)
image = ex.make_volume(64)

mapper = Mapper()
mapper.SetInputData(image)
mapper.SetBlendModeToComposite()
mapper.SetRequestedRenderModeToDefault()  # automatic choice (the default)
mapper.SetInteractiveUpdateRate(1.0)      # frames faster than 1 fps count as interactive

opacity = vtkPiecewiseFunction()
for x, y in ((0, 0.0), (50, 0.0), (150, 0.5), (255, 0.9)):
    opacity.AddPoint(x, y)
color = vtkColorTransferFunction()
color.AddRGBPoint(50, 0.2, 0.5, 0.9)
color.AddRGBPoint(150, 0.9, 0.7, 0.3)
color.AddRGBPoint(255, 1.0, 1.0, 1.0)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()
prop.ShadeOn()

# parallel projection lets the automatic choice consider shear-warp
_, _, window = ex.make_scene(mapper, prop, 30, 20, 1.5, parallel=True)
choices = []
for rate in (0.0001, 20.0):  # a still frame, then an interactive one (as an interactor does)
    window.SetDesiredUpdateRate(rate)
    ex.render(NAME, window, mapper)
    choices.append("%s (%s)" % (Mapper.GetRenderModeAsString(mapper.GetLastRenderMode()),
                                mapper.GetLastChoiceReason()))
note = ex.write_png(NAME, window, args.output, args.check)
print("%s: still frame: %s; interactive frame: %s -> %s%s"
      % (NAME, choices[0], choices[1], args.output, note))
