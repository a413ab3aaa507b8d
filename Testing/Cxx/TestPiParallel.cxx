// SPDX-License-Identifier: BSD-3-Clause
// pisurf::ParallelFor (PiParallel.h): with each backend (Sequential, STDThread with 2 and 4
// threads), every index of the range is visited exactly once, in chunks that start on the grain's
// multiples and are at most a grain long (vtkSMPTools' default grain where it is 0);
// exactly one thread is the single thread of pisurf::SingleThread (the one that reports
// progress and checks for a cancel), also when the loop runs serially on the calling
// thread, where ParaView 5.11's vtkSMPTools::GetSingleThread() reads an empty stack and
// crashed this test; a pisurf::ParallelFor inside a pisurf::ParallelFor (as the mesher's passes
// nest in ParaView's pipelines) visits its whole range too.
#include "PiParallel.h"

#include "vtkSMPTools.h"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what.c_str());
    ++failures;
  }
}

void Run(const std::string& setup)
{
  for (const vtkIdType first : { vtkIdType(0), vtkIdType(13) })
    for (const vtkIdType n :
      { vtkIdType(0), vtkIdType(1), vtkIdType(7), vtkIdType(1000), vtkIdType(5451) })
      for (const vtkIdType grain :
        { vtkIdType(0), vtkIdType(1), vtkIdType(8), vtkIdType(16), vtkIdType(4096) })
      {
        const std::string what = setup + ", first " + std::to_string(first) + ", n " +
          std::to_string(n) + ", grain " + std::to_string(grain);
        std::vector<std::atomic<int>> visits(static_cast<size_t>(n));
        for (auto& v : visits)
        {
          v = 0;
        }
        std::atomic<bool> aligned{ true }, bounded{ true }, empty{ false };
        std::mutex mutex;
        std::set<std::thread::id> threads, single;
        pisurf::ParallelFor(first, first + n, grain,
          [&](vtkIdType begin, vtkIdType end)
          {
            if (!(begin < end))
            {
              empty = true;
            }
            if (grain > 0 && ((begin - first) % grain != 0 || end - begin > grain))
            {
              aligned = false;
            }
            if (begin < first || end > first + n)
            {
              bounded = false;
              return;
            }
            for (vtkIdType i = begin; i < end; ++i)
            {
              ++visits[static_cast<size_t>(i - first)];
            }
            std::lock_guard<std::mutex> lock(mutex);
            threads.insert(std::this_thread::get_id());
            if (pisurf::SingleThread())
            {
              single.insert(std::this_thread::get_id());
            }
          });
        bool once = true;
        for (const auto& v : visits)
        {
          once = once && v == 1;
        }
        Check(once, what + ": every index visited exactly once");
        Check(bounded, what + ": chunks within the range");
        Check(!empty, what + ": no empty chunk");
        Check(aligned, what + ": chunks start on the grain and are at most a grain long");
        Check(single.size() <= 1, what + ": at most one single thread");
        // (In a parallel loop the single thread may claim no chunk; a loop run on the
        // calling thread alone has that thread as its single thread.)
        if (n > 0 && threads.size() == 1 && *threads.begin() == std::this_thread::get_id())
        {
          Check(single.size() == 1, what + ": the calling thread, alone, is the single thread");
        }
      }

  // Nested: the inner loops run whole inside the outer one.
  std::atomic<long> sum{ 0 };
  pisurf::ParallelFor(0, 64, 1,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        pisurf::ParallelFor(0, 100, 8, [&](vtkIdType b, vtkIdType e) { sum += e - b; });
      }
    });
  Check(sum == 6400, setup + ": nested loops visit 64 x 100 indices");
}
}

int TestPiParallel(int, char*[])
{
  vtkSMPTools::SetBackend("Sequential");
  Run("Sequential");
  if (vtkSMPTools::SetBackend("STDThread"))
  {
    for (const int threads : { 2, 4 })
    {
      vtkSMPTools::Initialize(threads);
      Run("STDThread " + std::to_string(threads));
    }
  }
  vtkSMPTools::SetBackend("Sequential");
  std::printf("%s\n", failures == 0 ? "PiFor: all checks passed" : "PiFor: FAILED");
  return failures == 0 ? 0 : 1;
}
