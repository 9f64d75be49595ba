// Phantoms: deterministic procedural test volumes shared by the tests, the examples and the CLI.
#ifndef accelvolume_Phantoms_h
#define accelvolume_Phantoms_h

#include <string>
#include <vector>

namespace accelvolume
{

// Scalar volume with x varying fastest, then y, then z; values lie in [0, 1000].
struct PhantomVolume
{
  int dims[3] = { 0, 0, 0 };
  double spacing[3] = { 1, 1, 1 };
  std::vector<float> values;
};

// Names accepted by GeneratePhantom, the default ("vessels") first.
std::vector<std::string> PhantomNames();

// Fills out with the named phantom:
//   vessels  bright curved tubes with a Gaussian cross-section over faint value noise (MIP),
//   shells   nested spherical shells of different intensities (cropping),
//   blobs    Gaussian blobs of different intensity and size,
//   ramp     value 1000 * i / (dims[0] - 1) along x (0 when dims[0] == 1), constant in y and z,
//   box      1000 inside voxels [dims / 4, dims - dims / 4) on every axis, 0 elsewhere (chords).
// Shapes live in normalized [0,1]^3 volume coordinates, so they stretch with non-cubic dims.
// The output depends only on the arguments. time animates the phantom with period 1: features move
// or pulse smoothly, and at time 0 ramp and box have exactly the analytic values above.
// Returns false and sets error for an unknown name, dims < 1, more than 2^31 voxels or a
// non-finite time; out is left untouched then.
bool GeneratePhantom(
  const std::string& name, const int dims[3], double time, PhantomVolume& out, std::string& error);

} // namespace accelvolume

#endif
