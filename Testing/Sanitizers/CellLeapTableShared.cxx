// The cell-leap table built inside a shared library with default visibility (every Core
// function exported, calls between them through the PLT), as Core once was inside the module.
// GCC 12's -O1 -fPIC -fsanitize=thread build of that layout built a wrong table (configuration
// 1 without a usable axis, among 111 wrong entries) when BuildCase called the exported
// CellEdgeCorners: TestAccelVolumeRayCastExact's "NaN voxels" case then leaped samples it must
// not. CellLeapTable.cxx now builds the table with an internal function; this test checks that
// table against a brute-force count of each configuration's crossing edges.
#include "skipping/CellLeapTable.h"

#include <cstdio>
#include <cstdlib>

int main()
{
  const auto& table = accelvolume::GetCellLeapTable();
  int wrong = 0;
  for (int configuration = 0; configuration < 256; ++configuration)
  {
    const accelvolume::CellLeapCase& entry = table[configuration];
    int crossings[3] = { 0, 0, 0 };
    bool fullEdge[3] = { false, false, false };
    for (int edge = 0; edge < 12; ++edge)
    {
      int low = 0, high = 0;
      accelvolume::CellEdgeCorners(edge, low, high);
      const bool a = (configuration >> low) & 1, b = (configuration >> high) & 1;
      crossings[edge / 4] += a != b;
      fullEdge[edge / 4] = fullEdge[edge / 4] || (a && b);
    }
    int usable = 0;
    for (int axis = 0; axis < 3; ++axis)
    {
      usable += !fullEdge[axis] && crossings[axis] > 0;
    }
    bool ok = entry.axisCount <= usable;
    for (int a = 0; a < entry.axisCount && ok; ++a)
    {
      ok = entry.axes[a].count == crossings[entry.axes[a].axis] && !fullEdge[entry.axes[a].axis];
    }
    // One opaque or one transparent corner: three usable axes of one crossing each.
    const int corners = __builtin_popcount(configuration);
    if ((corners == 1) && entry.axisCount != 3)
    {
      ok = false;
    }
    if (!ok && ++wrong <= 5)
    {
      std::printf("configuration %d: %d axes, %d usable\n", configuration, entry.axisCount, usable);
    }
  }
  std::printf("%d wrong table entries\n", wrong);
  return wrong == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
