#!/usr/bin/env python3
"""ReadRealVolume: renders a real scan instead of the procedural volume: a gzip-compressed raw
file named NAME_XxYxZ_uint8.raw.gz (or _uint16, little endian) as in ../shared/data, read with
gzip into a vtkImageData (vtkImageImport) and shown as a MIP with the slice mapper. The data
folder is --data, else $ACCELVOLUME_DATA_DIR, else ../shared/data next to the checkout. Without
the file it exits with code 125 (ctest: skipped).

    ReadRealVolume.py [output.png] [--check] [--data DIR] [--input FILE.raw.gz]
"""
import gzip
import os
import re
import sys

import _accelvolume_example as ex  # first: imports accelvolume before VTK's OpenGL modules
import accelvolume
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkVolumeProperty

NAME = "ReadRealVolume"
args = ex.parse_arguments(NAME, data=True)
here = os.path.dirname(os.path.abspath(__file__))
folder = (args.data or os.environ.get("ACCELVOLUME_DATA_DIR")
          or os.path.normpath(os.path.join(here, "..", "..", "..", "shared", "data")))
path = args.input or os.path.join(folder, "HeadMRVolume_48x62x42_uint8.raw.gz")
# The raw file has no header: dimensions and type come from its name.
match = re.search(r"_(\d+)x(\d+)x(\d+)_(uint8|uint16)\.raw\.gz$", path)
if not match:
    ex.fail(NAME, "%s is not named NAME_XxYxZ_uint8|uint16.raw.gz" % path)
if not os.path.isfile(path):
    print("%s: %s not found, skipped" % (NAME, path))
    sys.exit(125)  # ctest SKIP_RETURN_CODE: the data folder is optional
dims = [int(match.group(i)) for i in (1, 2, 3)]
uint8 = match.group(4) == "uint8"
try:
    with gzip.open(path, "rb") as stream:
        data = stream.read()
except OSError as error:
    ex.fail(NAME, "cannot read %s: %s" % (path, error))
expected = dims[0] * dims[1] * dims[2] * (1 if uint8 else 2)
if len(data) != expected:
    ex.fail(NAME, "%s holds %d bytes, expected %d" % (path, len(data), expected))
# x fastest, then y, then z: VTK's own order (little endian, as vtkImageImport assumes here).
image = ex.import_volume(data, dims, "unsigned_char" if uint8 else "unsigned_short")
low, high = image.GetScalarRange()

mapper = accelvolume.vtkAccelVolumeSliceMapper()
mapper.SetInputData(image)
mapper.SetBlendModeToMaximumIntensity()
color = vtkColorTransferFunction()  # MIP: a grey ramp over the data range
color.AddRGBPoint(low, 0.0, 0.0, 0.0)
color.AddRGBPoint(high, 1.0, 1.0, 1.0)
opacity = vtkPiecewiseFunction()
opacity.AddPoint(low, 1.0)
opacity.AddPoint(high, 1.0)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.SetInterpolationTypeToLinear()

_, _, window = ex.make_scene(mapper, prop, 0, -90, 1.3)
ex.render(NAME, window, mapper)
note = ex.write_png(NAME, window, args.output, args.check)
print("%s: MIP of %s (%dx%dx%d, values %g..%g), %.1f ms -> %s%s"
      % (NAME, path, dims[0], dims[1], dims[2], low, high, 1000.0 * mapper.GetLastRenderTime(),
         args.output, note))
