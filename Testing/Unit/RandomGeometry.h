// Random points, directions and boxes shared by the Core geometry tests (seeded generators).
#ifndef accelvolume_test_RandomGeometry_h
#define accelvolume_test_RandomGeometry_h

#include "common/Geometry.h"

#include <random>

namespace accelvolume_test
{
inline double Uniform(std::mt19937& random, double low, double high)
{
  return std::uniform_real_distribution<double>(low, high)(random);
}

inline accelvolume::Vec3 RandomPoint(std::mt19937& random, const accelvolume::Box& box)
{
  return { Uniform(random, box.lower.x, box.upper.x), Uniform(random, box.lower.y, box.upper.y),
    Uniform(random, box.lower.z, box.upper.z) };
}

inline accelvolume::Vec3 RandomUnit(std::mt19937& random)
{
  std::normal_distribution<double> normal;
  return accelvolume::Normalize({ normal(random), normal(random), normal(random) });
}

// Lower corner in [-5, 5]^3, sides in [0.2, 4].
inline accelvolume::Box RandomBox(std::mt19937& random)
{
  const accelvolume::Vec3 lower{ Uniform(random, -5, 5), Uniform(random, -5, 5),
    Uniform(random, -5, 5) };
  return { lower,
    lower +
      accelvolume::Vec3{
        Uniform(random, 0.2, 4), Uniform(random, 0.2, 4), Uniform(random, 0.2, 4) } };
}
}

#endif
