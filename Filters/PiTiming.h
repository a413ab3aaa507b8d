// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiTiming.h
 * @brief PISURF_TIMING=1: the time of each pass of an algorithm on stderr
 *
 * `PassTimer lap("vtkPiFlyingEdges");` then `lap("classify");` after each pass prints
 * "vtkPiFlyingEdges classify: 0.0123 s" (wall time) when the environment variable
 * PISURF_TIMING is set, and nothing otherwise. Where the system has getrusage, a lap
 * also gives the CPU time of all threads and the page faults (first touches of fresh
 * memory) of the pass:
 * "vtkPiFlyingEdges classify: 0.0123 s (CPU 0.0240 s, 1200 page faults)".
 */
#ifndef PiTiming_h
#define PiTiming_h

#include <chrono>
#include <cstdlib>
#include <iostream>
#if defined(__unix__) || defined(__APPLE__)
#include <sys/resource.h>

namespace pisurf
{
#define PI_TIMING_RUSAGE 1
#endif

class PassTimer
{
public:
  explicit PassTimer(const char* owner)
    : Owner(owner)
    , Enabled(std::getenv("PISURF_TIMING") != nullptr)
  {
    this->Reset();
  }

  /// Whether PISURF_TIMING is set (for other diagnostics of the same kind).
  bool IsEnabled() const { return this->Enabled; }

  /// Prints the time since the last lap (or the start) under `pass`.
  void operator()(const char* pass)
  {
    if (!this->Enabled)
    {
      return;
    }
    const double now = this->Now();
    std::cerr << this->Owner << " " << pass << ": " << now - this->Last << " s";
#ifdef PI_TIMING_RUSAGE
    double cpu;
    long faults;
    Usage(cpu, faults);
    std::cerr << " (CPU " << cpu - this->LastCpu << " s, " << faults - this->LastFaults
              << " page faults)";
    this->LastCpu = cpu;
    this->LastFaults = faults;
#endif
    std::cerr << "\n";
    this->Last = now;
  }

  /// Prints the time since the start under `pass` (the last lap is kept).
  void Total(const char* pass) const
  {
    if (this->Enabled)
    {
      std::cerr << this->Owner << " " << pass << ": " << this->Now() - this->Start << " s\n";
    }
  }

private:
  static double Now()
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }
  void Reset()
  {
    this->Start = this->Last = this->Now();
#ifdef PI_TIMING_RUSAGE
    if (this->Enabled)
    {
      Usage(this->LastCpu, this->LastFaults);
    }
#endif
  }
#ifdef PI_TIMING_RUSAGE
  // The process's CPU time (user and system, all threads) and minor page faults.
  static void Usage(double& cpu, long& faults)
  {
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    cpu = u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
    faults = u.ru_minflt;
  }
#endif

  const char* Owner;
  bool Enabled;
  double Start = 0, Last = 0;
  double LastCpu = 0;
  long LastFaults = 0;
};
}

#endif
