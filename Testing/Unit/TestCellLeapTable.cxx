// Tests of the modified Marching Cubes table (CellLeapTable) against VTK's own Marching Cubes
// triangle table and brute-force trilinear interpolation.
#include "skipping/CellLeapTable.h"

#include "vtkHexahedron.h"                 // For the edges of VTK's triangle table
#include "vtkMarchingCubesTriangleCases.h" // For the standard triangle table

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

namespace
{
using accelvolume::CellEdgeCorners;
using accelvolume::CellLeapBox;
using accelvolume::CellLeapCase;
using accelvolume::CellLeapSampleIsTransparent;
using accelvolume::GetCellLeapTable;
using accelvolume::MarchingCubesCase;

constexpr int Configurations = 256;
// Our corner c (x fastest) as VTK's hexahedron corner (bottom face walked round): the map is
// its own inverse.
constexpr int VtkCorner[8] = { 0, 1, 3, 2, 4, 5, 7, 6 };
// Box bounds are floats computed in double: this covers their rounding.
constexpr double BoxTolerance = 1e-5;

bool Opaque(int configuration, int corner)
{
  return ((configuration >> corner) & 1) != 0;
}

int OpaqueCount(int configuration)
{
  int count = 0;
  for (int c = 0; c < 8; ++c)
  {
    count += Opaque(configuration, c) ? 1 : 0;
  }
  return count;
}

double Coordinate(int corner, int axis)
{
  return (corner >> axis) & 1;
}

double Trilinear(const std::array<float, 8>& v, const double f[3])
{
  double result = 0;
  for (int c = 0; c < 8; ++c)
  {
    double weight = 1;
    for (int a = 0; a < 3; ++a)
    {
      weight *= Coordinate(c, a) > 0 ? f[a] : 1 - f[a];
    }
    result += weight * v[c];
  }
  return result;
}

struct ValueSet
{
  std::array<float, 8> values;
  float threshold;
};

// Corner values consistent with the configuration (opaque >= threshold > transparent): binary
// values at three thresholds, uniform values, values just around the threshold (opaque ones
// exactly on it), and integer values like unsigned char volumes.
std::vector<ValueSet> ValueSets(int configuration, std::mt19937& random)
{
  std::vector<ValueSet> sets;
  for (float threshold : { 0.25f, 0.5f, 0.75f })
  {
    ValueSet set{ {}, threshold };
    for (int c = 0; c < 8; ++c)
    {
      set.values[c] = Opaque(configuration, c) ? 1.0f : 0.0f;
    }
    sets.push_back(set);
  }
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> opaqueByte(100, 255), transparentByte(0, 99);
  for (int repeat = 0; repeat < 3; ++repeat)
  {
    ValueSet uniform{ {}, 0.4f }, nearThreshold{ {}, 0.5f }, bytes{ {}, 100.0f };
    for (int c = 0; c < 8; ++c)
    {
      const bool opaque = Opaque(configuration, c);
      uniform.values[c] = opaque ? 0.4f + unit(random) : 0.4f - 0.001f - unit(random) * 0.399f;
      const float offset = 1e-3f * unit(random);
      nearThreshold.values[c] =
        opaque ? (unit(random) < 0.5f ? 0.5f : 0.5f + offset) : 0.5f - 1e-4f - offset;
      bytes.values[c] = static_cast<float>(opaque ? opaqueByte(random) : transparentByte(random));
    }
    sets.push_back(uniform);
    sets.push_back(nearThreshold);
    sets.push_back(bytes);
  }
  return sets;
}

// Sample points: a 17^3 grid (includes the faces) plus random points.
std::vector<std::array<float, 3>> SamplePoints()
{
  constexpr int GridPoints = 17;
  constexpr int RandomPoints = 500;
  std::vector<std::array<float, 3>> points;
  for (int k = 0; k < GridPoints; ++k)
  {
    for (int j = 0; j < GridPoints; ++j)
    {
      for (int i = 0; i < GridPoints; ++i)
      {
        points.push_back({ i / 16.0f, j / 16.0f, k / 16.0f });
      }
    }
  }
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int n = 0; n < RandomPoints; ++n)
  {
    points.push_back({ unit(random), unit(random), unit(random) });
  }
  return points;
}

