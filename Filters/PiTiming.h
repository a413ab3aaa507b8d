// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiTiming.h
 * @brief PISURF_TIMING=1: the time of each pass of an algorithm on stderr
 *
 * `PiPassTimer lap("vtkPiFlyingEdges");` then `lap("classify");` after each pass prints
 * "vtkPiFlyingEdges classify: 0.0123 s" (wall time, or process CPU time with `Cpu`)
 * when the environment variable PISURF_TIMING is set, and nothing otherwise.
 */
#ifndef PiTiming_h
#define PiTiming_h

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <iostream>

class PiPassTimer
{
public:
  enum Clock
  {
    Wall,
    Cpu
  };

  explicit PiPassTimer(const char* owner, Clock clock = Wall)
    : Owner(owner)
    , Kind(clock)
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
    std::cerr << this->Owner << " " << pass << ": " << now - this->Last << " s"
              << (this->Kind == Cpu ? " CPU" : "") << "\n";
    this->Last = now;
  }

  /// Prints the time since the start under `pass` (the last lap is kept).
  void Total(const char* pass) const
  {
    if (this->Enabled)
    {
      std::cerr << this->Owner << " " << pass << ": " << this->Now() - this->Start << " s"
                << (this->Kind == Cpu ? " CPU" : "") << "\n";
    }
  }

private:
  double Now() const
  {
    if (this->Kind == Cpu)
    {
      return double(std::clock()) / CLOCKS_PER_SEC;
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }
  void Reset() { this->Start = this->Last = this->Now(); }

  const char* Owner;
  Clock Kind;
  bool Enabled;
  double Start = 0, Last = 0;
};

#endif
