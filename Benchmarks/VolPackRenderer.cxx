// VolPackRenderer: VolPack's classified-volume shear-warp renderer driven with our view
// convention (see VolPackRenderer.h).
//
// How VolPack maps the volume to its image (vp_view.c, VPComputeViewTransform):
//   screen = Viewport * PROJECT * VIEW * MODEL * Pre * voxel
// Pre moves voxel index coordinates into a unit cube (scale 1 / max(dims), centre dims / 2);
// Viewport maps x, y from [-1, 1] to [0, width] x [0, height] and depth z to -0.5 z + 0.5 (depth
// grows TOWARDS the viewer: front-to-back order and depth cueing rely on it). The composite is
// used as is: voxel (i, j, k) of slice k lands at intermediate (i + shear_i k + trans_i, ...),
// and the warp gives output pixel (x, y) the value of the screen point (x, y) exactly: pixel
// centres are at INTEGER screen coordinates, and output row y is memory row y (VolPack does not
// flip; only its PGM examples treat row 0 as the top). Hence the screen matrix we need is
//   row 0, 1: voxelToImage rows 0, 1 with the translation minus 0.5 (our centres are at a + 0.5),
//   row 2:    minus voxelToImage row 2 (our depth grows away from the viewer),
// and the image comes back with rows from the bottom, as we want.
//
// Lighting fixes how that screen matrix is split: vpShadeTable takes the light and the viewer
// (+z of world space, towards the viewer) into object space with MODEL^-1, i.e. it treats MODEL
// as orthonormal. So MODEL = F * Q, Q the orthogonal polar factor of voxelToImage's linear part
// and F = diag(1, 1, -1) (our image axes -> VolPack's world axes), PROJECT = identity and VIEW
// carries the rest: VIEW = Viewport^-1 * Screen * Pre^-1 * MODEL^-1. The light is given in world
// space as F * lightDirection, set while MODEL is the identity (vpSetLight applies MODEL).
//
// Colours: one lookup shader, 1 channel (grey) or 3 (RGB). Without shading the colour field is
// the scalar and the table is grey * 255 or (r, g, b) * 255 (VolPack colours are 0..255). With
// shading the colour field is the quantized normal and materials are blended per scalar by the
// weight table (vpShadeTable fills table[normal][material][channel]):
//   grey: material 0 (ambient, diffuse) weighted by grey, material 1 (specular only) by 1;
//   RGB:  materials 0, 1, 2 (ambient, diffuse in channel r, g, b alone) weighted by r, g, b,
//         material 3 (white specular only) by 1,
// so each channel is c * (ambient + diffuse N.L) + specular (N.H)^power.
#include "VolPackRenderer.h"

#include <volpack.h> // declares everything extern "C" itself when compiled as C++

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstring>

namespace accelvolume
{
namespace bench
{
namespace
{
using Mat4 = std::array<std::array<double, 4>, 4>;

// Raw voxel layout: field 0 = colour index (uint16: the scalar, or the quantized normal when
// shading; VolPack requires a 2-byte colour field), field 1 = scalar (uint8: classification and
// the material weights). The shading fields must come first, so the classified volume keeps
// field 0 (and field 1 when shading) plus one opacity byte per voxel.
constexpr int VoxelBytes = 4;
constexpr int IndexField = 0;
constexpr int ScalarField = 1;
constexpr int ScalarOffset = 2;
// Min-max octree: the values of VolPack's examples (subdivide nodes whose scalar range exceeds 4,
// down to 4^3 voxels).
constexpr int OctreeRange = 4;
constexpr int OctreeBaseNode = 4;

double Seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string VolPackError(const char* call, vpResult code)
{
  const char* text = vpGetErrorString(code);
  return std::string("VolPack ") + call + ": " + (text ? text : "unknown error") + " (" +
    std::to_string(code) + ")";
}

Mat4 Identity()
{
  Mat4 m{};
  for (int i = 0; i < 4; ++i)
  {
    m[i][i] = 1.0;
  }
  return m;
}

void ToVolPack(const Mat4& m, vpMatrix4 out)
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[r][c] = m[r][c];
    }
  }
}

