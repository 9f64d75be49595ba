// ParallelFor: a fixed number of std::threads taking chunks dynamically.
#include "common/ParallelFor.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace accelvolume
{

ParallelFor FixedThreadsParallelFor(int threads)
{
  const std::size_t workers = static_cast<std::size_t>(std::max(threads, 1));
  return [workers](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    const std::size_t used = std::min(workers, count);
    if (used <= 1)
    {
      if (count > 0)
      {
        body(0, count);
      }
      return;
    }
    // Several chunks per worker so that uneven items (tiles of dense and empty space) balance.
    const std::size_t chunk = std::max<std::size_t>(1, count / (used * 8));
    std::atomic<std::size_t> next{ 0 };
    std::exception_ptr failure;
    std::mutex failureLock;
    const auto work = [&]()
    {
      try
      {
        for (;;)
        {
          const std::size_t begin = next.fetch_add(chunk, std::memory_order_relaxed);
          if (begin >= count)
          {
            return;
          }
          body(begin, std::min(count, begin + chunk));
        }
      }
      catch (...)
      {
        const std::lock_guard<std::mutex> lock(failureLock);
        if (!failure)
        {
          failure = std::current_exception();
        }
        next.store(count, std::memory_order_relaxed); // the others stop at their next chunk
      }
    };
    std::vector<std::thread> helpers;
    helpers.reserve(used - 1);
    for (std::size_t t = 1; t < used; ++t)
    {
      helpers.emplace_back(work);
    }
    work();
    for (std::thread& helper : helpers)
    {
      helper.join();
    }
    if (failure)
    {
      std::rethrow_exception(failure);
    }
  };
}

} // namespace accelvolume
