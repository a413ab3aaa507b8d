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
  T& operator[](std::size_t k) { return this->Data[k]; }
  const T& operator[](std::size_t k) const { return this->Data[k]; }

private:
  std::unique_ptr<T[]> Data;
  std::size_t Size = 0;
};
}

#endif