Mat4 Multiply(const Mat4& a, const Mat4& b)
{
  Mat4 c{};
  for (int r = 0; r < 4; ++r)
  {
    for (int col = 0; col < 4; ++col)
    {
      for (int k = 0; k < 4; ++k)
      {
        c[r][col] += a[r][k] * b[k][col];
      }
    }
  }
  return c;
}

double Determinant3(const double m[3][3])
{
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Inverse transpose of a 3x3 matrix (false when singular).
bool InverseTranspose3(const double m[3][3], double out[3][3])
{
  const double det = Determinant3(m);
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det))
  {
    return false;
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      // Cofactor (r, c) / det is element (r, c) of the inverse transpose.
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      out[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
    }
  }
  return true;
}

// Orthogonal polar factor Q of m (m = Q * P, P symmetric positive definite) by Newton's
// iteration Q <- (Q + Q^-T) / 2: the rotation (or reflection) closest to the view's linear part.
bool OrthogonalFactor(const double m[3][3], double q[3][3])
{
  // Start from m scaled to unit determinant magnitude so the iteration converges quickly.
  const double det = Determinant3(m);
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det))
  {
    return false;
  }
  const double scale = 1.0 / std::cbrt(std::abs(det));
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      q[r][c] = m[r][c] * scale;
    }
  }
  for (int iteration = 0; iteration < 100; ++iteration)
  {
    double it[3][3];
    if (!InverseTranspose3(q, it))
    {
      return false;
    }
    double change = 0;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double next = 0.5 * (q[r][c] + it[r][c]);
        change = std::max(change, std::abs(next - q[r][c]));
        q[r][c] = next;
      }
    }
    if (change < 1e-14)
    {
      break;
    }
  }
  return true;
}

bool ValidTable(const std::vector<float>& table)
{
  if (table.size() != 256)
  {
    return false;
  }
  for (float v : table)
  {
    if (!(v >= 0.0f && v <= 1.0f))
    {
      return false;
    }
  }
  return true;
}

bool ValidColour(const std::vector<float>& table)
{
  if (table.size() != 256 * 3)
  {
    return false;
  }
  for (float v : table)
  {
    if (!(v >= 0.0f && v <= 1.0f))
    {
      return false;
    }
  }
  return true;
}

bool CheckVolume(const VolPackScene& scene, std::string& error)
{
  for (int a = 0; a < 3; ++a)
  {
    if (scene.dims[a] < 1 || scene.dims[a] > VP_MAX_VOLUME_DIM)
    {
      error = "VolPackRenderer: every dimension must be in [1, " +
        std::to_string(VP_MAX_VOLUME_DIM) + "] (VolPack's scanline limit)";
      return false;
    }
  }
  const double bytes = static_cast<double>(VoxelBytes) * scene.dims[0] * scene.dims[1] *
    static_cast<double>(scene.dims[2]);
  if (bytes > INT_MAX)
  {
    error = "VolPackRenderer: the volume is too large for VolPack (int sizes)";
    return false;
  }
  if (!scene.scalars)
  {
    error = "VolPackRenderer: no scalars";
    return false;
  }
  if (!ValidTable(scene.opacity))
  {
    error = "VolPackRenderer: opacity must have 256 entries in [0, 1]";
    return false;
  }
  if (scene.colour.empty() ? !ValidTable(scene.grey) : !ValidColour(scene.colour))
  {
    error = scene.colour.empty()
      ? "VolPackRenderer: grey must have 256 entries in [0, 1] (or give colour)"
      : "VolPackRenderer: colour must have 256 * 3 entries in [0, 1]";
    return false;
  }
  if (scene.shade)
  {
    const float m[4] = { scene.ambient, scene.diffuse, scene.specular, scene.specularPower };
    for (float v : m)
    {
      if (!(v >= 0.0f) || !std::isfinite(v))
      {
        error = "VolPackRenderer: material coefficients must be finite and >= 0";
        return false;
      }
    }
  }
  return true;
}
}

