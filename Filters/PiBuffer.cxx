// SPDX-License-Identifier: BSD-3-Clause
#include "PiBuffer.h"

#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pisurf
{
namespace
{
// The size classes of large blocks (AllocateLarge rounds a request up to a multiple).
constexpr std::size_t SizeClass = std::size_t(1) << 21;

// Every live or kept block of AllocateLarge's large path, with its capacity, and the
// kept ones, oldest first. Made on first use and never destroyed: VTK arrays may give
// their memory back during the process's static destruction.
struct LargeCache
{
  std::mutex Mutex;
  std::unordered_map<void*, std::size_t> Capacity;
  std::vector<std::pair<void*, std::size_t>> Kept;
  std::size_t KeptBytes = 0;
};

LargeCache& Cache()
{
  static LargeCache* cache = new LargeCache;
  return *cache;
}
}

void* AllocateLarge(std::size_t bytes)
{
  if (bytes < SizeClass / 4)
  {
    return std::malloc(bytes > 0 ? bytes : 1);
  }
  const std::size_t rounded = (bytes + SizeClass - 1) & ~(SizeClass - 1);
  LargeCache& cache = Cache();
  {
    // The smallest kept block that holds the request and is at most twice its size.
    std::lock_guard<std::mutex> lock(cache.Mutex);
    size_t best = cache.Kept.size();
    for (size_t k = 0; k < cache.Kept.size(); ++k)
    {
      const std::size_t capacity = cache.Kept[k].second;
      if (capacity >= rounded && capacity / 2 <= rounded &&
        (best == cache.Kept.size() || capacity < cache.Kept[best].second))
      {
        best = k;
      }
    }
    if (best < cache.Kept.size())
    {
      void* data = cache.Kept[best].first;
      cache.KeptBytes -= cache.Kept[best].second;
      cache.Kept.erase(cache.Kept.begin() + static_cast<std::ptrdiff_t>(best));
      return data;
    }
  }
  // (In ordinary pages, not advised to transparent huge pages: see AllocateLarge's
  // documentation.)
  void* data = std::malloc(rounded);
  if (!data)
  {
    return nullptr;
  }
  try
  {
    std::lock_guard<std::mutex> lock(cache.Mutex);
    // (Assigned, not emplaced: an entry left by a block freed some other way must not
    // keep its old capacity for this one.)
    cache.Capacity[data] = rounded;
  }
  catch (...)
  {
    // Not recorded (out of memory for the table): ReleaseLarge will simply free it.
  }
  return data;
}

void ReleaseLarge(void* data)
{
  if (!data)
  {
    return;
  }
  LargeCache& cache = Cache();
  std::lock_guard<std::mutex> lock(cache.Mutex);
  const auto found = cache.Capacity.find(data);
  if (found == cache.Capacity.end())
  {
    // A small block (plain malloc) or one the table could not record.
    std::free(data);
    return;
  }
  const std::size_t capacity = found->second;
  bool kept = false;
  if (capacity <= LargeCacheBytes)
  {
    try
    {
      cache.Kept.emplace_back(data, capacity);
      cache.KeptBytes += capacity;
      kept = true;
    }
    catch (...)
    {
    }
  }
  if (!kept)
  {
    cache.Capacity.erase(found);
    std::free(data);
    return;
  }
  // Over the limit: the oldest kept blocks go back to the system.
  size_t oldest = 0;
  while (cache.KeptBytes > LargeCacheBytes && oldest < cache.Kept.size())
  {
    cache.KeptBytes -= cache.Kept[oldest].second;
    cache.Capacity.erase(cache.Kept[oldest].first);
    std::free(cache.Kept[oldest].first);
    ++oldest;
  }
  cache.Kept.erase(cache.Kept.begin(), cache.Kept.begin() + static_cast<std::ptrdiff_t>(oldest));
}

std::size_t KeptLargeBytes()
{
  LargeCache& cache = Cache();
  std::lock_guard<std::mutex> lock(cache.Mutex);
  return cache.KeptBytes;
}
}
