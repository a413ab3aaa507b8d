// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiBuffer.h
 * @brief arrays left uninitialized when allocated, large blocks kept for reuse
 *
 * For big work arrays that a parallel pass fills completely: their pages are first
 * touched (and zeroed by the kernel) by the threads that write them, not zeroed once
 * more by one thread as std::vector's resize would; from 512 KiB on they come in 2 MiB
 * size classes, and blocks given back are kept for the next execution (AllocateLarge).
 * PiLargeArrays.h gives VTK's output arrays the same memory.
 */
#ifndef PiBuffer_h
#define PiBuffer_h

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace pisurf
{
/// Memory for a large array that is written once, from its first byte: from 512 KiB on,
/// rounded up to a multiple of 2 MiB (the size classes of the reuse below), in the
/// kernel's ordinary 4 KiB pages. Every first touch of a page is a fault that the kernel
/// serves by zeroing it.
///
/// The blocks are not advised to transparent huge pages: on the benchmark host huge
/// pages took longer to fault in than 4 KiB pages (the measurements are in
/// Documentation/benchmark-history.md, "Huge pages").
///
/// The kernel zeroes every fresh page (a cost that grows with the size: an all-hits
/// cast's output is about 100 MB). So large blocks given back with
/// ReleaseLarge are kept, up to LargeCacheBytes in all (oldest dropped first), and a
/// later request of the same size class (at most twice the rounded size) takes one of
/// them back, already faulted in: the next execution of a filter reuses its previous
/// output's memory once downstream has let it go, as vtkImageData::AllocateScalars
/// reuses an unshared array of the right size.
/// Release with ReleaseLarge only (it keeps the block's capacity on record). nullptr if
/// out of memory.
void* AllocateLarge(std::size_t bytes);
/// Gives back a block of AllocateLarge (or any malloc'ed block, which is freed).
/// Thread-safe; the block's contents are kept as they are.
void ReleaseLarge(void* data);
/// The most idle memory ReleaseLarge keeps (256 MiB).
constexpr std::size_t LargeCacheBytes = std::size_t(256) << 20;
/// The idle memory ReleaseLarge keeps now (for tests).
std::size_t KeptLargeBytes();

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
  /// Gives the memory back (ReleaseLarge).
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
    void operator()(T* p) const { ReleaseLarge(p); }
  };
  std::unique_ptr<T, Free> Data;
  std::size_t Size = 0;
};

/// A std::vector allocator whose resize leaves new elements of trivial types
/// uninitialized (default-initialized instead of value-initialized), for vectors that
/// grow by a resize the threads then fill. With Large, its memory is AllocateLarge's:
/// a vector that a new filter object grows to megabytes takes blocks an earlier one gave
/// back, already faulted in, instead of fresh pages zeroed by the kernel.
template <typename T, bool Large = false>
class DefaultInitAllocator : public std::allocator<T>
{
public:
  template <typename U>
  struct rebind
  {
    using other = DefaultInitAllocator<U, Large>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U, Large>&) noexcept
  {
  }
  T* allocate(std::size_t n)
  {
    if constexpr (Large)
    {
      T* p = static_cast<T*>(AllocateLarge(n * sizeof(T)));
      if (!p)
      {
        throw std::bad_alloc();
      }
      return p;
    }
    else
    {
      return std::allocator<T>::allocate(n);
    }
  }
  void deallocate(T* p, std::size_t n) noexcept
  {
    if constexpr (Large)
    {
      ReleaseLarge(p);
    }
    else
    {
      std::allocator<T>::deallocate(p, n);
    }
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

/// A std::vector of plain values in AllocateLarge's memory, uninitialized by resize.
template <typename T>
using LargeVector = std::vector<T, DefaultInitAllocator<T, true>>;
}

#endif
