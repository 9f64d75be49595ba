// VolPackRendererCheck: proves that VolPackRenderer places, orients and scales VolPack's image as
// voxelToImage says, by comparing it with an independent brute-force ray caster written here.
//
// The main risk of the wrapper is the view mapping (VolPack's own object / image conventions,
// half-pixel offsets, flips, the principal axis), so the volume is deliberately asymmetric and
// the views cover each principal axis, both viewing directions, scale, shift and a mirrored map.
// The reference: one ray through each pixel centre, samples where the ray crosses the integer
// slices of its principal axis (the step VolPack uses), trilinear scalar -> tables, opacity
// corrected for the step length (VolPack corrects by the same law), front-to-back compositing
// with the same early termination. It differs from VolPack in known, small ways (VolPack
// classifies voxels before resampling, resamples twice and stores 8-bit values), hence bounds.
// The colour mode (VolPack RGB, `colour` set) is checked against the same reference, unshaded and
// shaded, channel by channel; the shaded reference shades each voxel (central-difference normal,
// zero on the volume's border as vpVolumeNormals, turned to face the viewer) and interpolates the
// opacity-weighted colours, as VolPack classifies voxels before resampling (shaded grey too).
// Also checked: lighting follows lightDirection in image coordinates, shading leaves alpha
// alone, and Prepare / Render reject bad input with a message.
// Exit status 0: pass, 1: fail.
#include "VolPackReference.h"
#include "VolPackRenderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using accelvolume::bench::VolPackRenderer;
using accelvolume::bench::VolPackScene;
using accelvolume::bench::Normalize;
using accelvolume::bench::Reference;

namespace
{
constexpr int Width = 112;
constexpr int Height = 96;
// Agreement bounds (see the header comment for why the images are not identical).
constexpr double MaxMeanAlphaError = 0.03;  // over pixels covered by either image
constexpr double MaxCentroidError = 0.25;   // pixels; a half-pixel slip would show
constexpr double MaxMeanColourError = 0.03; // premultiplied grey / each of r, g, b

int Failures = 0;

void Expect(bool ok, const std::string& what)
{
  std::printf("  [%s] %s\n", ok ? "ok" : "FAIL", what.c_str());
  if (!ok)
  {
    ++Failures;
  }
}

// Asymmetric scene: a large blob off-centre, a small dense blob in the opposite corner and a bar
// along x, so that any flip, transposition or offset moves mass in the image.
std::vector<std::uint8_t> MakeVolume(const int dims[3])
{
  struct Blob
  {
    double c[3], r[3], peak;
  };
  const Blob blobs[] = { { { 22, 17, 15 }, { 13, 10, 9 }, 230 },
    { { 47, 33, 29 }, { 6, 5, 5 }, 255 }, { { 36, 36, 10 }, { 18, 2.5, 2.5 }, 200 } };
  std::vector<std::uint8_t> v(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        double value = 0;
        for (const Blob& b : blobs)
        {
          const double dx = (x - b.c[0]) / b.r[0], dy = (y - b.c[1]) / b.r[1];
          const double dz = (z - b.c[2]) / b.r[2];
          value = std::max(value, b.peak * std::exp(-1.5 * (dx * dx + dy * dy + dz * dz)));
        }
        v[x + static_cast<std::size_t>(dims[0]) * (y + static_cast<std::size_t>(dims[1]) * z)] =
          static_cast<std::uint8_t>(std::lround(std::min(255.0, value)));
      }
    }
  }
  return v;
}

// One centred spherical blob: shading asymmetries then come from the light alone.
std::vector<std::uint8_t> MakeSphere(const int dims[3])
{
  std::vector<std::uint8_t> v(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  std::size_t n = 0;
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x, ++n)
      {
        const double dx = x - 0.5 * (dims[0] - 1), dy = y - 0.5 * (dims[1] - 1);
        const double dz = z - 0.5 * (dims[2] - 1);
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        // Smooth step from 255 inside r = 12 to 0 outside r = 16.
        const double t = std::min(1.0, std::max(0.0, (16.0 - r) / 4.0));
        v[n] = static_cast<std::uint8_t>(std::lround(255.0 * t * t * (3 - 2 * t)));
      }
    }
  }
  return v;
}


