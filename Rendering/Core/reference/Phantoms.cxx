// Phantoms: procedural test volumes built from closed-form functions and hash-based noise.
#include "Phantoms.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <new>

namespace accelvolume
{
namespace
{

constexpr double TwoPi = 6.283185307179586;
constexpr double MaximumValue = 1000.0;
constexpr std::int64_t MaximumVoxels = std::int64_t(1) << 31;

// Normalized coordinate of voxel centers, so shapes keep their place at any resolution.
std::vector<double> AxisCoordinates(int size)
{
  std::vector<double> coordinates(size);
  for (int i = 0; i < size; ++i)
  {
    coordinates[i] = (i + 0.5) / size;
  }
  return coordinates;
}

// Integer hash (lowbias32 finalizer): stateless, so output never depends on call order or threads.
std::uint32_t Mix(std::uint32_t h)
{
  h ^= h >> 16;
  h *= 0x7feb352dU;
  h ^= h >> 15;
  h *= 0x846ca68bU;
  h ^= h >> 16;
  return h;
}

double LatticeValue(int x, int y, int z, std::uint32_t seed)
{
  std::uint32_t h = Mix(seed + static_cast<std::uint32_t>(x));
  h = Mix(h + static_cast<std::uint32_t>(y));
  h = Mix(h + static_cast<std::uint32_t>(z));
  return h / 4294967296.0;
}

// Smoothly interpolated lattice noise in [0, 1).
double ValueNoise(double x, double y, double z, std::uint32_t seed)
{
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int ix = static_cast<int>(fx), iy = static_cast<int>(fy), iz = static_cast<int>(fz);
  auto smooth = [](double t) { return t * t * (3 - 2 * t); };
  const double tx = smooth(x - fx), ty = smooth(y - fy), tz = smooth(z - fz);
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  double layers[2];
  for (int dz = 0; dz < 2; ++dz)
  {
    const double v00 = LatticeValue(ix, iy, iz + dz, seed);
    const double v10 = LatticeValue(ix + 1, iy, iz + dz, seed);
    const double v01 = LatticeValue(ix, iy + 1, iz + dz, seed);
    const double v11 = LatticeValue(ix + 1, iy + 1, iz + dz, seed);
    layers[dz] = lerp(lerp(v00, v10, tx), lerp(v01, v11, tx), ty);
  }
  return lerp(layers[0], layers[1], tz);
}

double Clamp(double value)
{
  return std::min(MaximumValue, std::max(0.0, value));
}

using VoxelFunction = std::function<double(int i, int j, int k)>;

void Fill(const int dims[3], const VoxelFunction& function, std::vector<float>& values)
{
  std::size_t index = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        values[index++] = static_cast<float>(Clamp(function(i, j, k)));
      }
    }
  }
}

// A tube running along one axis whose center wanders sinusoidally in the other two.
struct Tube
{
  int axis;
  double center[2];
  double amplitude[2];
  double frequency;
  double phase;
  double sigma;
  double peak;
};

