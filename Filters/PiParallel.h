// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiParallel.h
 * @brief vtkSMPTools::For with one task per thread, the chunks claimed from a counter
 *
 * `ParallelFor(first, last, grain, f)` calls f(begin, end) on the chunks [first + c·grain,
 * first + (c + 1)·grain) ∩ [first, last), each exactly once, like
 * `vtkSMPTools::For(first, last, grain, f)`, but hands vtkSMPTools only one task per
 * thread: each task claims chunks in increasing order from a shared atomic counter until
 * none is left (the same dynamic balancing, chunk by chunk).
 *
 * Why: VTK 9.2's STDThread backend (ParaView 5.11's) queues every chunk as a
 * std::function behind a mutex and a condition variable. On this 2-core machine that
 * costs about 0.6 µs per chunk (681 chunks of 8 blocks: 0.51 ms for a loop that takes
 * 0.12 ms as two tasks), which the mesher's passes paid several times per execution.
 * With the Sequential backend (one thread) ParallelFor is vtkSMPTools::For itself.
 *
 * The functor keeps everything vtkSMPTools gives it: it runs on vtkSMPTools' threads,
 * so `SingleThread()` (below) is true on exactly one of them (progress and cancel
 * checks), and nested calls run serially as vtkSMPTools runs them. It must not
 * need per-thread Initialize/Reduce (no PiSurfaces functor has them).
 */
#ifndef PiParallel_h
#define PiParallel_h

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>

namespace pisurf
{

/// `vtkSMPTools::GetSingleThread()`, also where a loop runs serially. ParaView 5.11's
/// STDThread backend answers it from a stack of thread ids that only its parallel loops
/// push: in a loop it runs serially on the calling thread (a range no longer than the
/// grain), it reads the top of the empty stack, which is undefined (TestPiParallel
/// crashed on it). Outside a parallel scope the calling thread is the only one, so it
/// is the single thread. The functors use this to decide which thread reports progress
/// and checks for a cancel.
inline bool SingleThread()
{
  return !vtkSMPTools::IsParallelScope() || vtkSMPTools::GetSingleThread();
}

template <class Functor>
void ParallelFor(vtkIdType first, vtkIdType last, vtkIdType grain, Functor&& f)
{
  const vtkIdType n = last - first;
  if (n <= 0)
  {
    return;
  }
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  // (grain <= 0: vtkSMPTools' own default, about four chunks per thread)
  const vtkIdType size = grain > 0 ? grain : std::max<vtkIdType>(1, n / (4 * std::max(threads, 1)));
  const vtkIdType chunks = (n + size - 1) / size;
  if (threads <= 1 || chunks <= 1)
  {
    vtkSMPTools::For(first, last, grain, f);
    return;
  }
  std::atomic<vtkIdType> next{ 0 };
  vtkSMPTools::For(0, std::min<vtkIdType>(threads, chunks), 1,
    [&](vtkIdType, vtkIdType)
    {
      for (vtkIdType c = next.fetch_add(1, std::memory_order_relaxed); c < chunks;
           c = next.fetch_add(1, std::memory_order_relaxed))
      {
        const vtkIdType begin = first + c * size;
        f(begin, std::min(last, begin + size));
      }
    });
}

}

#endif
