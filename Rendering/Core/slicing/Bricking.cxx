// Bricking: splitting a volume into 3D-texture bricks and ordering them for compositing.
#include "slicing/Bricking.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>

namespace accelvolume
{
namespace
{
int CeilDivide(int a, int b)
{
  return (a + b - 1) / b;
}

// Fills layout.bricks for the current cellsPerBrick; sizes and byte totals too.
void BuildBricks(const BrickRequest& request, BrickLayout& layout)
{
  const auto& dims = request.dimensions;
  for (int a = 0; a < 3; ++a)
  {
    const int cells = dims[a] - 1;
    layout.gridSize[a] = cells > 0 ? CeilDivide(cells, layout.cellsPerBrick[a]) : 1;
  }
  layout.bricks.clear();
  layout.largestBrickBytes = 0;
  layout.totalBytes = 0;
  std::array<int, 3> g{ { 0, 0, 0 } };
  for (g[2] = 0; g[2] < layout.gridSize[2]; ++g[2])
  {
    for (g[1] = 0; g[1] < layout.gridSize[1]; ++g[1])
    {
      for (g[0] = 0; g[0] < layout.gridSize[0]; ++g[0])
      {
        Brick brick;
        brick.gridIndex = g;
        for (int a = 0; a < 3; ++a)
        {
          const int cells = dims[a] - 1;
          const int per = layout.cellsPerBrick[a];
          brick.firstOnAxis[a] = g[a] == 0;
          brick.lastOnAxis[a] = g[a] == layout.gridSize[a] - 1;
          brick.pointLower[a] = cells > 0 ? g[a] * per : 0;
          brick.pointUpper[a] = cells > 0 ? std::min(cells, (g[a] + 1) * per) : 0;
          // One extra point wherever a neighbour exists: linear samples reach the next point,
          // central differences one point further back or ahead.
          const int low = std::max(0, brick.pointLower[a] - 1);
          const int high = std::min(dims[a] - 1, brick.pointUpper[a] + 1);
          brick.textureOrigin[a] = layout.gridSize[a] > 1 ? low : 0;
          brick.textureSize[a] = layout.gridSize[a] > 1 ? high - low + 1 : dims[a];
        }
        const std::uint64_t bytes = brick.TexelCount() * request.bytesPerVoxel;
        layout.largestBrickBytes = std::max(layout.largestBrickBytes, bytes);
        layout.totalBytes += bytes;
        layout.bricks.push_back(brick);
      }
    }
  }
}
}

bool ComputeBrickLayout(const BrickRequest& request, BrickLayout& layout, std::string& error)
{
  const auto& dims = request.dimensions;
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    error = "empty volume";
    return false;
  }
  if (request.maximumTextureSize < 4)
  {
    error = "the 3D texture size limit (" + std::to_string(request.maximumTextureSize) +
      ") is too small for bricks";
    return false;
  }
  // A brick's texture spans its cells + 1 points, plus one point on each side with a neighbour.
  const int widestBrickCells = request.maximumTextureSize - 3;
  for (int a = 0; a < 3; ++a)
  {
    const int cells = dims[a] - 1;
    if (dims[a] <= request.maximumTextureSize)
    {
      layout.cellsPerBrick[a] = std::max(cells, 1);
    }
    else
    {
      // The fewest bricks that fit, then cells spread evenly over them.
      const int count = CeilDivide(cells, widestBrickCells);
      layout.cellsPerBrick[a] = CeilDivide(cells, count);
    }
  }
  BuildBricks(request, layout);
  if (request.budgetBytes == 0 || layout.totalBytes <= request.budgetBytes)
  {
    return true;
  }
  // Over budget: halve the longest brick axis until a brick is a budget share (or as thin as
  // allowed), so the budget keeps BudgetShare - 1 bricks resident and streams the others.
  const std::uint64_t target = std::max<std::uint64_t>(1, request.budgetBytes / BudgetShare);
  while (layout.largestBrickBytes > target)
  {
    int longest = -1;
    for (int a = 0; a < 3; ++a)
    {
      if (layout.cellsPerBrick[a] > MinimumBrickCells &&
        (longest < 0 || layout.cellsPerBrick[a] > layout.cellsPerBrick[longest]))
      {
        longest = a;
      }
    }
    if (longest < 0)
    {
      break;
    }
    layout.cellsPerBrick[longest] =
      std::max(MinimumBrickCells, CeilDivide(layout.cellsPerBrick[longest], 2));
    BuildBricks(request, layout);
  }
  if (layout.largestBrickBytes > request.budgetBytes)
  {
    error = "the GPU memory budget (" + std::to_string(request.budgetBytes) +
      " bytes) is smaller than one brick (" + std::to_string(layout.largestBrickBytes) + " bytes)";
    return false;
  }
  return true;
}

Box BrickOwnedBox(const Brick& brick, const Box& volumeBox)
{
  Box box = volumeBox;
  double* lower[3] = { &box.lower.x, &box.lower.y, &box.lower.z };
  double* upper[3] = { &box.upper.x, &box.upper.y, &box.upper.z };
  for (int a = 0; a < 3; ++a)
  {
    if (!brick.firstOnAxis[a])
    {
      *lower[a] = brick.pointLower[a];
    }
    if (!brick.lastOnAxis[a])
    {
      *upper[a] = brick.pointUpper[a];
    }
  }
  return box;
}

std::vector<int> BrickVisibilityOrder(
  const BrickLayout& layout, bool perspective, const Vec3& eye, const Vec3& direction)
{
  const double eyeAt[3] = { eye.x, eye.y, eye.z };
  const double along[3] = { direction.x, direction.y, direction.z };
  std::vector<int> distance(layout.bricks.size(), 0);
  for (size_t b = 0; b < layout.bricks.size(); ++b)
  {
    const Brick& brick = layout.bricks[b];
    for (int a = 0; a < 3; ++a)
    {
      const int count = layout.gridSize[a];
      const int i = brick.gridIndex[a];
      if (count == 1)
      {
        continue;
      }
      if (perspective)
      {
        // The brick row holding the eye (clamped: an eye outside sees the nearest row first).
        const double cell = std::floor(eyeAt[a] / layout.cellsPerBrick[a]);
        const int eyeRow = static_cast<int>(std::min<double>(count - 1, std::max(0.0, cell)));
        distance[b] += std::abs(i - eyeRow);
      }
      else if (along[a] > 0)
      {
        distance[b] += i;
      }
      else if (along[a] < 0)
      {
        distance[b] += count - 1 - i;
      }
    }
  }
  std::vector<int> order(layout.bricks.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&distance](int a, int b) { return distance[a] < distance[b]; });
  return order;
}
}