// voxelToImage for a parallel camera looking along `forward` (away from the viewer) with `up`:
// image = scale * [right; up; forward] * (voxel - centre) + (W / 2 + shift, H / 2 + shift, 0).
// mirror flips the image horizontally (a reflection, det < 0).
void MakeView(const int dims[3], const double forwardIn[3], const double upIn[3], double scale,
  const double shift[2], bool mirror, double m[3][4])
{
  double f[3] = { forwardIn[0], forwardIn[1], forwardIn[2] };
  Normalize(f);
  double u[3] = { upIn[0], upIn[1], upIn[2] };
  const double fu = f[0] * u[0] + f[1] * u[1] + f[2] * u[2];
  for (int a = 0; a < 3; ++a)
  {
    u[a] -= fu * f[a];
  }
  Normalize(u);
  double r[3] = { f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0] };
  if (mirror)
  {
    for (double& c : r)
    {
      c = -c;
    }
  }
  const double* rows[3] = { r, u, f };
  const double centre[3] = { 0.5 * (dims[0] - 1), 0.5 * (dims[1] - 1), 0.5 * (dims[2] - 1) };
  const double offset[3] = { 0.5 * Width + shift[0], 0.5 * Height + shift[1], 0.0 };
  for (int row = 0; row < 3; ++row)
  {
    m[row][3] = offset[row];
    for (int c = 0; c < 3; ++c)
    {
      m[row][c] = scale * rows[row][c];
      m[row][3] -= scale * rows[row][c] * centre[c];
    }
  }
}


struct Comparison
{
  double meanAlpha = 0, maxAlpha = 0, meanColour = 0, centroid = 0; // meanColour: worst channel
  double meanChannel[3] = { 0, 0, 0 };
  double centroidA[2] = { 0, 0 }, centroidB[2] = { 0, 0 };
  double massA = 0, massB = 0;
};

void Centroid(const std::vector<float>& rgba, double c[2], double& mass)
{
  double sx = 0, sy = 0;
  mass = 0;
  for (int b = 0; b < Height; ++b)
  {
    for (int a = 0; a < Width; ++a)
    {
      const double w = rgba[4 * (a + static_cast<std::size_t>(Width) * b) + 3];
      sx += w * (a + 0.5);
      sy += w * (b + 0.5);
      mass += w;
    }
  }
  c[0] = mass > 0 ? sx / mass : 0;
  c[1] = mass > 0 ? sy / mass : 0;
}

Comparison Compare(const std::vector<float>& vp, const std::vector<float>& ref)
{
  Comparison r;
  std::size_t covered = 0;
  for (std::size_t p = 0; p < vp.size() / 4; ++p)
  {
    const double a = vp[4 * p + 3], b = ref[4 * p + 3];
    if (a > 0.02 || b > 0.02)
    {
      ++covered;
      r.meanAlpha += std::abs(a - b);
      for (int c = 0; c < 3; ++c)
      {
        r.meanChannel[c] += std::abs(vp[4 * p + c] - ref[4 * p + c]);
      }
    }
    r.maxAlpha = std::max(r.maxAlpha, std::abs(a - b));
  }
  r.meanAlpha /= std::max<std::size_t>(1, covered);
  for (double& m : r.meanChannel)
  {
    m /= std::max<std::size_t>(1, covered);
    r.meanColour = std::max(r.meanColour, m);
  }
  Centroid(vp, r.centroidA, r.massA);
  Centroid(ref, r.centroidB, r.massB);
  r.centroid = std::hypot(r.centroidA[0] - r.centroidB[0], r.centroidA[1] - r.centroidB[1]);
  return r;
}

