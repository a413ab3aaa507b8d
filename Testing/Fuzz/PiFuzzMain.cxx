// SPDX-License-Identifier: BSD-3-Clause
// One libFuzzer entry point per executable; PISURF_FUZZ_TARGET names the target.
#include "PiFuzzTargets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  pisurf::fuzz::PISURF_FUZZ_TARGET(data, size);
  return 0;
}
