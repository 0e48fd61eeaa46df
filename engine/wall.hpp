// Rigid walls: 2D line segments, 3D planar rectangles, and infinite lines/planes in either dimension.
// A wall moves by translation only, under one of four controls: fixed, prescribed velocity with a smooth
// ramp, a normal-stress servo (PFC), or an opening servo (CMOD control, Tang §7.1). It records the force and moment the
// balls exert on it and its displacement.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "engine/contact_geometry.hpp"  // WallMaterial
#include "engine/dim.hpp"
#include "engine/ramp.hpp"

namespace mc {

enum class WallControl { Fixed, Velocity, Servo, Opening };

template <int D>
struct Wall {
  std::string name;
  Vec<D> origin;                   // centre of the segment/rectangle, a point of an infinite wall [m]
  Vec<D> normal;                   // unit normal, pointing to the side where the material is
  std::array<Vec<D>, D - 1> axis;  // in-plane unit axes
  std::array<double, D - 1> half;  // half-extents along the axes [m]; ∞ for an infinite wall
  WallMaterial material;

  WallControl control = WallControl::Fixed;
  Vec<D> target_velocity = Vec<D>::Zero();  // Velocity control [m/s]
  double ramp_time = 0;                     // [s]: velocity rises as (1 − cos πt/T)/2, no jerk at start
  double target_stress = 0;                 // Servo: compressive normal stress to hold [Pa]
  double servo_area = kNaN;                 // [m² in 3D, m in 2D]; NaN: the wall's own area
  // Pairs of opposite walls (indices) whose current distances span the loaded area (one pair in 2D, two in
  // 3D): the stress follows the specimen as it shrinks, as PFC computes it. Empty: servo_area or own area.
  std::vector<std::array<int, 2>> area_between;
  double servo_gain = 0.5;        // α of the PFC servo, 0 < α ≤ 1
  double servo_max_speed = kInf;  // [m/s], both servos
  // Opening: the wall moves along its normal so that the opening gauge `gauge` (World::gauges) grows at
  // `opening_rate`, reached over ramp_time like the velocity ramp. Proportional control, as PFC's servos:
  // v = clamp(opening_gain (target − reading), −retreat_speed, servo_max_speed), positive into the material:
  // the wall may back off after a crack jump at another speed than it advances (on Tang's beam a retreat at the
  // rate or at three times it made no measurable difference; the loop's gain sets how calm the branch is).
  int gauge = -1;
  double opening_rate = 0;      // [m/s]
  double opening_gain = 0;      // [1/s]
  double retreat_speed = kInf;  // [m/s]

  Vec<D> velocity = Vec<D>::Zero();
  Vec<D> displacement = Vec<D>::Zero();  // since the start of the run [m]
  Vec<D> force = Vec<D>::Zero();         // exerted by the balls on the wall [N]
  Rot<D> moment = Rot<D>::Zero();        // about the origin [N m]
  double contact_kn = 0;  // Σ(k_n + k_s) of its touching contacts (servo gain; ≥ Σk_n, so conservative)

  // Closest point of the wall to p; the contact normal runs from it to p.
  Vec<D> closest(const Vec<D>& p) const {
    Vec<D> c = origin;
    for (int k = 0; k < D - 1; ++k) {
      const double s = (p - origin).dot(axis[k]);
      c += std::clamp(s, -half[k], half[k]) * axis[k];
    }
    return c;
  }

  double area() const {
    double a = 1;  // 2D: per unit thickness
    for (int k = 0; k < D - 1; ++k) a *= 2 * half[k];
    return a;
  }

  // Compressive stress the balls exert on the wall [Pa].
  double normal_stress() const {
    const double a = std::isnan(servo_area) ? area() : servo_area;
    return -force.dot(normal) / a;
  }

  // Velocity for the next step, from the control law. t is the time since the run started; `opening` the
  // reading of the wall's gauge with the particles already moved to t + dt (Opening control only).
  void control_velocity(double t, double dt, double opening) {
    switch (control) {
      case WallControl::Fixed: velocity.setZero(); break;
      case WallControl::Velocity: {
        velocity = target_velocity * ramp_factor(t, ramp_time);
        break;
      }
      case WallControl::Servo: {
        // PFC servo: G = α A / (Σk_n Δt) makes the stress error shrink by at most α per step, so the wall
        // cannot overshoot into an instability whatever the current stiffness (Σ(k_n + k_s) here: a smaller,
        // safer gain).
        const double a = std::isnan(servo_area) ? area() : servo_area;
        double speed = 0;
        if (contact_kn > 0)
          speed = servo_gain * a / (contact_kn * dt) * (target_stress - normal_stress());
        else if (std::isfinite(servo_max_speed))
          speed = servo_max_speed;  // nothing touched yet: approach at full speed
        speed = std::clamp(speed, -servo_max_speed, servo_max_speed);
        velocity = speed * normal;
        break;
      }
      case WallControl::Opening: {
        // The target follows the velocities' own ramp: the time the ramped rate has acted.
        const double target = opening_rate * ramped_time(t + dt, ramp_time);
        velocity = std::clamp(opening_gain * (target - opening), -retreat_speed, servo_max_speed) * normal;
        break;
      }
    }
  }

  // Segment a→b (2D); the normal is chosen to point towards `inside`.
  static Wall segment(const Vec<2>& a, const Vec<2>& b, const Vec<2>& inside) requires(D == 2) {
    Wall w;
    w.origin = 0.5 * (a + b);
    w.axis[0] = (b - a).normalized();
    w.half[0] = 0.5 * (b - a).norm();
    w.normal = Vec<2>(-w.axis[0][1], w.axis[0][0]);
    if ((inside - w.origin).dot(w.normal) < 0) w.normal = -w.normal;
    return w;
  }
  // Infinite line (2D) or plane (3D) through `point`, normal towards the material.
  static Wall plane(const Vec<D>& point, const Vec<D>& normal) {
    Wall w;
    w.origin = point;
    w.normal = normal.normalized();
    if constexpr (D == 2) {
      w.axis[0] = Vec<2>(-w.normal[1], w.normal[0]);
    } else {
      Vec<3> t = std::abs(w.normal[0]) < 0.9 ? Vec<3>::UnitX() : Vec<3>::UnitY();
      w.axis[0] = (t - t.dot(w.normal) * w.normal).normalized();
      w.axis[1] = w.normal.cross(w.axis[0]);
    }
    w.half.fill(kInf);
    return w;
  }
  // Rectangle (3D) centred at `centre` with normal `normal`, edge `axis0` of length `size0` and the third
  // direction of length `size1`.
  static Wall rectangle(const Vec<3>& centre, const Vec<3>& normal, const Vec<3>& axis0, double size0,
                        double size1) requires(D == 3) {
    Wall w = plane(centre, normal);
    w.axis[0] = (axis0 - axis0.dot(w.normal) * w.normal).normalized();
    w.axis[1] = w.normal.cross(w.axis[0]);
    w.half = {0.5 * size0, 0.5 * size1};
    return w;
  }
};

}  // namespace mc