VolPackScene BaseScene(const int dims[3], const std::vector<std::uint8_t>& volume)
{
  VolPackScene scene;
  for (int a = 0; a < 3; ++a)
  {
    scene.dims[a] = dims[a];
  }
  scene.scalars = volume.data();
  scene.opacity.resize(256);
  scene.grey.resize(256);
  for (int v = 0; v < 256; ++v)
  {
    scene.opacity[v] = v < 40 ? 0.0f : 0.3f * static_cast<float>(v - 40) / 215.0f;
    scene.grey[v] = 0.25f + 0.75f * static_cast<float>(v) / 255.0f;
  }
  scene.width = Width;
  scene.height = Height;
  return scene;
}

// Mean unpremultiplied brightness of the opaque-enough pixels on each side of a line through the
// alpha centroid (horizontal: left / right; vertical: bottom / top).
void SideBrightness(const std::vector<float>& rgba, bool horizontal, double& low, double& high)
{
  double c[2], mass;
  Centroid(rgba, c, mass);
  double sum[2] = { 0, 0 }, count[2] = { 0, 0 };
  for (int b = 0; b < Height; ++b)
  {
    for (int a = 0; a < Width; ++a)
    {
      const float* px = &rgba[4 * (a + static_cast<std::size_t>(Width) * b)];
      if (px[3] < 0.3f)
      {
        continue;
      }
      const int side = (horizontal ? a + 0.5 > c[0] : b + 0.5 > c[1]) ? 1 : 0;
      sum[side] += px[0] / px[3];
      count[side] += 1;
    }
  }
  low = count[0] > 0 ? sum[0] / count[0] : 0;
  high = count[1] > 0 ? sum[1] / count[1] : 0;
}

void CheckViews(const int dims[3], const std::vector<std::uint8_t>& volume)
{
  struct ViewCase
  {
    const char* name;
    double forward[3], up[3], scale, shift[2];
    bool mirror;
    int axis; // principal axis the view must produce
  };
  const ViewCase cases[] = {
    { "front (+z), unit scale", { 0, 0, 1 }, { 0, 1, 0 }, 1.0, { 0, 0 }, false, 2 },
    { "back (-z), scaled 1.3, shifted", { 0, 0, -1 }, { 0, 1, 0 }, 1.3, { 6.3, -4.6 }, false, 2 },
    { "oblique az 30 el 20 (+z)", { 0.47, 0.34, 0.81 }, { 0, 1, 0 }, 1.1, { -3.2, 2.7 }, false, 2 },
    { "principal x, oblique", { 0.9, 0.25, -0.35 }, { 0, 0, 1 }, 1.2, { 2.5, 1.5 }, false, 0 },
    { "principal -x, oblique", { -0.85, -0.3, 0.4 }, { 0, 1, 0 }, 0.9, { 0, 0 }, false, 0 },
    { "principal y (looking down -y)", { 0.25, -0.9, 0.3 }, { 0, 0, 1 }, 1.25, { -1, 3 }, false,
      1 },
    { "principal +y, mirrored image", { -0.3, 0.85, -0.35 }, { 1, 0, 0 }, 1.0, { 2, -2 }, true, 1 },
    { "negative side oblique (-x -y -z)", { -0.5, -0.45, -0.74 }, { 0, 1, 0 }, 1.15, { 0.5, 0.5 },
      false, 2 },
    { "partly outside the image", { 0.3, -0.2, 0.93 }, { 0, 1, 0 }, 1.4, { 38, -27 }, false, 2 },
  };
  VolPackScene scene = BaseScene(dims, volume);
  VolPackRenderer renderer;
  std::string error;
  const bool prepared = renderer.Prepare(scene, error);
  Expect(prepared, "Prepare (unshaded) " + error);
  std::printf("  Prepare (raw voxels, min-max octree, vpClassifyVolume): %.3f s\n",
    renderer.ClassifySeconds());
  std::printf("  bounds: mean |d alpha| < %.3f over covered pixels, centroid < %.2f px, "
              "mean |d colour| < %.3f\n",
    MaxMeanAlphaError, MaxCentroidError, MaxMeanColourError);
  for (const ViewCase& v : cases)
  {
    MakeView(dims, v.forward, v.up, v.scale, v.shift, v.mirror, scene.voxelToImage);
    std::vector<float> image;
    if (!renderer.Render(scene, image, error))
    {
      Expect(false, std::string(v.name) + ": Render failed: " + error);
      continue;
    }
    const std::vector<float> reference = Reference(scene);
    const Comparison c = Compare(image, reference);
    std::printf("  %-34s axis %d  mean|da| %.4f  max|da| %.3f  mean|dc| %.4f  centroid "
                "(%.2f, %.2f) vs (%.2f, %.2f) = %.3f px  mass %.0f / %.0f  %.2f ms\n",
      v.name, renderer.LastPrincipalAxis(), c.meanAlpha, c.maxAlpha, c.meanColour, c.centroidA[0],
      c.centroidA[1], c.centroidB[0], c.centroidB[1], c.centroid, c.massA, c.massB,
      1e3 * renderer.LastRenderSeconds());
    const bool ok = c.meanAlpha < MaxMeanAlphaError && c.centroid < MaxCentroidError &&
      c.meanColour < MaxMeanColourError && renderer.LastPrincipalAxis() == v.axis && c.massB > 50;
    Expect(ok, std::string(v.name) + " agrees with the reference");
  }
}

