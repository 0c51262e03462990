// Backward Euler steps of the config's size k = T/steps; when Newton fails,
// the step is retried with k halved (at most max_halvings times in a row)
// and the smaller k is kept until the next nominal time t_n = n k. Used by
// the C++ time loop; the reference engine takes fixed steps and never halves.
#pragma once

#include <string>
#include <utility>

namespace piezocontact
{
class StepControl
{
public:
  StepControl(double T, int N, int max_halvings)
      : N(N), max_halvings(max_halvings), _k_nominal(T / N), k(T / N), k_last(T / N)
  {
  }

  bool done() const { return _n == N; }

  /// (t, k) of the next try; lands exactly on the next nominal time
  std::pair<double, double> attempt() const
  {
    const double target = (_n + 1) * _k_nominal;
    if (t + k >= target - 1e-9 * _k_nominal)
      return {target, target - t};
    return {t + k, k};
  }

  void accept()
  {
    const auto [t_new, k_used] = attempt();
    t = t_new;
    k_last = k_used;
    _halvings = 0;
    ++accepted;
    if (t_new == (_n + 1) * _k_nominal)
    {
      ++_n;
      k = _k_nominal;
    }
  }

  /// "halve k" or, past the limit, "stop"
  std::string reject()
  {
    if (_halvings == max_halvings)
      return "stop";
    ++_halvings;
    k /= 2;
    return "halve k";
  }

  /// Nominal steps completed
  int nominal_steps() const { return _n; }

  /// Continue from a checkpoint: the state right after an accepted step
  void restore(int nominal_steps, double t_, double k_, double k_last_, int accepted_)
  {
    _n = nominal_steps;
    _halvings = 0;
    t = t_;
    k = k_;
    k_last = k_last_;
    accepted = accepted_;
  }

  const int N, max_halvings;

private:
  double _k_nominal;
  int _n = 0;         // nominal steps completed
  int _halvings = 0;  // consecutive failures

public:
  double t = 0.0;     ///< time of the last accepted state
  double k;           ///< step size of the next try
  double k_last;      ///< size of the last accepted step
  int accepted = 0;
};
} // namespace piezocontact
