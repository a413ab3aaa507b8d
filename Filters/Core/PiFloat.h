// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiFloat.h
 * @brief frexp and ldexp on the bits of a double, for the hot paths
 *
 * The C library's std::frexp and std::ldexp are calls that the compiler does not inline;
 * the overflow-safe products use them for every factor of every point. These give the
 * same results bit for bit: for normal numbers (and normal results) they read and write
 * the exponent field directly, and hand everything else (0, subnormals, inf, NaN, a
 * result outside the normal range) to the library.
 */
#ifndef PiFloat_h
#define PiFloat_h

#include <cmath>
#include <cstdint>
#include <cstring>

/// Marks a hot function to be compiled twice, for AVX2 (4 doubles per vector
/// instruction instead of SSE2's 2) and for any x86-64, the version chosen when the
/// library loads. No FMA: the AVX2 version computes the same bits.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define PISURF_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PISURF_AVX2_CLONES
#endif

namespace pisurf
{
/// std::frexp(x, e), bit for bit.
inline double Frexp(double x, int* e)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0 || biased == 0x7ff)
  {
    return std::frexp(x, e);
  }
  *e = biased - 1022;
  bits = (bits & ~(std::uint64_t(0x7ff) << 52)) | (std::uint64_t(1022) << 52);
  double m;
  std::memcpy(&m, &bits, sizeof m);
  return m;
}

/// std::ldexp(x, n), bit for bit.
inline double Ldexp(double x, int n)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const long biased = static_cast<long>((bits >> 52) & 0x7ff);
  const long result = biased + n;
  if (biased == 0 || biased == 0x7ff || result <= 0 || result >= 0x7ff)
  {
    return std::ldexp(x, n);
  }
  bits = (bits & ~(std::uint64_t(0x7ff) << 52)) | (std::uint64_t(result) << 52);
  double y;
  std::memcpy(&y, &bits, sizeof y);
  return y;
}
}

#endif
