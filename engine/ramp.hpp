// The smooth start of a prescribed motion: a velocity rises as (1 − cos πt/T)/2 over T, with no jerk at t = 0
// (walls under velocity or opening control, driven particle groups).
#pragma once
#include <algorithm>
#include <cmath>

namespace mc {

// The fraction of the full velocity reached at t; 1 from T on (and at once when T = 0).
inline double ramp_factor(double t, double ramp_time) {
  const double s = ramp_time > 0 ? std::min(t / ramp_time, 1.0) : 1.0;
  return 0.5 * (1.0 - std::cos(M_PI * s));
}

// The integral of ramp_factor over [0, t]: the time a constant rate has acted by t when it rises so.
inline double ramped_time(double t, double ramp_time) {
  if (ramp_time <= 0) return t;
  if (t >= ramp_time) return t - 0.5 * ramp_time;
  return 0.5 * t - ramp_time / (2 * M_PI) * std::sin(M_PI * t / ramp_time);
}

}  // namespace mc
