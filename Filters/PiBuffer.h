// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiBuffer.h
 * @brief an array left uninitialized when allocated
 *
 * For big work arrays that a parallel pass fills completely: their pages are first
 * touched (and zeroed by the kernel) by the threads that write them, not zeroed once
 * more by one thread as std::vector's resize would.
 */
#ifndef PiBuffer_h
#define PiBuffer_h

#include <cstddef>
#include <memory>
#include <utility>

namespace pisurf
{
template <typename T>
class Buffer
{
public:
  void Allocate(std::size_t n)
  {
    this->Data.reset(new T[n]);
    this->Size = n;
  }
  bool Empty() const { return this->Size == 0; }
  std::size_t GetSize() const { return this->Size; }
  T* GetPointer() { return this->Data.get(); }
  T& operator[](std::size_t k) { return this->Data[k]; }
  const T& operator[](std::size_t k) const { return this->Data[k]; }

private:
  std::unique_ptr<T[]> Data;
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