struct VolPackRenderer::Internals
{
  vpContext* Context = nullptr;
  int Dims[3] = { 0, 0, 0 };
  bool Shade = false;
  int Channels = 1; // 1: grey (VP_LUMINANCEA), 3: RGB (VP_RGBA)
  // VolPack keeps pointers to all of these: they live as long as the context.
  std::vector<std::uint8_t> Voxels;
  std::vector<float> OpacityTable;
  std::vector<float> ColourTable;
  std::vector<float> WeightTable;
  std::vector<std::uint8_t> Image; // VP_LUMINANCEA (2 bytes per pixel) or VP_RGBA (4), rows
                                   // from the bottom
  double ClassifySeconds = 0;
  double RenderSeconds = 0;
  int Axis = -1;

  ~Internals() { this->Release(); }

  void Release()
  {
    if (this->Context)
    {
      vpDestroyContext(this->Context);
      this->Context = nullptr;
    }
    this->Voxels.clear();
    this->Voxels.shrink_to_fit();
    this->Axis = -1;
  }

  bool Build(const VolPackScene& scene, std::string& error);
  bool SetView(const VolPackScene& scene, std::string& error);
};

// Calls VolPack; on failure sets `error` (naming the call) and returns false from the caller,
// which declares `vpResult code` and `std::string& error`.
#define ACCELVOLUME_VP(call)                                                                       \
  if ((code = (call)) != VP_OK)                                                                    \
  {                                                                                                \
    error = VolPackError(#call, code);                                                             \
    return false;                                                                                  \
  }

bool VolPackRenderer::Internals::Build(const VolPackScene& scene, std::string& error)
{
  vpContext* vpc = this->Context;
  const int nx = scene.dims[0], ny = scene.dims[1], nz = scene.dims[2];
  const std::size_t count = static_cast<std::size_t>(nx) * ny * nz;
  vpResult code = VP_OK;
  ACCELVOLUME_VP(vpSetVolumeSize(vpc, nx, ny, nz));
  ACCELVOLUME_VP(vpSetVoxelSize(vpc, VoxelBytes, 2, scene.shade ? 2 : 1, 1));
  ACCELVOLUME_VP(vpSetVoxelField(vpc, IndexField, 2, 0, scene.shade ? VP_NORM_MAX : VP_SCALAR_MAX));
  ACCELVOLUME_VP(vpSetVoxelField(vpc, ScalarField, 1, ScalarOffset, VP_SCALAR_MAX));
  this->Voxels.assign(count * VoxelBytes, 0);
  ACCELVOLUME_VP(vpSetRawVoxels(vpc, this->Voxels.data(), static_cast<int>(count * VoxelBytes),
    VoxelBytes, VoxelBytes * nx, VoxelBytes * nx * ny));
  if (scene.shade)
  {
    // Central-difference normals, quantized to VolPack's 13-bit code (0 on the volume's border).
    // VolPack only reads the scalars.
    ACCELVOLUME_VP(vpVolumeNormals(vpc, const_cast<unsigned char*>(scene.scalars),
      static_cast<int>(count), ScalarField, VP_SKIP_FIELD, IndexField));
  }
  else
  {
    std::uint8_t* voxel = this->Voxels.data();
    for (std::size_t v = 0; v < count; ++v, voxel += VoxelBytes)
    {
      const std::uint16_t index = scene.scalars[v];
      std::memcpy(voxel, &index, sizeof(index));
      voxel[ScalarOffset] = scene.scalars[v];
    }
  }

  this->OpacityTable = scene.opacity;
  ACCELVOLUME_VP(vpSetClassifierTable(vpc, 0, ScalarField, this->OpacityTable.data(),
    static_cast<int>(this->OpacityTable.size() * sizeof(float))));
  // Voxels whose opacity would round to byte 0 are dropped from the run-length encoding: they
  // contribute nothing either way (VolPack stores rint(opacity * 255)).
  ACCELVOLUME_VP(vpSetd(vpc, VP_MIN_VOXEL_OPACITY, 0.5 / 255.0));
  ACCELVOLUME_VP(vpMinMaxOctreeThreshold(vpc, 0, OctreeRange));
  ACCELVOLUME_VP(vpCreateMinMaxOctree(vpc, 0, OctreeBaseNode));
  ACCELVOLUME_VP(vpClassifyVolume(vpc));

  const int channels = this->Channels;
  if (scene.shade)
  {
    // Colour table [normal][material][channel], refilled by vpShadeTable every frame; weights
    // [scalar][material]: grey (or r, g, b) for the ambient + diffuse material(s), 1 for the
    // specular one (the last).
    const int materials = channels + 1;
    this->ColourTable.assign(
      static_cast<std::size_t>(VP_NORM_MAX + 1) * materials * channels, 0.0f);
    this->WeightTable.assign(static_cast<std::size_t>(256) * materials, 1.0f);
    for (int v = 0; v < 256; ++v)
    {
      for (int c = 0; c < channels; ++c)
      {
        this->WeightTable[materials * v + c] =
          channels == 1 ? scene.grey[v] : scene.colour[3 * v + c];
      }
    }
    ACCELVOLUME_VP(vpSetLookupShader(vpc, channels, materials, IndexField,
      this->ColourTable.data(), static_cast<int>(this->ColourTable.size() * sizeof(float)),
      ScalarField, this->WeightTable.data(),
      static_cast<int>(this->WeightTable.size() * sizeof(float))));
  }
  else
  {
    // Colour table [scalar][channel] (one material).
    this->ColourTable.resize(static_cast<std::size_t>(256) * channels);
    for (std::size_t i = 0; i < this->ColourTable.size(); ++i)
    {
      this->ColourTable[i] = 255.0f * (channels == 1 ? scene.grey[i] : scene.colour[i]);
    }
    this->WeightTable.clear();
    ACCELVOLUME_VP(vpSetLookupShader(vpc, channels, 1, IndexField, this->ColourTable.data(),
      static_cast<int>(this->ColourTable.size() * sizeof(float)), 0, nullptr, 0));
  }
  return true;
}

bool VolPackRenderer::Internals::SetView(const VolPackScene& scene, std::string& error)
{
  vpContext* vpc = this->Context;
  const double(*m)[4] = scene.voxelToImage;
  double linear[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      if (!std::isfinite(m[r][c]))
      {
        error = "VolPackRenderer: voxelToImage is not finite";
        return false;
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      linear[r][c] = m[r][c];
    }
  }
  double q[3][3];
  if (!OrthogonalFactor(linear, q))
  {
    error = "VolPackRenderer: voxelToImage is singular";
    return false;
  }
  const float* light = scene.lightDirection;
  if (scene.shade &&
    (!std::isfinite(light[0]) || !std::isfinite(light[1]) || !std::isfinite(light[2]) ||
      !(std::abs(light[0]) + std::abs(light[1]) + std::abs(light[2]) > 0)))
  {
    error = "VolPackRenderer: the light direction must be finite and non-zero";
    return false;
  }

  // The screen matrix VolPack must end up with (see the top of this file).
  Mat4 screen = Identity();
  for (int c = 0; c < 4; ++c)
  {
    screen[0][c] = m[0][c];
    screen[1][c] = m[1][c];
    screen[2][c] = -m[2][c];
  }
  screen[0][3] -= 0.5;
  screen[1][3] -= 0.5;

  // Pre^-1: unit cube -> voxel index coordinates.
  const int maxDim = std::max(this->Dims[0], std::max(this->Dims[1], this->Dims[2]));
  Mat4 preInverse = Identity();
  for (int a = 0; a < 3; ++a)
  {
    preInverse[a][a] = maxDim;
    preInverse[a][3] = 0.5 * this->Dims[a];
  }
  // Viewport^-1: screen -> [-1, 1] x, y and VolPack's depth.
  Mat4 viewportInverse = Identity();
  viewportInverse[0][0] = 2.0 / scene.width;
  viewportInverse[0][3] = -1.0;
  viewportInverse[1][1] = 2.0 / scene.height;
  viewportInverse[1][3] = -1.0;
  viewportInverse[2][2] = -2.0;
  viewportInverse[2][3] = 1.0;
  // MODEL = F * Q (orthogonal) and its inverse, the transpose.
  Mat4 model = Identity(), modelInverse = Identity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      model[r][c] = (r == 2 ? -1.0 : 1.0) * q[r][c];
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      modelInverse[r][c] = model[c][r];
    }
  }
  Mat4 view = Multiply(Multiply(Multiply(viewportInverse, screen), preInverse), modelInverse);

  vpResult code = VP_OK;
  vpMatrix4 matrix;
  ACCELVOLUME_VP(vpCurrentMatrix(vpc, VP_MODEL));
  ACCELVOLUME_VP(vpIdentityMatrix(vpc));
  if (scene.shade)
  {
    // World space = F * image space; vpSetLight applies the current (identity) MODEL.
    ACCELVOLUME_VP(vpSetLight(vpc, VP_LIGHT0, VP_DIRECTION, scene.lightDirection[0],
      scene.lightDirection[1], -static_cast<double>(scene.lightDirection[2])));
    ACCELVOLUME_VP(vpSetLight(vpc, VP_LIGHT0, VP_COLOR, 1.0, 1.0, 1.0));
    ACCELVOLUME_VP(vpEnable(vpc, VP_LIGHT0, 1));
    const double a = scene.ambient, d = scene.diffuse, s = scene.specular;
    const double p = scene.specularPower;
    // Materials 0 .. channels-1: ambient + diffuse in their own channel (grey: the one channel);
    // material `channels`: white specular only (see the top of this file).
    const int channels = this->Channels;
    for (int m = 0; m <= channels; ++m)
    {
      double amb[3] = { 0, 0, 0 }, diff[3] = { 0, 0, 0 }, spec[3] = { 0, 0, 0 };
      for (int c = 0; c < 3; ++c)
      {
        const bool own = m < channels && (channels == 1 || c == m);
        amb[c] = own ? a : 0.0;
        diff[c] = own ? d : 0.0;
        spec[c] = m == channels ? s : 0.0;
      }
      const int material = VP_MATERIAL0 + m;
      ACCELVOLUME_VP(
        vpSetMaterial(vpc, material, VP_AMBIENT, VP_BOTH_SIDES, amb[0], amb[1], amb[2]));
      ACCELVOLUME_VP(
        vpSetMaterial(vpc, material, VP_DIFFUSE, VP_BOTH_SIDES, diff[0], diff[1], diff[2]));
      ACCELVOLUME_VP(
        vpSetMaterial(vpc, material, VP_SPECULAR, VP_BOTH_SIDES, spec[0], spec[1], spec[2]));
      ACCELVOLUME_VP(vpSetMaterial(vpc, material, VP_SHINYNESS, VP_BOTH_SIDES, p, 0, 0));
    }
  }
  ToVolPack(model, matrix);
  ACCELVOLUME_VP(vpSetMatrix(vpc, matrix));
  ACCELVOLUME_VP(vpCurrentMatrix(vpc, VP_VIEW));
  ToVolPack(view, matrix);
  ACCELVOLUME_VP(vpSetMatrix(vpc, matrix));
  ACCELVOLUME_VP(vpCurrentMatrix(vpc, VP_PROJECT));
  ACCELVOLUME_VP(vpIdentityMatrix(vpc));
  ACCELVOLUME_VP(vpCurrentMatrix(vpc, VP_MODEL));

  // VolPack composes the screen matrix itself: make sure it is the one we meant.
  ACCELVOLUME_VP(vpGetMatrix(vpc, VP_SCREEN, matrix));
  double worst = 0, size = 1;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      worst = std::max(worst, std::abs(matrix[r][c] - screen[r][c]));
      size = std::max(size, std::abs(screen[r][c]));
    }
  }
  if (!(worst <= 1e-9 * size))
  {
    error = "VolPackRenderer: VolPack's screen matrix differs from voxelToImage";
    return false;
  }
  return true;
}