void FillVessels(const int dims[3], double time, std::vector<float>& values)
{
  static const Tube tubes[] = {
    { 2, { 0.35, 0.45 }, { 0.12, 0.08 }, 1.0, 0.0, 0.025, 900 },
    { 2, { 0.65, 0.60 }, { 0.08, 0.12 }, 0.75, 0.3, 0.018, 750 },
    { 0, { 0.30, 0.65 }, { 0.10, 0.10 }, 1.25, 0.55, 0.015, 600 },
    { 1, { 0.50, 0.30 }, { 0.15, 0.06 }, 0.5, 0.8, 0.03, 850 },
  };
  std::vector<double> coordinates[3] = { AxisCoordinates(dims[0]), AxisCoordinates(dims[1]),
    AxisCoordinates(dims[2]) };
  // Tube centers depend on one coordinate only, so precompute them per position along the axis.
  struct TubeTable
  {
    std::vector<double> first, second;
    double peak, inverseTwoSigmaSquared;
  };
  std::vector<TubeTable> tables;
  for (const Tube& tube : tubes)
  {
    TubeTable table;
    const double angle = TwoPi * (tube.phase + time);
    for (double s : coordinates[tube.axis])
    {
      table.first.push_back(
        tube.center[0] + tube.amplitude[0] * std::sin(TwoPi * tube.frequency * s + angle));
      table.second.push_back(
        tube.center[1] + tube.amplitude[1] * std::cos(TwoPi * 0.7 * tube.frequency * s + angle));
    }
    table.peak = tube.peak * (0.9 + 0.1 * std::cos(angle));
    table.inverseTwoSigmaSquared = 1.0 / (2 * tube.sigma * tube.sigma);
    tables.push_back(std::move(table));
  }
  Fill(
    dims,
    [&](int i, int j, int k)
    {
      const double position[3] = { coordinates[0][i], coordinates[1][j], coordinates[2][k] };
      const int index[3] = { i, j, k };
      // Two octaves of noise give a background that looks like tissue texture but is fixed.
      double value = 40 +
        60 *
          (0.65 * ValueNoise(position[0] * 8, position[1] * 8, position[2] * 8, 17) +
            0.35 * ValueNoise(position[0] * 24, position[1] * 24, position[2] * 24, 91));
      for (std::size_t t = 0; t < tables.size(); ++t)
      {
        const int axis = tubes[t].axis;
        const int along = index[axis];
        const double da = position[(axis + 1) % 3] - tables[t].first[along];
        const double db = position[(axis + 2) % 3] - tables[t].second[along];
        value += tables[t].peak * std::exp(-(da * da + db * db) * tables[t].inverseTwoSigmaSquared);
      }
      return value;
    },
    values);
}

void FillShells(const int dims[3], double time, std::vector<float>& values)
{
  struct Shell
  {
    double radius, width, peak;
  };
  static const Shell shells[] = { { 0.42, 0.02, 400 }, { 0.30, 0.02, 700 }, { 0.16, 0.025, 1000 } };
  std::vector<double> coordinates[3] = { AxisCoordinates(dims[0]), AxisCoordinates(dims[1]),
    AxisCoordinates(dims[2]) };
  double radii[3];
  for (int s = 0; s < 3; ++s)
  {
    radii[s] = shells[s].radius * (1 + 0.06 * std::sin(TwoPi * time + s));
  }
  Fill(
    dims,
    [&](int i, int j, int k)
    {
      const double dx = coordinates[0][i] - 0.5, dy = coordinates[1][j] - 0.5,
                   dz = coordinates[2][k] - 0.5;
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      double value = 0;
      for (int s = 0; s < 3; ++s)
      {
        const double d = (r - radii[s]) / shells[s].width;
        value += shells[s].peak * std::exp(-0.5 * d * d);
      }
      return value;
    },
    values);
}

void FillBlobs(const int dims[3], double time, std::vector<float>& values)
{
  struct Blob
  {
    double center[3], sigma, peak, orbit, phase;
  };
  static const Blob blobs[] = {
    { { 0.30, 0.30, 0.30 }, 0.08, 1000, 0.05, 0.0 },
    { { 0.70, 0.35, 0.40 }, 0.12, 600, 0.04, 0.2 },
    { { 0.45, 0.70, 0.60 }, 0.05, 900, 0.06, 0.4 },
    { { 0.70, 0.70, 0.75 }, 0.09, 450, 0.03, 0.6 },
    { { 0.25, 0.60, 0.80 }, 0.04, 800, 0.05, 0.8 },
    { { 0.55, 0.45, 0.20 }, 0.15, 300, 0.02, 0.1 },
  };
  std::vector<double> coordinates[3] = { AxisCoordinates(dims[0]), AxisCoordinates(dims[1]),
    AxisCoordinates(dims[2]) };
  double centers[6][3];
  for (int b = 0; b < 6; ++b)
  {
    const double angle = TwoPi * (time + blobs[b].phase);
    centers[b][0] = blobs[b].center[0] + blobs[b].orbit * std::cos(angle);
    centers[b][1] = blobs[b].center[1] + blobs[b].orbit * std::sin(angle);
    centers[b][2] = blobs[b].center[2];
  }
  Fill(
    dims,
    [&](int i, int j, int k)
    {
      double value = 0;
      for (int b = 0; b < 6; ++b)
      {
        const double dx = coordinates[0][i] - centers[b][0], dy = coordinates[1][j] - centers[b][1],
                     dz = coordinates[2][k] - centers[b][2];
        const double s = blobs[b].sigma;
        value += blobs[b].peak * std::exp(-(dx * dx + dy * dy + dz * dz) / (2 * s * s));
      }
      return value;
    },
    values);
}