void CheckShading(const int dims[3])
{
  const std::vector<std::uint8_t> sphere = MakeSphere(dims);
  VolPackScene flat = BaseScene(dims, sphere);
  std::fill(flat.grey.begin(), flat.grey.end(), 1.0f);
  // Oblique view: image left / up are not voxel axes, so the light must follow the image.
  const double forward[3] = { 0.47, 0.34, 0.81 }, up[3] = { 0, 1, 0 }, shift[2] = { 0, 0 };
  MakeView(dims, forward, up, 1.1, shift, false, flat.voxelToImage);
  VolPackRenderer plain, lit;
  std::string error;
  std::vector<float> flatImage, litImage;
  const bool flatOk = plain.Prepare(flat, error) && plain.Render(flat, flatImage, error);
  Expect(flatOk, "unshaded sphere " + error);
  VolPackScene shaded = flat;
  shaded.shade = true;
  const bool prepared = lit.Prepare(shaded, error);
  Expect(prepared, "Prepare (shaded) " + error);
  if (!flatOk || !prepared)
  {
    return;
  }

  struct LightCase
  {
    const char* name;
    float direction[3];
    bool horizontal, brighterHigh; // which side must be brighter
  };
  const LightCase lights[] = { { "light from the image left", { -1, 0, -0.5f }, true, false },
    { "light from the image right", { 1, 0, -0.5f }, true, true },
    { "light from the image top", { 0, 1, -0.5f }, false, true },
    { "light from the image bottom", { 0, -1, -0.5f }, false, false } };
  for (const LightCase& l : lights)
  {
    std::copy(l.direction, l.direction + 3, shaded.lightDirection);
    if (!lit.Render(shaded, litImage, error))
    {
      Expect(false, std::string(l.name) + ": Render failed: " + error);
      continue;
    }
    double low = 0, high = 0;
    SideBrightness(litImage, l.horizontal, low, high);
    const double bright = l.brighterHigh ? high : low, dark = l.brighterHigh ? low : high;
    std::printf("  %-28s brightness lit side %.3f, far side %.3f\n", l.name, bright, dark);
    Expect(bright > 1.3 * dark, std::string(l.name) + " lights that side");
  }
  // Depth: image z grows away from the viewer, so (0, 0, -1) lights the visible (front) surface
  // and (0, 0, 1) lights it from behind (ambient only, VolPack turns normals to the viewer).
  double front[2] = { 0, 0 }, back[2] = { 0, 0 };
  const float towards[3] = { 0, 0, -1 }, behind[3] = { 0, 0, 1 };
  std::copy(behind, behind + 3, shaded.lightDirection);
  const bool backOk = lit.Render(shaded, litImage, error);
  SideBrightness(litImage, true, back[0], back[1]);
  std::copy(towards, towards + 3, shaded.lightDirection);
  const bool frontOk = lit.Render(shaded, litImage, error);
  SideBrightness(litImage, true, front[0], front[1]);
  std::printf("  light towards viewer: brightness %.3f; from behind: %.3f (ambient %.2f)\n",
    0.5 * (front[0] + front[1]), 0.5 * (back[0] + back[1]), shaded.ambient);
  Expect(backOk && frontOk && front[0] + front[1] > 3 * (back[0] + back[1]),
    "depth sign of the light direction");

  // Shading changes colour only; premultiplied colour never exceeds alpha (8-bit rounding aside).
  double alphaDiff = 0, excess = 0;
  for (std::size_t p = 0; p < litImage.size() / 4; ++p)
  {
    alphaDiff = std::max(alphaDiff, std::abs(double(litImage[4 * p + 3]) - flatImage[4 * p + 3]));
    excess = std::max(excess, double(litImage[4 * p]) - litImage[4 * p + 3]);
  }
  std::printf(
    "  alpha shaded vs unshaded: max diff %.4f; colour - alpha: max %.4f\n", alphaDiff, excess);
  Expect(alphaDiff <= 1.0 / 255 + 1e-6, "shading leaves alpha unchanged");
  Expect(excess <= 1.0 / 255 + 1e-6, "colour is premultiplied (<= alpha)");
}