#undef ACCELVOLUME_VP

VolPackRenderer::VolPackRenderer()
  : Impl(new Internals)
{
}

VolPackRenderer::~VolPackRenderer() = default;

bool VolPackRenderer::Prepare(const VolPackScene& scene, std::string& error)
{
  this->Impl->Release();
  this->Impl->ClassifySeconds = 0;
  if (!CheckVolume(scene, error))
  {
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  this->Impl->Context = vpCreateContext();
  if (!this->Impl->Context)
  {
    error = "VolPackRenderer: vpCreateContext failed";
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->Impl->Dims[a] = scene.dims[a];
  }
  this->Impl->Shade = scene.shade;
  this->Impl->Channels = scene.colour.empty() ? 1 : 3;
  if (!this->Impl->Build(scene, error))
  {
    this->Impl->Release();
    return false;
  }
  this->Impl->ClassifySeconds = Seconds(t0);
  return true;
}

bool VolPackRenderer::Render(
  const VolPackScene& scene, std::vector<float>& rgba, std::string& error)
{
  Internals& impl = *this->Impl;
  impl.RenderSeconds = 0;
  impl.Axis = -1;
  if (!impl.Context)
  {
    error = "VolPackRenderer: Render before a successful Prepare";
    return false;
  }
  if (scene.dims[0] != impl.Dims[0] || scene.dims[1] != impl.Dims[1] ||
    scene.dims[2] != impl.Dims[2] || scene.shade != impl.Shade ||
    (scene.colour.empty() ? 1 : 3) != impl.Channels)
  {
    error = "VolPackRenderer: dims, shade and the colour mode (grey / colour) must be those "
            "given to Prepare";
    return false;
  }
  if (scene.width < 1 || scene.height < 1 ||
    static_cast<double>(scene.width) * scene.height * 4 > INT_MAX)
  {
    error = "VolPackRenderer: bad image size";
    return false;
  }
  if (!(scene.maxRayOpacity > 0.0 && scene.maxRayOpacity <= 1.0))
  {
    error = "VolPackRenderer: maxRayOpacity must be in (0, 1]";
    return false;
  }
  vpContext* vpc = impl.Context;
  const int pixelBytes = impl.Channels == 1 ? 2 : 4;
  impl.Image.assign(static_cast<std::size_t>(scene.width) * scene.height * pixelBytes, 0);
  vpResult code = vpSetImage(vpc, impl.Image.data(), scene.width, scene.height,
    scene.width * pixelBytes, impl.Channels == 1 ? VP_LUMINANCEA : VP_RGBA);
  if (code != VP_OK)
  {
    error = VolPackError("vpSetImage", code);
    return false;
  }
  if (!impl.SetView(scene, error))
  {
    return false;
  }
  if ((code = vpSetd(vpc, VP_MAX_RAY_OPACITY, scene.maxRayOpacity)) != VP_OK)
  {
    error = VolPackError("vpSetd(VP_MAX_RAY_OPACITY)", code);
    return false;
  }

  const auto t0 = std::chrono::steady_clock::now();
  if (scene.shade && (code = vpShadeTable(vpc)) != VP_OK)
  {
    error = VolPackError("vpShadeTable", code);
    return false;
  }
  if ((code = vpRenderClassifiedVolume(vpc)) != VP_OK)
  {
    error = VolPackError("vpRenderClassifiedVolume", code);
    return false;
  }
  impl.RenderSeconds = Seconds(t0);
  int axis = -1;
  if (vpGeti(vpc, VP_VIEW_AXIS, &axis) == VP_OK)
  {
    impl.Axis = axis;
  }

  // Colours are already premultiplied (VolPack composites colour * opacity).
  const std::size_t pixels = static_cast<std::size_t>(scene.width) * scene.height;
  rgba.resize(pixels * 4);
  const float toUnit = 1.0f / 255.0f;
  if (impl.Channels == 1)
  {
    for (std::size_t p = 0; p < pixels; ++p)
    {
      const float luminance = impl.Image[2 * p] * toUnit;
      rgba[4 * p + 0] = luminance;
      rgba[4 * p + 1] = luminance;
      rgba[4 * p + 2] = luminance;
      rgba[4 * p + 3] = impl.Image[2 * p + 1] * toUnit;
    }
  }
  else
  {
    for (std::size_t i = 0; i < pixels * 4; ++i)
    {
      rgba[i] = impl.Image[i] * toUnit; // VP_RGBA: r, g, b, a bytes
    }
  }
  return true;
}

double VolPackRenderer::ClassifySeconds() const
{
  return this->Impl->ClassifySeconds;
}

double VolPackRenderer::LastRenderSeconds() const
{
  return this->Impl->RenderSeconds;
}

int VolPackRenderer::LastPrincipalAxis() const
{
  return this->Impl->Axis;
}

}
}
