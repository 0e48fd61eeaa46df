// The geometry of one ball–ball or ball–wall contact from the particles' current state (Tang 3.1–3.6): what the
// contact sets hand their models, and the lever arms from each centre to the contact point.
#pragma once
#include "engine/contact_geometry.hpp"
#include "engine/particles.hpp"
#include "engine/wall.hpp"

namespace mc {

// Particles i (A) and j (B); ca, cb: from each centre to the contact point.
template <int D>
[[gnu::always_inline]] inline ContactGeometry<D> ball_geometry(const Particles<D>& p, int i, int j, double dt,
                                                               Vec<D>& ca, Vec<D>& cb) {
  ContactGeometry<D> g;
  const Vec<D> d = p.x[j] - p.x[i];
  const double dist = d.norm();
  g.n = d * (1.0 / dist);
  g.overlap = p.radius[i] + p.radius[j] - dist;
  ca = (p.radius[i] - 0.5 * g.overlap) * g.n;  // centre of A to the contact point, Tang (3.4)
  cb = ca - d;                                 // centre of B to the contact point
  g.v_rel = (p.v[j] + Dim<D>::cross(p.w[j], cb)) - (p.v[i] + Dim<D>::cross(p.w[i], ca));
  g.w_rel = p.w[j] - p.w[i];
  if constexpr (D == 3)
    g.spin_n = 0.5 * (p.w[i] + p.w[j]).dot(g.n);
  else
    g.spin_n = 0;
  g.r_a = p.radius[i];
  g.r_b = p.radius[j];
  g.m_a = p.mass[i];
  g.m_b = p.mass[j];
  g.k_a = p.stiffness[i];
  g.k_b = p.stiffness[j];
  g.dt = dt;
  return g;
}

// The wall (A) and particle j (B); cw: the contact point about the wall origin, cb: from the centre to it.
template <int D>
inline ContactGeometry<D> wall_geometry(const Particles<D>& p, const Wall<D>& w, int j, double dt, Vec<D>& cw,
                                        Vec<D>& cb) {
  ContactGeometry<D> g;
  const Vec<D> c = w.closest(p.x[j]);
  const Vec<D> d = p.x[j] - c;
  const double dist = d.norm();
  g.n = dist > 0 ? Vec<D>(d / dist) : w.normal;
  g.overlap = p.radius[j] - dist;               // Tang (3.3), ball–wall
  cb = -(p.radius[j] - 0.5 * g.overlap) * g.n;  // Tang (3.4)
  cw = p.x[j] + cb - w.origin;                  // contact point about the wall origin
  g.v_rel = p.v[j] + Dim<D>::cross(p.w[j], cb) - w.velocity;
  g.w_rel = p.w[j];
  if constexpr (D == 3)
    g.spin_n = 0.5 * p.w[j].dot(g.n);
  else
    g.spin_n = 0;
  g.r_a = kInf;
  g.r_b = p.radius[j];
  g.m_a = 0;
  g.m_b = p.mass[j];
  g.k_a = 1;
  g.k_b = p.stiffness[j];
  g.dt = dt;
  return g;
}

}  // namespace mc
