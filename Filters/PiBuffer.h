// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiBuffer.h
 * @brief arrays left uninitialized when allocated, in huge pages when large
 *
 * For big work arrays that a parallel pass fills completely: their pages are first
 * touched (and zeroed by the kernel) by the threads that write them, not zeroed once
 * more by one thread as std::vector's resize would; from 512 KiB on they are 2 MiB-aligned
 * and advised to transparent huge pages (AllocateLarge). PiLargeArrays.h gives VTK's
 * output arrays the same memory.
 */
#ifndef PiBuffer_h
#define PiBuffer_h

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pisurf
{
/// Memory for a large array that is written once, from its first byte: from 512 KiB on,
/// aligned to 2 MiB and backed by transparent huge pages where the kernel offers them
/// (Linux with THP in "madvise" mode, as on Debian). Every first touch of a 4 KiB page
/// is a fault that the kernel serves by zeroing it; in a virtual machine each costs
/// several microseconds: a 128 MiB grid faulted 32 768 times, two thirds of
/// vtkPiSampleFunction's time at 256³, and a few megabytes of mesh arrays, a tenth of
/// vtkPiFlyingEdges'. With huge pages that is one fault per 2 MiB. Only a hint: where
/// the kernel declines, or elsewhere than Linux, this is plain aligned memory.
/// Release with std::free. nullptr if out of memory.
inline void* AllocateLarge(std::size_t bytes)
{
  constexpr std::size_t Huge = std::size_t(1) << 21;
  if (bytes < Huge / 4)
  {
    return std::malloc(bytes > 0 ? bytes : 1);
  }
#if defined(__unix__) || defined(__APPLE__)
  const std::size_t rounded = (bytes + Huge - 1) & ~(Huge - 1);
  void* data = nullptr;
  if (::posix_memalign(&data, Huge, rounded) != 0)
  {
    return nullptr;
  }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  ::madvise(data, rounded, MADV_HUGEPAGE);
#endif
  return data;
#else
  return std::malloc(bytes);
#endif
}

/// An uninitialized array of n plain values (T trivial, as the work arrays are) in
/// AllocateLarge's memory.
template <typename T>
class Buffer
{
  static_assert(std::is_trivial<T>::value, "Buffer holds plain values");

public:
  /// Throws std::bad_alloc if out of memory (as new[] did).
  void Allocate(std::size_t n)
  {
    this->Data.reset(static_cast<T*>(AllocateLarge(n * sizeof(T))));
    if (!this->Data)
    {
      throw std::bad_alloc();
    }
    this->Size = n;
  }
  /// Allocate(n) unless the buffer already holds at least n values (kept as they are).
  void Reserve(std::size_t n)
  {
    if (this->Size < n || !this->Data)
    {
      this->Allocate(n);
    }
  }
  /// Frees the memory.
  void Release()
  {
    this->Data.reset();
    this->Size = 0;
  }
  bool Empty() const { return this->Size == 0; }
  std::size_t GetSize() const { return this->Size; }
  T* GetPointer() { return this->Data.get(); }
  T& operator[](std::size_t k) { return this->Data.get()[k]; }
  const T& operator[](std::size_t k) const { return this->Data.get()[k]; }

private:
  struct Free
  {
    void operator()(T* p) const { std::free(p); }
  };
  std::unique_ptr<T, Free> Data;
  std::size_t Size = 0;
};

/// A std::vector allocator whose resize leaves new elements of trivial types
/// uninitialized (default-initialized instead of value-initialized), for vectors that
/// grow by a resize the threads then fill.
template <typename T>
class DefaultInitAllocator : public std::allocator<T>
{
public:
  template <typename U>
  struct rebind
  {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
}

#endif
