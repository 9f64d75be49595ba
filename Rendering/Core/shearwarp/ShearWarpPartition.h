// ShearWarpPartition: splits the intermediate image's scanlines into contiguous bands of nearly
// equal cost (the paper's sheared-space partition with load balancing; plain C++).
#ifndef accelvolume_ShearWarpPartition_h
#define accelvolume_ShearWarpPartition_h

#include <vector>

namespace accelvolume
{

// parts + 1 increasing boundaries from 0 to cost.size(): band b is [bounds[b], bounds[b + 1]).
// Boundary b sits where the running cost comes closest to b / parts of the total, so no band
// exceeds its share by more than one scanline's cost; negative or NaN costs count as zero, and
// all-zero costs give equal bands. Bands may be empty when there are fewer scanlines than parts.
std::vector<int> BalanceBands(const std::vector<double>& cost, int parts);

// parts + 1 boundaries splitting `count` scanlines into bands of equal size (no balancing).
std::vector<int> EqualBands(int count, int parts);

// Cost per scanline resampled to a new scanline count (the view changed the intermediate
// image's height); total cost is preserved.
std::vector<double> ResampleCosts(const std::vector<double>& cost, int count);

// Largest band cost over the mean band cost (1 = perfect balance; 1 when all are zero).
double Imbalance(const std::vector<double>& bandCost);

}

#endif
