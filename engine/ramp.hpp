// The smooth start of a prescribed motion: a velocity rises as (1 − cos πt/T)/2 over T, with no jerk at t = 0
// (walls under velocity or opening control, driven particle groups); or, for the rigid-cell plates, as Květoň's
// (9.1), whose acceleration vanishes at both ends of the rise.
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

// Květoň (9.1): the displacement per unit of the full velocity at t when the velocity rises as
// t/T − sin(2πt/T)/(2π) over T: t²/(2T) + T/(4π²)(cos(2πt/T) − 1), then t − T/2. (The thesis prints the formula
// garbled; this is the one whose velocity and acceleration are continuous at 0 and T, as its text asks.)
inline double smooth_rise_displacement(double t, double ramp_time) {
  if (ramp_time <= 0) return t;
  if (t >= ramp_time) return t - 0.5 * ramp_time;
  return t * t / (2 * ramp_time) + ramp_time / (4 * M_PI * M_PI) * (std::cos(2 * M_PI * t / ramp_time) - 1);
}

// Its velocity per unit of the full velocity: t/T − sin(2πt/T)/(2π), then 1 (at once, from t = 0 on, when T = 0).
inline double smooth_rise_velocity(double t, double ramp_time) {
  if (ramp_time <= 0 || t >= ramp_time) return 1;
  return t / ramp_time - std::sin(2 * M_PI * t / ramp_time) / (2 * M_PI);
}

// Its acceleration per unit of the full velocity: (1 − cos(2πt/T))/T, then 0.
inline double smooth_rise_acceleration(double t, double ramp_time) {
  if (ramp_time <= 0 || t >= ramp_time) return 0;
  return (1 - std::cos(2 * M_PI * t / ramp_time)) / ramp_time;
}

}  // namespace mc
