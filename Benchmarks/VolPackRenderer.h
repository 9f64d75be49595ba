// VolPackRenderer: Lacroute's VolPack (libvolpack) behind a neutral interface, for benchmarks.
//
// The shear-warp benchmark renders the same volume, transfer function, view and image size with
// VolPack's fastest path as the anchor of comparison: a classified (run-length encoded) volume
// built by vpClassifyVolume with the help of a min-max octree, rendered single-threaded by
// vpRenderClassifiedVolume with early ray termination (VP_MAX_RAY_OPACITY).
//
// What VolPack does differently from our shear-warp renderer (see VolPackRenderer.cxx):
// - Opacity IS corrected for the ray length between slices: VolPack stores each voxel's opacity
//   as a byte and looks it up in 1 - (1 - a)^L with L = sqrt(1 + shear_i^2 + shear_j^2), the
//   ray length per slice in voxel units (vp_view.c, ComputeAffineOpacityCorrection). The scene's
//   opacity table is per voxel of ray length, so this is the same convention as ours.
// - Classified voxels (opacity, opacity * colour) are resampled bilinearly in each slice; the
//   classified opacity and the final image are 8-bit (VP_LUMINANCEA in grey mode, VP_RGBA in
//   colour mode), so expect ~1/255 steps.
// - Two colour modes: grey (one channel, `grey`, VolPack's luminance mode) or RGB (`colour`
//   non-empty: three channels per voxel, VolPack's RGB lookup shader and VP_RGBA image, the work
//   of a colour renderer).
// - Shading (shade = true) uses VolPack's lookup shader over 13-bit quantized normals: colour =
//   c * (ambient + diffuse * max(N.L, 0)) + specular * max(N.H, 0)^power per channel (c the grey
//   or the r, g, b of the scalar; white light), the normal turned to face the viewer (VolPack
//   treats back-facing normals as the interior side).
#ifndef accelvolume_bench_VolPackRenderer_h
#define accelvolume_bench_VolPackRenderer_h

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace accelvolume
{
namespace bench
{

struct VolPackScene
{
  int dims[3] = { 0, 0, 0 };             // x fastest; each at most 1024 (VolPack's limit)
  const std::uint8_t* scalars = nullptr; // dims[0]*dims[1]*dims[2] 8-bit values
  std::vector<float> opacity;            // 256 entries in [0,1]: opacity per 8-bit scalar value,
                                         // for a sample spacing of one voxel
  std::vector<float> grey;               // 256 entries in [0,1]: grey colour per scalar value
                                         // (VolPack luminance mode; ignored when colour is set)
  std::vector<float> colour;             // empty (grey mode) or 256*3 entries in [0,1]: r, g, b
                                         // per scalar value (VolPack RGB mode)
  bool shade = false; // false: colour = grey / rgb (no lighting); true: Phong, one white
                      // directional light
  float ambient = 0.1f, diffuse = 0.7f, specular = 0.2f, specularPower = 10.0f;
  float lightDirection[3] = { 0, 0, 1 }; // in IMAGE coordinates (see below), towards the light
  int width = 0, height = 0;             // final image size in pixels
  // Parallel projection: voxel (x,y,z) index coordinates (voxel centres at integers) ->
  // continuous image coordinates; pixel (a,b) covers [a,a+1) x [b,b+1), rows counted from the
  // BOTTOM (b = 0 is the bottom row), the third row is depth increasing AWAY from the viewer.
  // Shading is exact when the linear part is a rotation (or reflection) times a uniform scale.
  double voxelToImage[3][4] = {};
  double maxRayOpacity = 0.99; // early ray termination threshold, in (0, 1]
};

class VolPackRenderer
{
public:
  VolPackRenderer();
  ~VolPackRenderer();
  VolPackRenderer(const VolPackRenderer&) = delete;
  VolPackRenderer& operator=(const VolPackRenderer&) = delete;

  // Builds VolPack's context, the raw voxels (with quantized normals when shading), the min-max
  // octree and the classified volume; the whole preprocessing is timed in ClassifySeconds().
  // The scalars are read only here. False with error on bad input (nothing is kept then).
  bool Prepare(const VolPackScene& scene, std::string& error);

  // Renders with the scene's view, image size, lighting and maxRayOpacity (the volume, opacity
  // and grey / colour are those given to Prepare; dims, shade and the colour mode must match).
  // rgba = width*height*4 floats, premultiplied by alpha, rows from the bottom; in grey mode
  // r = g = b = VolPack's luminance.
  // LastRenderSeconds() times VolPack's per-frame work (shading table and rendering).
  bool Render(const VolPackScene& scene, std::vector<float>& rgba, std::string& error);

  double ClassifySeconds() const;
  double LastRenderSeconds() const;

  // Principal viewing axis VolPack chose for the last Render (0 = x, 1 = y, 2 = z; -1: none).
  int LastPrincipalAxis() const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

}
}

#endif