// Our edge id of VTK hexahedron edge e (whose corners VTK lists in its own numbering).
int OurEdge(int vtkEdge)
{
  const vtkIdType* corners = vtkHexahedron::GetEdgeArray(vtkEdge);
  const int a = VtkCorner[corners[0]], b = VtkCorner[corners[1]];
  for (int e = 0; e < 12; ++e)
  {
    int low, high;
    CellEdgeCorners(e, low, high);
    if ((low == a && high == b) || (low == b && high == a))
    {
      return e;
    }
  }
  return -1;
}

int VtkIndex(int configuration)
{
  int index = 0;
  for (int c = 0; c < 8; ++c)
  {
    index |= Opaque(configuration, c) ? 1 << VtkCorner[c] : 0;
  }
  return index;
}

// Our edges on which VTK's triangle table puts a vertex for this configuration.
std::set<int> TriangleEdges(int configuration)
{
  std::set<int> edges;
  const int* list = vtkMarchingCubesTriangleCases::GetCases()[VtkIndex(configuration)].edges;
  for (int i = 0; list[i] >= 0; ++i)
  {
    edges.insert(OurEdge(list[i]));
  }
  return edges;
}

bool IsCrossing(int configuration, int edge)
{
  int low, high;
  CellEdgeCorners(edge, low, high);
  return Opaque(configuration, low) != Opaque(configuration, high);
}
}