// Analytic phantoms only pulse in brightness, so their shape stays exactly predictable.
double Pulse(double time)
{
  return 0.75 + 0.25 * std::cos(TwoPi * time);
}

void FillRamp(const int dims[3], double time, std::vector<float>& values)
{
  const double scale = dims[0] > 1 ? MaximumValue * Pulse(time) / (dims[0] - 1) : 0.0;
  Fill(
    dims, [&](int i, int, int) { return i * scale; }, values);
}

void FillBox(const int dims[3], double time, std::vector<float>& values)
{
  const double value = MaximumValue * Pulse(time);
  Fill(
    dims,
    [&](int i, int j, int k)
    {
      const int index[3] = { i, j, k };
      for (int axis = 0; axis < 3; ++axis)
      {
        if (index[axis] < dims[axis] / 4 || index[axis] >= dims[axis] - dims[axis] / 4)
        {
          return 0.0;
        }
      }
      return value;
    },
    values);
}

using PhantomFunction = void (*)(const int dims[3], double time, std::vector<float>& values);

struct PhantomEntry
{
  const char* name;
  PhantomFunction function;
};

const PhantomEntry Entries[] = {
  { "vessels", FillVessels },
  { "shells", FillShells },
  { "blobs", FillBlobs },
  { "ramp", FillRamp },
  { "box", FillBox },
};

} // namespace

std::vector<std::string> PhantomNames()
{
  std::vector<std::string> names;
  for (const PhantomEntry& entry : Entries)
  {
    names.emplace_back(entry.name);
  }
  return names;
}

bool GeneratePhantom(
  const std::string& name, const int dims[3], double time, PhantomVolume& out, std::string& error)
{
  PhantomFunction function = nullptr;
  for (const PhantomEntry& entry : Entries)
  {
    if (name == entry.name)
    {
      function = entry.function;
    }
  }
  if (!function)
  {
    error = "unknown phantom '" + name + "' (expected one of:";
    for (const PhantomEntry& entry : Entries)
    {
      error += std::string(" ") + entry.name;
    }
    error += ")";
    return false;
  }
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    error = "phantom dimensions must be at least 1, got " + std::to_string(dims[0]) + "x" +
      std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
    return false;
  }
  // Each dimension is below 2^31, so two products cannot overflow 64 bits before the check.
  const std::int64_t voxels = std::int64_t(dims[0]) * dims[1];
  if (voxels > MaximumVoxels || voxels * dims[2] > MaximumVoxels)
  {
    error = "phantom " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
      std::to_string(dims[2]) + " has more than 2^31 voxels";
    return false;
  }
  if (!std::isfinite(time))
  {
    error = "phantom time must be a finite number";
    return false;
  }
  PhantomVolume result;
  try
  {
    result.values.resize(static_cast<std::size_t>(voxels * dims[2]));
  }
  catch (const std::bad_alloc&)
  {
    error = "not enough memory for a " + std::to_string(voxels * dims[2]) + "-voxel phantom";
    return false;
  }
  std::copy(dims, dims + 3, result.dims);
  function(dims, time, result.values);
  out = std::move(result);
  return true;
}

} // namespace accelvolume
