#include "rigid_cell/fibre_pullout.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mc::rigid_cell {

namespace {
// π² E_f d_f³/2, the factor under the root of the debonding branch (5.1).
double debonding_stiffness(const FibreMaterial& f) {
  const double d = f.diameter;
  return 0.5 * M_PI * M_PI * f.modulus * d * d * d;
}
}  // namespace

double debonding_force(const FibreMaterial& f, double v) {
  return std::sqrt(debonding_stiffness(f) * (f.friction_stress * v + f.debonding_energy));
}

double full_debonding_slip(const FibreMaterial& f, double embedment) {
  const double ed = f.modulus * f.diameter, l2 = embedment * embedment;
  return 2.0 * f.friction_stress * l2 / ed + std::sqrt(8.0 * f.debonding_energy * l2 / ed);
}

double friction_force(const FibreMaterial& f, double embedment) {
  return M_PI * embedment * f.diameter * f.friction_stress;
}

double sliding_force(const FibreMaterial& f, double embedment, double v) {
  const double s = v - full_debonding_slip(f, embedment);
  const double left = 1.0 - s / embedment, hardening = 1.0 + f.slip_hardening * s / f.diameter;
  if (left <= 0 || hardening <= 0) return 0.0;
  return friction_force(f, embedment) * left * hardening;
}

double pullout_force(const FibreMaterial& f, double embedment, double v) {
  return v <= full_debonding_slip(f, embedment) ? debonding_force(f, v) : sliding_force(f, embedment, v);
}

double debonded_length(const FibreMaterial& f, double v) {
  const double g = f.debonding_energy;
  return std::sqrt(2.0 * f.modulus * f.diameter) * v / (2.0 * (std::sqrt(g + f.friction_stress * v) + std::sqrt(g)));
}

double pullout_work(const FibreMaterial& f, double embedment) {
  const double tau = f.friction_stress, g = f.debonding_energy, vd = full_debonding_slip(f, embedment);
  const double debonding =
      2.0 / 3.0 * std::sqrt(debonding_stiffness(f)) * (std::pow(tau * vd + g, 1.5) - std::pow(g, 1.5)) / tau;
  const double sliding =
      friction_force(f, embedment) * embedment * (0.5 + f.slip_hardening * embedment / (6.0 * f.diameter));
  return debonding + sliding;
}

double spalling_length(const FibreMaterial& f, double normal_force, double theta, double matrix_strength) {
  if (f.spalling_coefficient == 0) return 0.0;
  const double c = std::cos(0.5 * theta);
  return normal_force * std::sin(0.5 * theta) / (f.spalling_coefficient * matrix_strength * f.diameter * c * c);
}

double snubbing_factor(const FibreMaterial& f, double phi) { return std::exp(f.snubbing_coefficient * phi); }

double inclined_strength(const FibreMaterial& f, double phi) {
  return f.tensile_strength * std::exp(-f.rupture_coefficient * phi);
}

double pullout_resistance(const FibreMaterial& f, double embedment, double v) {
  return v < full_debonding_slip(f, embedment) ? debonding_force(f, v) : sliding_force(f, embedment, v);
}

