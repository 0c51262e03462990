// Wall time of the library's operations: per run, for summary.json, and in
// dolfinx's TimeLogger under "piezocontact: ..." (dolfinx's list_timings,
// from C++ or Python, shows them beside dolfinx's own).
#pragma once

#include "config.h"

#include "compat.h"
#include <string>

namespace piezocontact
{
/// How often an operation ran in this run, and its total wall time
struct OperationStats
{
  int count = 0;
  double seconds = 0.0;
  json to_json() const { return {{"count", count}, {"seconds", seconds}}; }
};

/// Times a scope into `stats` and the TimeLogger task "piezocontact: TASK"
class ScopedTimer
{
public:
  ScopedTimer(OperationStats& stats, const std::string& task)
      : _stats(stats), _timer("piezocontact: " + task)
  {
  }
  ~ScopedTimer()
  {
    _stats.seconds += _timer.stop();
    ++_stats.count;
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
  OperationStats& _stats;
  compat::Timer _timer;
};
} // namespace piezocontact
