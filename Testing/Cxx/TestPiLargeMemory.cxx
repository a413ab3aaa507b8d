// SPDX-License-Identifier: BSD-3-Clause
// pisurf::AllocateLarge / ReleaseLarge: large blocks given back are kept (up to
// LargeCacheBytes) and handed out again for requests of their size class, also through
// the VTK output arrays of PiLargeArrays.h; small blocks and blocks beyond the limit go
// back to the system.
#include "PiBuffer.h"
#include "PiLargeArrays.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>

namespace
{
int failures = 0;
void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::fprintf(stderr, "FAILED: %s\n", what);
    ++failures;
  }
}
constexpr std::size_t MiB = std::size_t(1) << 20;
}

int TestPiLargeMemory(int, char*[])
{
  Check(pisurf::KeptLargeBytes() == 0, "nothing kept at start");

  // A block given back is the next block of its size class.
  void* a = pisurf::AllocateLarge(3 * MiB);
  Check(a != nullptr, "3 MiB allocated");
  std::memset(a, 1, 3 * MiB);
  pisurf::ReleaseLarge(a);
  Check(pisurf::KeptLargeBytes() == 4 * MiB, "a 3 MiB request is kept as its 4 MiB size class");
  void* b = pisurf::AllocateLarge(4 * MiB);
  Check(b == a, "a request of the same rounded size takes the kept block");
  Check(pisurf::KeptLargeBytes() == 0, "the block is no longer kept once handed out");

  // A much smaller request (less than half the block) gets its own memory.
  pisurf::ReleaseLarge(b);
  void* small = pisurf::AllocateLarge(1 * MiB); // rounds to 2 MiB: the 4 MiB block fits (≤ 2×)
  Check(small == a, "a block at most twice the rounded request is reused");
  pisurf::ReleaseLarge(small);
  void* tiny = pisurf::AllocateLarge(700 * 1024); // rounds to 2 MiB as well
  Check(tiny == a, "700 KiB rounds to 2 MiB: the 4 MiB block is reused");
  pisurf::ReleaseLarge(tiny);
  void* big8 = pisurf::AllocateLarge(8 * MiB);
  Check(big8 != a, "a request larger than every kept block is fresh memory");
  pisurf::ReleaseLarge(big8);
  void* two = pisurf::AllocateLarge(2 * MiB);
  Check(two == a, "the smallest fitting block is taken (4 MiB, not 8 MiB)");
  void* three = pisurf::AllocateLarge(2 * MiB);
  Check(three != big8, "8 MiB is more than twice a 2 MiB request: not reused");
  pisurf::ReleaseLarge(three);
  three = pisurf::AllocateLarge(3 * MiB);
  Check(three == big8, "8 MiB is at most twice a 3 MiB request (4 MiB rounded): reused");
  pisurf::ReleaseLarge(two);
  pisurf::ReleaseLarge(three);

  // Small blocks are plain malloc: freed at once, never kept.
  const std::size_t kept = pisurf::KeptLargeBytes();
  void* m = pisurf::AllocateLarge(1000);
  Check(m != nullptr, "a small block");
  pisurf::ReleaseLarge(m);
  pisurf::ReleaseLarge(std::malloc(64)); // any malloc'ed block may be given back
  pisurf::ReleaseLarge(nullptr);
  Check(pisurf::KeptLargeBytes() == kept, "small blocks are not kept");

  // Over the limit the oldest kept blocks are freed.
  void* blocks[3];
  for (void*& block : blocks)
  {
    block = pisurf::AllocateLarge(100 * MiB);
    Check(block != nullptr, "100 MiB allocated");
  }
  for (void* block : blocks)
  {
    pisurf::ReleaseLarge(block);
  }
  Check(pisurf::KeptLargeBytes() <= pisurf::LargeCacheBytes, "the limit holds");
  std::set<void*> again;
  again.insert(pisurf::AllocateLarge(100 * MiB));
  again.insert(pisurf::AllocateLarge(100 * MiB));
  Check(again.count(blocks[1]) == 1 && again.count(blocks[2]) == 1,
    "the two newest 100 MiB blocks were kept and are handed out again");
  for (void* block : again)
  {
    pisurf::ReleaseLarge(block);
  }

  // A block beyond the limit is never kept.
  const std::size_t before = pisurf::KeptLargeBytes();
  void* huge = pisurf::AllocateLarge(pisurf::LargeCacheBytes + MiB);
  Check(huge != nullptr, "a block beyond the limit");
  pisurf::ReleaseLarge(huge);
  Check(pisurf::KeptLargeBytes() == before, "a block beyond the limit is freed");

  // VTK arrays give their memory back through ReleaseLarge: a filter's next output of
  // the same size reuses the previous one's pages.
  const double* first = nullptr;
  {
    vtkNew<vtkDoubleArray> array;
    array->SetNumberOfComponents(3);
    pisurf::AllocateLargeArray(array.GetPointer(), 1000000);
    Check(array->GetNumberOfTuples() == 1000000, "the array has its tuples");
    first = array->GetPointer(0);
    array->FillValue(2.0);
  }
  {
    vtkNew<vtkDoubleArray> array;
    array->SetNumberOfComponents(3);
    pisurf::AllocateLargeArray(array.GetPointer(), 1000000);
    Check(array->GetPointer(0) == first, "the next array of that size reuses the memory");
    // Growing the array moves it to fresh memory and gives the block back.
    array->InsertNextTuple3(1.0, 2.0, 3.0);
    Check(array->GetNumberOfTuples() == 1000001 && array->GetComponent(1000000, 2) == 3.0 &&
        array->GetComponent(999999, 0) == 2.0,
      "a grown array keeps its values");
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