TEST(CellLeapTable, EdgeCornersFollowTheNumbering)
{
  const int expected[12][2] = { { 0, 1 }, { 2, 3 }, { 4, 5 }, { 6, 7 }, { 0, 2 }, { 1, 3 },
    { 4, 6 }, { 5, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
  for (int e = 0; e < 12; ++e)
  {
    int low, high;
    CellEdgeCorners(e, low, high);
    EXPECT_EQ(low, expected[e][0]) << "edge " << e;
    EXPECT_EQ(high, expected[e][1]) << "edge " << e;
    EXPECT_EQ(high, low | (1 << (e / 4))) << "edge " << e << " runs along axis e / 4";
  }
  int low = 0, high = 0;
  CellEdgeCorners(12, low, high);
  EXPECT_EQ(low, -1);
  EXPECT_EQ(high, -1);
}

TEST(CellLeapTable, VtkTrianglesUseExactlyTheCrossingEdges)
{
  // Checks the corner and edge mapping to VTK: a wrong map would pick other edges.
  for (int e = 0; e < 12; ++e)
  {
    ASSERT_GE(OurEdge(e), 0) << "VTK edge " << e;
  }
  for (int configuration = 0; configuration < Configurations; ++configuration)
  {
    std::set<int> crossing;
    for (int e = 0; e < 12; ++e)
    {
      if (IsCrossing(configuration, e))
      {
        crossing.insert(e);
      }
    }
    EXPECT_EQ(TriangleEdges(configuration), crossing) << "configuration " << configuration;
  }
}

TEST(CellLeapTable, MarchingCubesClasses)
{
  const int expectedSizes[15] = { 2, 16, 24, 24, 8, 48, 48, 16, 6, 8, 6, 12, 24, 2, 12 };
  int sizes[15] = {};
  for (int configuration = 0; configuration < Configurations; ++configuration)
  {
    const int mc = MarchingCubesCase(configuration);
    ASSERT_GE(mc, 0);
    ASSERT_LT(mc, 15);
    ++sizes[mc];
    EXPECT_EQ(mc, MarchingCubesCase(255 & ~configuration)) << "complement of " << configuration;
    // Quarter turn about z: (x, y) -> (1 - y, x); built here independently of the table.
    int turned = 0, mirrored = 0;
    for (int c = 0; c < 8; ++c)
    {
      if (Opaque(configuration, c))
      {
        const int x = c & 1, y = (c >> 1) & 1;
        turned |= 1 << ((1 - y) | (x << 1) | (c & 4));
        mirrored |= 1 << (c ^ 1);
      }
    }
    EXPECT_EQ(mc, MarchingCubesCase(turned)) << "rotation of " << configuration;
    // A mirror swaps the two zig-zag cases and keeps every other case.
    const int mirror = mc == 11 ? 14 : (mc == 14 ? 11 : mc);
    EXPECT_EQ(mirror, MarchingCubesCase(mirrored)) << "mirror of " << configuration;
  }
  for (int c = 0; c < 15; ++c)
  {
    EXPECT_EQ(sizes[c], expectedSizes[c]) << "case " << c;
  }
  // Representatives named in docs/cell-leaping.md: {configuration, case}.
  const int representatives[][2] = { { 0x01, 1 }, { 0x09, 3 }, { 0x83, 6 }, { 0x16, 7 },
    { 0x17, 9 }, { 0xC3, 10 }, { 0x8B, 11 }, { 0x69, 13 }, { 0x47, 14 } };
  for (const auto& representative : representatives)
  {
    EXPECT_EQ(MarchingCubesCase(representative[0]), representative[1]);
  }
  EXPECT_EQ(MarchingCubesCase(256), -1);
}

TEST(CellLeapTable, LeapableCasesAndCosts)
{
  const auto& table = GetCellLeapTable();
  // Derivation: an axis is usable unless a parallel edge is fully opaque. With 5+ opaque
  // corners some edge of every axis is (4 edges per axis), and cases 9, 11 and 14 have a fully
  // opaque edge along each axis; everything else with <= 4 opaque corners is leapable.
  const int expectedLeapable[15] = { 1, 8, 12, 12, 4, 24, 24, 8, 6, 0, 6, 0, 24, 2, 0 };
  const int expectedCost[15] = { 0, 3, 4, 6, 6, 3, 6, 6, 4, -1, 4, -1, 4, 4, -1 };
  int leapable[15] = {};
  for (int configuration = 0; configuration < Configurations; ++configuration)
  {
    const CellLeapCase& entry = table[configuration];
    const int mc = entry.marchingCubesCase;
    const bool excluded = OpaqueCount(configuration) > 4 || mc == 9 || mc == 11 || mc == 14;
    EXPECT_EQ(entry.leapCase, excluded ? -1 : mc) << "configuration " << configuration;
    if (entry.leapCase < 0)
    {
      continue;
    }
    ++leapable[mc];
    EXPECT_EQ(entry.cost, expectedCost[mc]) << "configuration " << configuration;
    EXPECT_LE(entry.cost, accelvolume::TrilinearLerps);
    EXPECT_EQ(entry.axisCount == 0, configuration == 0);

    // Independent oracle of the usable axes: no fully opaque parallel edge, >= 1 crossing.
    std::vector<std::pair<int, int>> usable; // (crossings, axis)
    for (int axis = 0; axis < 3; ++axis)
    {
      int crossings = 0;
      bool full = false;
      for (int e = axis * 4; e < axis * 4 + 4; ++e)
      {
        int low, high;
        CellEdgeCorners(e, low, high);
        crossings += IsCrossing(configuration, e) ? 1 : 0;
        full = full || (Opaque(configuration, low) && Opaque(configuration, high));
      }
      if (!full && crossings > 0)
      {
        usable.emplace_back(crossings, axis);
      }
    }
    std::sort(usable.begin(), usable.end());
    int cost = 0;
    ASSERT_LE(entry.axisCount, usable.size());
    for (int a = 0; a < entry.axisCount; ++a)
    {
      const auto& axis = entry.axes[a];
      EXPECT_EQ(axis.axis, usable[a].second) << "configuration " << configuration;
      EXPECT_EQ(axis.count, usable[a].first) << "configuration " << configuration;
      cost += axis.count;
      for (int i = 0; i < axis.count; ++i)
      {
        EXPECT_EQ(axis.highCorner[i], axis.lowCorner[i] | (1 << axis.axis));
        EXPECT_NE(
          Opaque(configuration, axis.lowCorner[i]), Opaque(configuration, axis.highCorner[i]));
      }
    }
    EXPECT_EQ(cost, entry.cost);
    if (entry.axisCount < usable.size()) // the next axis must not have fitted
    {
      EXPECT_GT(cost + usable[entry.axisCount].first, accelvolume::TrilinearLerps);
    }
  }
  std::printf("MC case: leapable configurations / all, cost (lerps)\n");
  for (int c = 0; c < 15; ++c)
  {
    int all = 0;
    for (int configuration = 0; configuration < Configurations; ++configuration)
    {
      all += table[configuration].marchingCubesCase == c ? 1 : 0;
    }
    std::printf("  case %2d: %2d / %2d, cost %d\n", c, leapable[c], all, expectedCost[c]);
    EXPECT_EQ(leapable[c], expectedLeapable[c]) << "case " << c;
  }
  EXPECT_EQ(table[0].leapCase, 0);
  EXPECT_EQ(table[255].leapCase, -1);
}

TEST(CellLeapTable, PaperEdgeField)
{
  for (int configuration = 0; configuration < Configurations; ++configuration)
  {
    const CellLeapCase& entry = GetCellLeapTable()[configuration];
    for (int axis = 0; axis < 3; ++axis)
    {
      bool lowSide = false, highSide = false;
      for (int e = axis * 4; e < axis * 4 + 4; ++e)
      {
        int low, high;
        CellEdgeCorners(e, low, high);
        lowSide = lowSide || Opaque(configuration, low);
        highSide = highSide || Opaque(configuration, high);
      }
      std::set<int> directions;
      for (int e = axis * 4; e < axis * 4 + 4; ++e)
      {
        const auto& field = entry.edges[e];
        const bool expectStored = IsCrossing(configuration, e) && !(lowSide && highSide);
        ASSERT_EQ(field.lowCorner >= 0, expectStored) << "configuration " << configuration;
        if (expectStored)
        {
          int low, high;
          CellEdgeCorners(e, low, high);
          EXPECT_EQ(field.lowCorner, low);
          EXPECT_EQ(field.highCorner, high);
          EXPECT_EQ(field.direction, Opaque(configuration, low) ? 0 : 1);
          directions.insert(field.direction);
        }
      }
      EXPECT_LE(directions.size(), 1u) << "one direction per axis, " << configuration;
    }
  }
}

TEST(CellLeapTable, BoxIsTheMarchingCubesSolidBoundingBox)
{
  std::mt19937 random(1);
  int compared = 0;
  for (int configuration = 0; configuration < Configurations; ++configuration)
  {
    const CellLeapCase& entry = GetCellLeapTable()[configuration];
    for (const ValueSet& set : ValueSets(configuration, random))
    {
      // Brute force: opaque corners plus the vertices of VTK's triangles.
      double lower[3] = { 2, 2, 2 }, upper[3] = { -1, -1, -1 };
      const auto add = [&](const double p[3])
      {
        for (int a = 0; a < 3; ++a)
        {
          lower[a] = std::min(lower[a], p[a]);
          upper[a] = std::max(upper[a], p[a]);
        }
      };
      for (int c = 0; c < 8; ++c)
      {
        if (Opaque(configuration, c))
        {
          const double p[3] = { Coordinate(c, 0), Coordinate(c, 1), Coordinate(c, 2) };
          add(p);
        }
      }
      for (int e : TriangleEdges(configuration))
      {
        int a, b;
        CellEdgeCorners(e, a, b);
        const double s =
          (set.threshold - double(set.values[a])) / (double(set.values[b]) - double(set.values[a]));
        double p[3];
        for (int axis = 0; axis < 3; ++axis)
        {
          p[axis] = Coordinate(a, axis) + s * (Coordinate(b, axis) - Coordinate(a, axis));
        }
        add(p);
      }
      float boxLower[3], boxUpper[3];
      CellLeapBox(entry, set.values.data(), set.threshold, boxLower, boxUpper);
      for (int a = 0; a < 3; ++a)
      {
        if (configuration == 0)
        {
          EXPECT_GT(boxLower[a], boxUpper[a]) << "configuration 0 has an empty box";
          continue;
        }
        EXPECT_NEAR(boxLower[a], lower[a], BoxTolerance) << "configuration " << configuration;
        EXPECT_NEAR(boxUpper[a], upper[a], BoxTolerance) << "configuration " << configuration;
      }
      ++compared;
    }
  }
  std::printf("compared %d boxes with VTK's Marching Cubes solid\n", compared);
}

TEST(CellLeapTable, DenseSamplingIsConservativeAndLeaps)
{
  std::mt19937 random(2);
  const std::vector<std::array<float, 3>> points = SamplePoints();
  long long samples = 0, transparent = 0, certified = 0, certifiedLeapable = 0;
  long long transparentLeapable = 0, outsideBoxMissed = 0;
  for (int configuration = 0; configuration < Configurations; ++configuration)
  {
    const CellLeapCase& entry = GetCellLeapTable()[configuration];
    long long configurationCertified = 0;
    for (const ValueSet& set : ValueSets(configuration, random))
    {
      float lower[3], upper[3];
      CellLeapBox(entry, set.values.data(), set.threshold, lower, upper);
      const auto corner = [&set](int c) { return set.values[c]; };
      for (const auto& point : points)
      {
        const double f[3] = { point[0], point[1], point[2] };
        const double value = Trilinear(set.values, f);
        const bool opaque = value >= set.threshold;
        const bool leap = CellLeapSampleIsTransparent(entry, point.data(), set.threshold, corner);
        ++samples;
        transparent += opaque ? 0 : 1;
        certified += leap ? 1 : 0;
        if (opaque)
        {
          for (int a = 0; a < 3; ++a)
          {
            ASSERT_GE(f[a], lower[a] - 1e-6) << "configuration " << configuration;
            ASSERT_LE(f[a], upper[a] + 1e-6) << "configuration " << configuration;
          }
        }
        if (leap)
        {
          ASSERT_LT(value, set.threshold) << "configuration " << configuration << " at (" << f[0]
                                          << ", " << f[1] << ", " << f[2] << ")";
        }
        if (entry.leapCase >= 0)
        {
          transparentLeapable += opaque ? 0 : 1;
          certifiedLeapable += leap ? 1 : 0;
          configurationCertified += leap ? 1 : 0;
          // Outside the box (clearly) on a tested axis: the exact test must leap too.
          for (int a = 0; a < entry.axisCount && !leap; ++a)
          {
            const int axis = entry.axes[a].axis;
            if (f[axis] < lower[axis] - 1e-4 || f[axis] > upper[axis] + 1e-4)
            {
              ++outsideBoxMissed;
            }
          }
        }
      }
    }
    if (entry.leapCase >= 0)
    {
      EXPECT_GT(configurationCertified, 0) << "configuration " << configuration;
    }
  }
  std::printf("%lld samples, %lld transparent, %lld leaped; leapable configurations: %lld of "
              "%lld transparent samples leaped\n",
    samples, transparent, certified, certifiedLeapable, transparentLeapable);
  EXPECT_EQ(outsideBoxMissed, 0);
  EXPECT_GT(certifiedLeapable, transparentLeapable / 3);
}

TEST(CellLeapTable, FaceDiagonalComponentsNeedOneBox)
{
  // docs/cell-leaping.md: corners 0 and 3 at 1, the rest at 0, threshold 0.4. Boxes around
  // each Marching Cubes component would be [0, 0.6]^3 and [0.4, 1]^2 x [0, 0.6], but the
  // bilinear face joins the components: (0.7, 0.35, 0) is opaque and outside both.
  std::array<float, 8> values = { 1, 0, 0, 1, 0, 0, 0, 0 };
  const double p[3] = { 0.7, 0.35, 0 };
  EXPECT_NEAR(Trilinear(values, p), 0.44, 1e-12);
  const CellLeapCase& entry = GetCellLeapTable()[0x09];
  float lower[3], upper[3];
  CellLeapBox(entry, values.data(), 0.4f, lower, upper);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_LE(lower[a], p[a]);
    EXPECT_GE(upper[a], p[a]);
  }
  const float f[3] = { 0.7f, 0.35f, 0.0f };
  EXPECT_FALSE(CellLeapSampleIsTransparent(entry, f, 0.4f, [&values](int c) { return values[c]; }));
}
