// Odd but valid volumes give the image they must, with no message, for the slice, ray cast,
// shear-warp and smart mappers:
// - one voxel thick along x, y or z (a slab one voxel deep): its centre shows the transfer
//   function's colour of the centre value, seen head-on and obliquely, composite and MIP;
// - a constant volume (range [v, v + 1]): composite with opacity 1 shows colour(v) exactly,
//   MIP / MinIP colour(v) * opacity(v) over the background, raysum and average black (the value
//   is the bottom of the range); the shear-warp mapper refuses raysum / average clearly;
// - NaN and +-Inf in float and double data: every mapper renders them as the slice mapper's
//   texture holds them (NaN and -Inf as the finite minimum, +Inf as the finite maximum), i.e.
//   exactly like the volume with those values substituted; an all-NaN volume like all zeros.
#include "AccelVolumeBadInputSupport.h"

#include <limits>

namespace
{
using namespace accelvolume_test;

const int Blends[] = { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
  vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND,
  vtkVolumeMapper::AVERAGE_INTENSITY_BLEND };

const char* BlendName(int blend)
{
  const char* names[] = { "composite", "MIP", "MinIP", "average", "additive" };
  return blend >= 0 && blend <= 4 ? names[blend] : "other";
}

bool ShearWarpCannot(MapperKind kind, int blend)
{
  return kind == MapperKind::ShearWarp &&
    (blend == vtkVolumeMapper::ADDITIVE_BLEND || blend == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND);
}

// A render and whether the mapper stayed quiet (no error, no warning).
struct Rendered
{
  std::vector<float> Image;
  bool Quiet = true;
};

Rendered RenderOnce(MapperKind kind, vtkImageData* image, int blend,
  const std::vector<TransferPoint>& transfer, int axis, double azimuth, double elevation,
  const std::string& what, int size = 40)
{
  Probe probe(kind, image, size);
  double bounds[6];
  image->GetBounds(bounds);
  probe.LookAt(bounds, axis, azimuth, elevation);
  probe.Mapper->SetBlendMode(blend);
  SetTransfer(probe.Volume->GetProperty(), transfer);
  Rendered result;
  result.Image = probe.Render();
  result.Quiet = CheckNoMessage(probe.Errors, probe.Name(what) + ": no error") &&
    CheckNoMessage(probe.Warnings, probe.Name(what) + ": no warning");
  return result;
}

bool ThinSlabs(MapperKind kind)
{
  bool ok = true;
  // Opaque orange at 100, transparent black at 0: the block's colour exactly.
  const std::vector<TransferPoint> transfer = { { 0, 0, 0, 0, 0 }, { 100, 0.9, 0.5, 0.1, 1 } };
  const double orange[3] = { 0.9, 0.5, 0.1 };
  for (int axis = 0; axis < 3; ++axis)
  {
    int dims[3] = { 12, 10, 9 };
    dims[axis] = 1;
    auto slab = BlockVolume(VTK_UNSIGNED_SHORT, dims[0], dims[1], dims[2], 0, 100);
    for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND })
    {
      for (bool oblique : { false, true })
      {
        const std::string what = std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
          std::to_string(dims[2]) + " " + BlendName(blend) + (oblique ? " oblique" : " head-on");
        const Rendered r =
          RenderOnce(kind, slab, blend, transfer, axis, oblique ? 25 : 0, oblique ? 20 : 0, what);
        ok = r.Quiet && ok;
        ok = CheckCentre(r.Image, 40, orange, 2 * OneLevel,
               std::string(MapperName(kind)) + ", " + what + ": block colour") &&
          ok;
      }
    }
  }
  return ok;
}

bool ConstantVolumes(MapperKind kind)
{
  bool ok = true;
  for (int type : { VTK_UNSIGNED_CHAR, VTK_FLOAT })
  {
    auto constant = BlockVolume(type, 8, 8, 8, 5, 5);
    for (int blend : Blends)
    {
      const std::string what =
        std::string("constant ") + vtkImageScalarTypeNameMacro(type) + " " + BlendName(blend);
      const bool extremum = blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
        blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
      const double opacity = extremum ? 0.6 : 1.0;
      const std::vector<TransferPoint> transfer = { { 0, 0, 0, 0, 0 },
        { 5, 0.3, 0.8, 0.5, opacity } };
      if (ShearWarpCannot(kind, blend))
      {
        Probe probe(kind, constant);
        probe.Mapper->SetBlendMode(blend);
        SetTransfer(probe.Volume->GetProperty(), transfer);
        const std::vector<float> image = probe.Render();
        ok = CheckMessage(probe.Errors, "not supported by the shear-warp mapper",
               probe.Name(what) + ": error") &&
          ok;
        ok = CheckBackground(image, probe.Name(what) + ": background") && ok;
        continue;
      }
      const Rendered r = RenderOnce(kind, constant, blend, transfer, 2, 15, 10, what);
      ok = r.Quiet && ok;
      double expected[3] = { 0, 0, 0 }; // raysum / average: value 0 of the range [5, 6]
      if (blend == vtkVolumeMapper::COMPOSITE_BLEND)
      {
        expected[0] = 0.3, expected[1] = 0.8, expected[2] = 0.5;
      }
      else if (extremum)
      {
        const double colour[3] = { 0.3, 0.8, 0.5 };
        for (int c = 0; c < 3; ++c)
        {
          expected[c] = colour[c] * opacity + Background[c] * (1 - opacity);
        }
      }
      ok = CheckCentre(r.Image, 40, expected, 2 * OneLevel,
             std::string(MapperName(kind)) + ", " + what + ": predicted colour") &&
        ok;
    }
  }
  return ok;
}