namespace {

// The stretch of rising resistance a side at v is on: it ends at `end`, where the resistance approaches `top` from
// below. end = v: the side's resistance falls (or stays 0) as it slides.
struct Rising {
  double end, top;
};

Rising rising_from(const FibreMaterial& f, double embedment, double v) {
  const double vd = full_debonding_slip(f, embedment);
  if (v < vd) return {vd, debonding_force(f, vd)};
  // The slide P_0 (1 − s/L)(1 + β s/d) rises up to s* = (L − d/β)/2 when β L > d.
  const double beta = f.slip_hardening;
  if (beta <= 0 || beta * embedment <= f.diameter) return {v, pullout_resistance(f, embedment, v)};
  const double top_at = vd + 0.5 * (embedment - f.diameter / beta);
  if (v >= top_at) return {v, pullout_resistance(f, embedment, v)};
  return {top_at, sliding_force(f, embedment, top_at)};
}

// The pull-out in [v, rising.end] at which the side's rising resistance reaches p (between its value at v and the top):
// the debonding branch inverted in closed form, the slide by bisection (its bracket halves 200 times: to the last bit).
double pullout_reaching(const FibreMaterial& f, double embedment, double v, const Rising& r, double p) {
  if (p >= r.top) return r.end;
  const double vd = full_debonding_slip(f, embedment);
  if (v < vd) {
    const double d = f.diameter;
    const double at = (p * p / (0.5 * M_PI * M_PI * f.modulus * d * d * d) - f.debonding_energy) / f.friction_stress;
    return std::clamp(at, v, r.end);
  }
  double lo = v, hi = r.end;
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (sliding_force(f, embedment, mid) < p ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

double open_crack(const FibreMaterial& f, TwoSidedPullout& t, double w) {
  if (!(w >= 0) || !std::isfinite(w)) throw std::invalid_argument("open_crack: the opening must be finite, >= 0");
  double rest = w - t.pullout[0] - t.pullout[1];
  if (rest < 0) return t.force = 0.0;
  // Each piece ends where a side's resistance turns or the two meet: at most a handful per side. The force is the
  // sliding side's at the end of the last piece; where that ends on a turn, the value reached there (at v_d the
  // debonding branch of (5.1), before the drop).
  for (int piece = 0; rest > 0; ++piece) {
    if (piece > 32) throw std::logic_error("open_crack: the opening did not settle in 32 pieces");
    double r[2];
    Rising up[2];
    for (int i = 0; i < 2; ++i) {
      r[i] = pullout_resistance(f, t.embedment[i], t.pullout[i]);
      up[i] = rising_from(f, t.embedment[i], t.pullout[i]);
    }
    const bool rises[2] = {up[0].end > t.pullout[0], up[1].end > t.pullout[1]};
    const bool tie = std::abs(r[0] - r[1]) <= 1e-12 * std::max(r[0], r[1]);
    // The weaker side; at a tie the one whose resistance falls (it gives way at once), else the shorter.
    int weak = r[1] < r[0] ? 1 : 0;
    if (tie) weak = rises[0] != rises[1] ? (rises[0] ? 1 : 0) : (t.embedment[1] < t.embedment[0] ? 1 : 0);
    const int strong = 1 - weak;
    if (!rises[weak]) {  // it slides alone: its resistance only falls
      t.pullout[weak] += rest;
      t.force = pullout_resistance(f, t.embedment[weak], t.pullout[weak]);
      break;
    }
    if (!tie) {  // it slides alone until it resists as much as the other does, or its resistance turns
      const double v = pullout_reaching(f, t.embedment[weak], t.pullout[weak], up[weak], r[strong]);
      if (v - t.pullout[weak] > rest) {
        t.pullout[weak] += rest;
        t.force = pullout_resistance(f, t.embedment[weak], t.pullout[weak]);
        break;
      }
      rest -= v - t.pullout[weak];
      t.pullout[weak] = v;
      t.force = std::min(r[strong], up[weak].top);
      continue;
    }
    // Both slide at one force p, rising from r to the lower top; moved(p) grows with p.
    const double p1 = std::min(up[0].top, up[1].top);
    auto at = [&](int i, double p) { return pullout_reaching(f, t.embedment[i], t.pullout[i], up[i], p); };
    auto moved = [&](double p) { return at(0, p) - t.pullout[0] + at(1, p) - t.pullout[1]; };
    if (moved(p1) <= rest) {
      rest -= moved(p1);
      const double v0 = at(0, p1), v1 = at(1, p1);
      t.pullout[0] = v0, t.pullout[1] = v1;
      t.force = p1;
      continue;
    }
    // The split: the shorter side's share x of the rest, where both resist alike. h(x), the shorter's resistance
    // less the longer's, grows with x (both rise as they slide), and changes sign within the stretches: bisection.
    const int longer = t.embedment[1] > t.embedment[0] ? 1 : 0, shorter = 1 - longer;
    auto rising_value = [&](int i, double v) {
      return v >= up[i].end ? up[i].top : pullout_resistance(f, t.embedment[i], v);
    };
    const double vs = t.pullout[shorter], vl = t.pullout[longer], total = vs + vl + rest;
    auto h = [&](double x) { return rising_value(shorter, vs + x) - rising_value(longer, total - (vs + x)); };
    double lo = std::max(0.0, rest - (up[longer].end - vl)), hi = std::min(rest, up[shorter].end - vs);
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (h(mid) < 0 ? lo : hi) = mid;
    }
    t.pullout[shorter] = vs + hi;
    t.pullout[longer] = total - t.pullout[shorter];
    t.force = rising_value(shorter, t.pullout[shorter]);
    rest = 0;
  }
  return t.force;
}

double side_debonded_length(const FibreMaterial& f, double embedment, double v) {
  return v >= full_debonding_slip(f, embedment) ? embedment : debonded_length(f, v);
}

double bonded_stiffness(const FibreMaterial& f) { return f.modulus * 0.25 * M_PI * f.diameter; }

double unloading_stiffness(const FibreBridge& b) { return b.opening > 0 ? b.force / b.opening : 0.0; }

double bridge_force(const FibreMaterial& f, FibreBridge& b, double w, double phi) {
  if (b.ruptured) return 0.0;
  if (w < b.opening) return unloading_stiffness(b) * w;
  const double pulled = open_crack(f, b.sides, w) * snubbing_factor(f, phi);
  const double force = std::min(pulled, bonded_stiffness(f) * w);
  b.opening = w;
  if (force >= inclined_strength(f, phi) * 0.25 * M_PI * f.diameter * f.diameter) {
    b.ruptured = true;
    return b.force = 0.0;
  }
  return b.force = force;
}

}  // namespace mc::rigid_cell