// Colour ramps that differ per channel, so a swapped or dropped channel shows.
void SetColourRamps(VolPackScene& scene)
{
  scene.colour.resize(256 * 3);
  for (int v = 0; v < 256; ++v)
  {
    const float x = static_cast<float>(v) / 255.0f;
    scene.colour[3 * v + 0] = 0.15f + 0.85f * x;                                 // r: up
    scene.colour[3 * v + 1] = 1.0f - std::abs(2.0f * x - 1.0f) * 0.8f;          // g: hump
    scene.colour[3 * v + 2] = std::min(1.0f, std::max(0.0f, 0.95f - 0.9f * x)); // b: down
  }
}

// RGB mode (and shaded grey) against the reference, a few views, unshaded and shaded.
void CheckColour(const int dims[3], const std::vector<std::uint8_t>& volume)
{
  struct ViewCase
  {
    const char* name;
    double forward[3], up[3], scale, shift[2];
    bool mirror;
  };
  const ViewCase views[] = {
    { "front (+z)", { 0, 0, 1 }, { 0, 1, 0 }, 1.0, { 0, 0 }, false },
    { "oblique az 30 el 20 (+z)", { 0.47, 0.34, 0.81 }, { 0, 1, 0 }, 1.1, { -3.2, 2.7 }, false },
    { "principal x, oblique", { 0.9, 0.25, -0.35 }, { 0, 0, 1 }, 1.2, { 2.5, 1.5 }, false },
    { "principal +y, mirrored", { -0.3, 0.85, -0.35 }, { 1, 0, 0 }, 1.0, { 2, -2 }, true },
  };
  struct ModeCase
  {
    const char* name;
    bool colour, shade;
  };
  const ModeCase modes[] = { { "rgb unshaded", true, false }, { "rgb shaded", true, true },
    { "grey shaded", false, true } };
  const float light[3] = { 0.45f, 0.55f, -0.7f }; // image right, up, towards the viewer
  for (const ModeCase& mode : modes)
  {
    VolPackScene scene = BaseScene(dims, volume);
    if (mode.colour)
    {
      SetColourRamps(scene);
    }
    scene.shade = mode.shade;
    std::copy(light, light + 3, scene.lightDirection);
    VolPackRenderer renderer;
    std::string error;
    const bool prepared = renderer.Prepare(scene, error);
    Expect(prepared, std::string("Prepare (") + mode.name + ") " + error);
    if (!prepared)
    {
      continue;
    }
    for (const ViewCase& v : views)
    {
      MakeView(dims, v.forward, v.up, v.scale, v.shift, v.mirror, scene.voxelToImage);
      std::vector<float> image;
      const std::string name = std::string(mode.name) + ", " + v.name;
      if (!renderer.Render(scene, image, error))
      {
        Expect(false, name + ": Render failed: " + error);
        continue;
      }
      const Comparison c = Compare(image, Reference(scene));
      std::printf("  %-42s mean|da| %.4f  mean|dc| r %.4f g %.4f b %.4f  centroid %.3f px  "
                  "%.2f ms\n",
        name.c_str(), c.meanAlpha, c.meanChannel[0], c.meanChannel[1], c.meanChannel[2],
        c.centroid, 1e3 * renderer.LastRenderSeconds());
      const bool ok = c.meanAlpha < MaxMeanAlphaError && c.centroid < MaxCentroidError &&
        c.meanColour < MaxMeanColourError && c.massB > 50;
      Expect(ok, name + " agrees with the reference");
    }
  }

  // The colour mode changes colours only: alpha as in grey mode, and each channel follows its
  // own ramp (grey = the mean of the ramps gives the mean of the channels, up to rounding).
  VolPackScene grey = BaseScene(dims, volume), rgb = grey;
  SetColourRamps(rgb);
  for (int v = 0; v < 256; ++v)
  {
    grey.grey[v] = (rgb.colour[3 * v] + rgb.colour[3 * v + 1] + rgb.colour[3 * v + 2]) / 3.0f;
  }
  const double forward[3] = { 0.47, 0.34, 0.81 }, up[3] = { 0, 1, 0 }, shift[2] = { 0, 0 };
  MakeView(dims, forward, up, 1.1, shift, false, grey.voxelToImage);
  MakeView(dims, forward, up, 1.1, shift, false, rgb.voxelToImage);
  VolPackRenderer g, c;
  std::string error;
  std::vector<float> gi, ci;
  const bool ok = g.Prepare(grey, error) && g.Render(grey, gi, error) && c.Prepare(rgb, error) &&
    c.Render(rgb, ci, error);
  Expect(ok, "grey and rgb renders " + error);
  if (ok)
  {
    double alphaDiff = 0, meanDiff = 0, spread = 0;
    for (std::size_t p = 0; p < gi.size() / 4; ++p)
    {
      alphaDiff = std::max(alphaDiff, std::abs(double(gi[4 * p + 3]) - ci[4 * p + 3]));
      meanDiff = std::max(
        meanDiff, std::abs((ci[4 * p] + ci[4 * p + 1] + ci[4 * p + 2]) / 3.0 - gi[4 * p]));
      spread = std::max(spread, double(std::abs(ci[4 * p] - ci[4 * p + 2])));
    }
    std::printf("  rgb vs grey (grey = mean of the ramps): alpha max diff %.4f, mean(r,g,b) - grey "
                "max %.4f, max |r - b| %.3f\n",
      alphaDiff, meanDiff, spread);
    Expect(alphaDiff <= 1e-6, "colour mode leaves alpha as in grey mode");
    Expect(meanDiff <= 2.0 / 255 + 1e-6, "mean of the channels is the grey image");
    Expect(spread > 0.1, "channels differ (colour is not grey)");
  }
}

