"""What every Python example shares: the command line, a procedural volume, the headless
window, error capture and writing / checking the PNG (the Python twin of
Examples/Cxx/Techniques/ExampleCommon.h), so each example shows only its technique.

Import this module (it imports `accelvolume`) before any other vtkmodules OpenGL module: the
package must be what loads VTK's OpenGL libraries for the OSMesa backend to work.
"""
import argparse
import math
import sys

import accelvolume  # noqa: F401  first: loads VTK's OpenGL libraries, registers the factory
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkImageImport
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkRenderer, vtkRenderWindow, vtkVolume,
                                         vtkWindowToImageFilter)

SIZE = 256
BACKGROUND = (0.1, 0.1, 0.2)


def fail(name, message):
    """A clear one-line error on stderr and exit code 1."""
    sys.stderr.write("%s: error: %s\n" % (name, message))
    sys.exit(1)


def parse_arguments(name, data=False):
    """[output.png] [--check] (ReadRealVolume also: [--data DIR] [--input FILE])."""
    parser = argparse.ArgumentParser(prog=name + ".py")
    parser.add_argument("output", nargs="?", default=name + ".png", help="PNG to write")
    parser.add_argument("--check", action="store_true",
                        help="read the PNG back and fail if it holds only background")
    if data:
        parser.add_argument("--data", help="folder of the real volumes (../shared/data)")
        parser.add_argument("--input", help="a NAME_XxYxZ_uint8|uint16.raw.gz file")
    return parser.parse_args()


def import_volume(data, dims, scalar_type="unsigned_char"):
    """A vtkImageData holding a copy of `data` (bytes, x fastest: VTK's own order)."""
    importer = vtkImageImport()
    importer.CopyImportVoidPointer(data, len(data))
    getattr(importer, "SetDataScalarTypeTo" + "".join(
        w.capitalize() for w in scalar_type.split("_")))()
    importer.SetNumberOfScalarComponents(1)
    importer.SetWholeExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1)
    importer.SetDataExtentToWholeExtent()
    importer.Update()
    image = vtkImageData()  # the importer's output points into its own copy, freed with it
    image.DeepCopy(importer.GetOutput())
    return image


def make_volume(n=64):
    """n^3 unsigned char: three Gaussian blobs and a thin torus, mostly empty space (the same
    volume as the C++ examples)."""
    blobs = ((0.30, 0.35, 0.40, 0.12), (0.70, 0.40, 0.55, 0.10), (0.50, 0.70, 0.35, 0.08))
    coords = [(i + 0.5) / n for i in range(n)]
    # Gaussians are separable: exp(-(dx^2+dy^2+dz^2)/r^2) = ex * ey * ez.
    axes = [[[math.exp(-((c - b[a]) ** 2) / b[3] ** 2) for c in coords] for a in range(3)]
            for b in blobs]
    ring = [[math.hypot(x - 0.5, y - 0.5) - 0.3 for x in coords] for y in coords]
    voxels = bytearray(n * n * n)
    i = 0
    for z in range(n):
        dz2 = (coords[z] - 0.5) ** 2
        zb = [255.0 * b[2][z] for b in axes]
        for y in range(n):
            yz = [zb[k] * axes[k][1][y] for k in range(3)]
            for x in range(n):
                r = ring[y][x]
                value = (yz[0] * axes[0][0][x] + yz[1] * axes[1][0][x] + yz[2] * axes[2][0][x]
                         + 200.0 * math.exp(-(r * r + dz2) / 0.0016))
                voxels[i] = 255 if value > 255.0 else int(value)
                i += 1
    return import_volume(bytes(voxels), (n, n, n))


class ErrorWatch:
    """Counts ErrorEvents of the watched objects, so a failed render exits non-zero."""

    def __init__(self, name, *objects):
        self.name, self.errors = name, 0
        for obj in objects:
            obj.AddObserver(vtkCommand.ErrorEvent, self._count)

    @calldata_type(VTK_STRING)
    def _count(self, obj, event, message):
        self.errors += 1
        sys.stderr.write("%s: error: %s\n" % (self.name, message))


def make_window(renderer):
    """256x256, no MSAA; the module's factory makes it headless (EGL / OSMesa)."""
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)  # volume mappers draw into their own targets
    window.SetSize(SIZE, SIZE)
    window.AddRenderer(renderer)
    renderer.SetBackground(*BACKGROUND)
    return window


def make_scene(mapper, prop, azimuth, elevation, zoom, parallel=False):
    """The volume in a renderer, the camera fitted, turned and zoomed (the bounding sphere leaves
    a wide margin), in the examples' window. Returns (volume, renderer, window)."""
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    camera = renderer.GetActiveCamera()
    camera.SetParallelProjection(parallel)
    renderer.ResetCamera()
    camera.Azimuth(azimuth)
    camera.Elevation(elevation)
    camera.OrthogonalizeViewUp()
    camera.Zoom(zoom)
    renderer.ResetCameraClippingRange()
    return volume, renderer, make_window(renderer)


def render(name, window, mapper, frames=1, camera=None):
    """Renders `frames` frames (camera.Azimuth(15) before each when camera is given)."""
    watch = ErrorWatch(name, mapper, window)
    for _ in range(frames):
        if camera is not None:
            camera.Azimuth(15)
            window.GetRenderers().GetFirstRenderer().ResetCameraClippingRange()
        window.Render()
        if watch.errors:
            fail(name, "rendering failed (%s)" % window.GetClassName())


def write_png(name, window, path, check):
    """Writes the window to `path`; with check, reads it back and requires 256x256 RGB with at
    least 1% of the pixels away from the background. Returns a short note for the summary."""
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()  # the offscreen framebuffer has no front buffer
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    if writer.GetErrorCode() != 0:
        fail(name, "cannot write " + path)
    if not check:
        return ""
    reader = vtkPNGReader()
    if not reader.CanReadFile(path):
        fail(name, "check failed: %s is not a readable PNG" % path)
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    comps = scalars.GetNumberOfComponents() if scalars else 0
    if image.GetDimensions()[:2] != (SIZE, SIZE) or comps < 3:
        fail(name, "check failed: %s is not a %dx%d RGB image" % (path, SIZE, SIZE))
    pixels = memoryview(scalars).cast("B")
    background = [255.0 * c for c in BACKGROUND]
    count = scalars.GetNumberOfTuples()
    drawn = sum(1 for i in range(0, count * comps, comps)
                if any(abs(pixels[i + c] - background[c]) > 3.0 for c in range(3)))
    if drawn * 100 < count:
        fail(name, "check failed: %s is blank (%d pixels differ from the background)"
             % (path, drawn))
    return ", check passed (%d of %d pixels drawn)" % (drawn, count)