// NaN at every 5th voxel and in a whole 8^3 corner (an octree leaf), +Inf at every 11th, -Inf
// at every 13th; `finite` gets the substitutes (NaN, -Inf: the finite minimum 20; +Inf: the
// finite maximum 100).
void Poison(vtkImageData* image, vtkImageData* finite)
{
  vtkDataArray* values = image->GetPointData()->GetScalars();
  vtkDataArray* substitutes = finite->GetPointData()->GetScalars();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  int dims[3];
  image->GetDimensions(dims);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    const int x = static_cast<int>(i % dims[0]), y = static_cast<int>(i / dims[0] % dims[1]),
              z = static_cast<int>(i / (dims[0] * dims[1]));
    if (i % 5 == 0 || (x < 8 && y < 8 && z < 8))
    {
      values->SetTuple1(i, nan);
      substitutes->SetTuple1(i, 20);
    }
    else if (i % 11 == 0)
    {
      values->SetTuple1(i, inf);
      substitutes->SetTuple1(i, 100);
    }
    else if (i % 13 == 0)
    {
      values->SetTuple1(i, -inf);
      substitutes->SetTuple1(i, 20);
    }
  }
  values->Modified();
  substitutes->Modified();
}

bool NonFinite(MapperKind kind)
{
  bool ok = true;
  // Opacity 0.3 at the minimum: NaN voxels are visible, so how they count shows.
  const std::vector<TransferPoint> transfer = { { 20, 0.1, 0.2, 0.9, 0.3 },
    { 50, 0.2, 0.9, 0.2, 0.05 }, { 100, 1, 0.9, 0.6, 0.9 } };
  for (int type : { VTK_FLOAT, VTK_DOUBLE })
  {
    auto poisoned = BlockVolume(type, 20, 18, 16, 20, 100);
    auto finite = BlockVolume(type, 20, 18, 16, 20, 100);
    Poison(poisoned, finite);
    for (int blend : Blends)
    {
      if (ShearWarpCannot(kind, blend))
      {
        continue;
      }
      const std::string what =
        std::string("NaN/Inf ") + vtkImageScalarTypeNameMacro(type) + " " + BlendName(blend);
      const Rendered withNaN = RenderOnce(kind, poisoned, blend, transfer, 2, 30, 25, what);
      const Rendered substituted =
        RenderOnce(kind, finite, blend, transfer, 2, 30, 25, what + " substituted");
      ok = withNaN.Quiet && substituted.Quiet && ok;
      ok = CheckImage(withNaN.Image, substituted.Image, OneLevel,
             std::string(MapperName(kind)) + ", " + what + ": as the substituted volume") &&
        ok;
    }
  }
  auto allNaN = BlockVolume(VTK_FLOAT, 9, 9, 9, std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::quiet_NaN());
  auto zeros = BlockVolume(VTK_FLOAT, 9, 9, 9, 0, 0);
  const std::vector<TransferPoint> flat = { { 0, 0.1, 0.2, 0.9, 0.5 }, { 1, 1, 1, 1, 1 } };
  const Rendered nanImage =
    RenderOnce(kind, allNaN, vtkVolumeMapper::COMPOSITE_BLEND, flat, 2, 30, 25, "all NaN");
  const Rendered zeroImage =
    RenderOnce(kind, zeros, vtkVolumeMapper::COMPOSITE_BLEND, flat, 2, 30, 25, "all zero");
  ok = nanImage.Quiet && zeroImage.Quiet && ok;
  ok = CheckImage(nanImage.Image, zeroImage.Image, OneLevel,
         std::string(MapperName(kind)) + ", all-NaN volume: as all zeros") &&
    ok;
  return ok;
}
}

int TestAccelVolumeOddVolumes(int, char*[])
{
  bool ok = true;
  for (MapperKind kind : AllMappers)
  {
    ok = ThinSlabs(kind) && ok;
    ok = ConstantVolumes(kind) && ok;
    ok = NonFinite(kind) && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