void CheckErrors(const int dims[3], const std::vector<std::uint8_t>& volume)
{
  const VolPackScene good = BaseScene(dims, volume);
  struct BadCase
  {
    const char* name;
    VolPackScene scene;
  };
  std::vector<BadCase> bad;
  bad.push_back({ "null scalars", good });
  bad.back().scene.scalars = nullptr;
  bad.push_back({ "zero dimension", good });
  bad.back().scene.dims[1] = 0;
  bad.push_back({ "dimension above 1024", good });
  bad.back().scene.dims[0] = 2000;
  bad.push_back({ "opacity with 255 entries", good });
  bad.back().scene.opacity.resize(255);
  bad.push_back({ "empty grey table", good });
  bad.back().scene.grey.clear();
  bad.push_back({ "opacity above 1", good });
  bad.back().scene.opacity[100] = 1.5f;
  bad.push_back({ "NaN grey", good });
  bad.back().scene.grey[7] = std::nanf("");
  bad.push_back({ "colour with 255 * 3 entries", good });
  SetColourRamps(bad.back().scene);
  bad.back().scene.colour.resize(255 * 3);
  bad.push_back({ "NaN colour", good });
  SetColourRamps(bad.back().scene);
  bad.back().scene.colour[100] = std::nanf("");
  bad.push_back({ "colour above 1", good });
  SetColourRamps(bad.back().scene);
  bad.back().scene.colour[5] = 1.01f;
  bad.push_back({ "negative diffuse (shaded)", good });
  bad.back().scene.shade = true;
  bad.back().scene.diffuse = -1.0f;
  for (const BadCase& b : bad)
  {
    VolPackRenderer renderer;
    std::string error;
    const bool prepared = renderer.Prepare(b.scene, error);
    Expect(!prepared && !error.empty(), std::string("Prepare rejects ") + b.name + ": " + error);
  }

  VolPackRenderer renderer;
  std::string error;
  std::vector<float> image;
  VolPackScene scene = good;
  const double forward[3] = { 0, 0, 1 }, up[3] = { 0, 1, 0 }, shift[2] = { 0, 0 };
  MakeView(dims, forward, up, 1.0, shift, false, scene.voxelToImage);
  const bool early = renderer.Render(scene, image, error);
  Expect(!early && !error.empty(), "Render before Prepare fails: " + error);
  error.clear();
  const bool prepared = renderer.Prepare(scene, error);
  Expect(prepared, "Prepare " + error);
  struct RenderCase
  {
    const char* name;
    VolPackScene scene;
  };
  std::vector<RenderCase> renders;
  renders.push_back({ "zero width", scene });
  renders.back().scene.width = 0;
  renders.push_back({ "singular voxelToImage", scene });
  for (int c = 0; c < 4; ++c)
  {
    renders.back().scene.voxelToImage[2][c] = 0;
  }
  renders.push_back({ "maxRayOpacity 0", scene });
  renders.back().scene.maxRayOpacity = 0;
  renders.push_back({ "other dims than Prepare", scene });
  renders.back().scene.dims[2] = dims[2] - 1;
  renders.push_back({ "shade differs from Prepare", scene });
  renders.back().scene.shade = true;
  renders.push_back({ "colour mode differs from Prepare", scene });
  SetColourRamps(renders.back().scene);
  for (const RenderCase& r : renders)
  {
    error.clear();
    const bool rendered = renderer.Render(r.scene, image, error);
    Expect(!rendered && !error.empty(), std::string("Render rejects ") + r.name + ": " + error);
  }
  error.clear();
  const bool again = renderer.Render(scene, image, error);
  Expect(again, "Render still works after rejections " + error);
}
}

int main()
{
  const int dims[3] = { 64, 48, 40 };
  const std::vector<std::uint8_t> volume = MakeVolume(dims);
  std::printf("VolPackRendererCheck: %dx%dx%d volume, %dx%d image\n", dims[0], dims[1], dims[2],
    Width, Height);
  std::printf("views against the brute-force reference:\n");
  CheckViews(dims, volume);
  std::printf("shading:\n");
  CheckShading(dims);
  std::printf("colour (VolPack RGB) and shaded grey against the reference:\n");
  CheckColour(dims, volume);
  std::printf("bad input:\n");
  CheckErrors(dims, volume);
  std::printf(
    "%s (%d failure%s)\n", Failures ? "FAIL" : "PASS", Failures, Failures == 1 ? "" : "s");
  return Failures ? 1 : 0;
}
