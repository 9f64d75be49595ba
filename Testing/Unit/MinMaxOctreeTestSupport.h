// Helpers shared by the min-max octree tests (TestMinMaxOctreeBuild, TestMinMaxOctreeQueries).
#ifndef accelvolume_test_MinMaxOctreeTestSupport_h
#define accelvolume_test_MinMaxOctreeTestSupport_h

#include "skipping/MinMaxOctree.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <random>
#include <thread>
#include <utility>
#include <vector>

namespace accelvolume_test
{
using accelvolume::ParallelFor;
using accelvolume::ScalarType;
using accelvolume::VolumeView;

template <typename T>
struct Scalar;
template <>
struct Scalar<std::int8_t>
{
  static constexpr ScalarType Type = ScalarType::Int8;
};
template <>
struct Scalar<std::uint8_t>
{
  static constexpr ScalarType Type = ScalarType::UInt8;
};
template <>
struct Scalar<std::int16_t>
{
  static constexpr ScalarType Type = ScalarType::Int16;
};
template <>
struct Scalar<std::uint16_t>
{
  static constexpr ScalarType Type = ScalarType::UInt16;
};
template <>
struct Scalar<std::int32_t>
{
  static constexpr ScalarType Type = ScalarType::Int32;
};
template <>
struct Scalar<float>
{
  static constexpr ScalarType Type = ScalarType::Float32;
};
template <>
struct Scalar<double>
{
  static constexpr ScalarType Type = ScalarType::Float64;
};

inline std::size_t VoxelCount(const int dims[3])
{
  return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
}

template <typename T>
inline VolumeView View(const std::vector<T>& volume, const int dims[3])
{
  VolumeView view;
  view.data = volume.data();
  view.type = Scalar<T>::Type;
  std::copy(dims, dims + 3, view.dims);
  return view;
}

// Splits into chunks of 1..3 items run in shuffled order.
inline ParallelFor ShuffledFor(unsigned seed)
{
  return [seed](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    std::mt19937 random(seed);
    std::vector<std::pair<std::size_t, std::size_t>> chunks;
    for (std::size_t begin = 0; begin < count;)
    {
      const std::size_t end = std::min(count, begin + 1 + random() % 3);
      chunks.emplace_back(begin, end);
      begin = end;
    }
    std::shuffle(chunks.begin(), chunks.end(), random);
    for (const auto& chunk : chunks)
    {
      body(chunk.first, chunk.second);
    }
  };
}

// Runs chunks of `chunk` items (0: about 8 per thread) on `threads` std::threads pulling from a
// shared counter.
inline ParallelFor ThreadedFor(unsigned threads, std::size_t chunk = 0)
{
  return
    [threads, chunk](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    const std::size_t grain = chunk > 0 ? chunk : std::max<std::size_t>(1, count / (8 * threads));
    std::atomic<std::size_t> next{ 0 };
    auto worker = [&]()
    {
      for (;;)
      {
        const std::size_t begin = next.fetch_add(grain);
        if (begin >= count)
        {
          return;
        }
        body(begin, std::min(count, begin + grain));
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t)
    {
      pool.emplace_back(worker);
    }
    worker();
    for (std::thread& thread : pool)
    {
      thread.join();
    }
  };
}
}

#endif
