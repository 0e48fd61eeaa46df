#include "preprocess/dense_packing.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "contact_models/linear.hpp"
#include "engine/cell_grid.hpp"
#include "engine/errors.hpp"
#include "engine/world.hpp"

namespace mc {

namespace {

// Mean particle volume (area in 2D, t = 1 m) for radii uniform in [a, b]: E[πR²] and E[4πR³/3].
template <int D>
double mean_volume(double a, double b) {
  if constexpr (D == 2)
    return M_PI * (a * a + a * b + b * b) / 3.0;
  else
    return M_PI * (a + b) * (a * a + b * b) / 3.0;
}

template <int D>
double box_volume(const Vec<D>& lo, const Vec<D>& hi) {
  double v = 1;
  for (int k = 0; k < D; ++k) v *= hi[k] - lo[k];
  return v;
}

// Unbalanced force: mean |net force| on the particles over the mean |contact force| (PFC's equilibrium ratio).
template <int D>
double unbalanced_ratio(const World<D>& w) {
  double fp = 0, fc = 0;
  std::size_t nc = 0;
  for (const auto& f : w.particles.f) fp += f.norm();
  w.for_each_contact_force([&](const Vec<D>& force) {
    if (const double f = force.norm(); f > 0) fc += f, ++nc;
  });
  if (nc == 0) return kInf;
  return (fp / w.particles.size()) / (fc / static_cast<double>(nc));
}

template <int D>
void set_radius(Particles<D>& p, int i, double r, double density) {
  p.radius[i] = r;
  p.set_density(i, density);
}

// Throws InputError for a porosity out of range or a box less than 3 largest diameters wide.
template <int D>
void check_spec(const DensePackingSpec<D>& s) {
  const double b = s.radius_min * s.radius_ratio;
  if (!(s.porosity > 0.05 && s.porosity < 0.9))
    throw InputError("porosity " + std::to_string(s.porosity) + " is outside (0.05, 0.9)");
  for (int k = 0; k < D; ++k)
    if (s.hi[k] - s.lo[k] < 6 * b)
      throw InputError("the box must be at least 3 largest diameters wide in every direction");
}

// The particles placed without overlap at half size: a packing fraction of (1 − n)/2^D, which random placement
// reaches. The drawn radii, grown back to twice their size, are to fill exactly 1 − n of the box: they are
// scaled to that.
template <int D>
Packing<D> half_size_packing(const DensePackingSpec<D>& s, double volume) {
  const double a = s.radius_min, b = s.radius_min * s.radius_ratio;
  const auto count = static_cast<std::int64_t>(std::llround((1 - s.porosity) * volume / mean_volume<D>(a, b)));
  Packing<D> half = random_box_packing<D>(s.lo, s.hi, count, 0.5 * a, 0.5 * b, s.seed);
  double drawn = 0;
  for (double r : half.radius) drawn += Dim<D>::volume(2 * r);
  const double scale = std::pow((1 - s.porosity) * volume / drawn, 1.0 / D);
  for (double& r : half.radius) r *= scale;
  return half;
}

// What bounds a floater's cage: a particle (centre, radius; normal zero) or a box wall (a point of it, radius 0,
// the normal into the box).
template <int D>
struct Obstacle {
  Vec<D> centre;
  double radius;
  Vec<D> normal;
  // Distance from x to the obstacle's surface: how large a ball at x may be.
  double clearance(const Vec<D>& x) const {
    return normal.isZero() ? (x - centre).norm() - radius : normal.dot(x - centre);
  }
  // Gradient of the clearance.
  Vec<D> direction(const Vec<D>& x) const { return normal.isZero() ? Vec<D>((x - centre).normalized()) : normal; }
};

// The largest ball of the cage near x: centre and radius where D + 1 obstacles are at the same clearance r
// (Apollonius' problem), found by Newton's method on the D + 1 nearest, which are chosen anew from the centre
// found until no other obstacle is nearer. False when that does not settle (then x, r are left as they were).
template <int D>
bool largest_ball(const std::vector<Obstacle<D>>& cage, Vec<D>& x, double& r) {
  constexpr int M = D + 1;
  if (static_cast<int>(cage.size()) < M) return false;
  Vec<D> c = x;
  std::vector<int> order(cage.size());
  for (int round = 0; round < 10; ++round) {
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return cage[a].clearance(c) < cage[b].clearance(c); });
    double rc = cage[order[0]].clearance(c);
    for (int it = 0; it < 50; ++it) {
      Eigen::Matrix<double, M, M> jac;
      Eigen::Matrix<double, M, 1> res;
      for (int k = 0; k < M; ++k) {
        const Obstacle<D>& o = cage[order[k]];
        res[k] = o.clearance(c) - rc;
        jac.row(k) << o.direction(c).transpose(), -1.0;
      }
      const Eigen::Matrix<double, M, 1> step = jac.fullPivLu().solve(-res);
      if (!step.allFinite()) return false;
      c += step.template head<D>();
      rc += step[D];
      if (step.norm() <= 1e-12 * std::abs(rc)) break;
    }
    double nearest = kInf;
    for (const auto& o : cage) nearest = std::min(nearest, o.clearance(c));
    if (!(rc > 0)) return false;
    if (nearest >= rc * (1 - 1e-9)) {
      x = c, r = rc;
      return true;
    }
  }
  return false;
}

// The genesis: the half-size particles in a box of walls, with frictionless linear contacts of the material's
// contact modulus, grown to full size and brought to the isotropic stress asked for.
template <int D>
class Genesis {
 public:
  Genesis(const DensePackingSpec<D>& s, const Packing<D>& half)
      : s_(s), a_(s.radius_min), b_(s.radius_min * s.radius_ratio) {
    LinearParams lp;
    lp.modulus = s.modulus;
    lp.kn_ks_ratio = 1.0;
    lp.friction = 0.0;  // frictionless genesis: the packing densifies to its own jammed state
    w_.sets.push_back(std::make_unique<ContactSet<Linear, D>>(lp));
    w_.model_of = {{0}};
    for (std::size_t i = 0; i < half.x.size(); ++i) w_.particles.add(half.x[i], half.radius[i], s.density, 0);
    WallMaterial wm;
    wm.kn = wm.ks = Linear::ball_kn<D>(lp, 0.5 * (a_ + b_));
    add_box_walls(wm);
    w_.local_damping = 0.7;
    const Vec<D> size = s.hi - s.lo;
    w_.domain_lo = s.lo - size;
    w_.domain_hi = s.hi + size;
    w_.keep_contact_forces();  // the unbalanced-force ratio reads every contact's force
    w_.init();
  }

  // Grown back to full size in ten steps, each followed by some cycling: the overlaps stay moderate.
  void grow() {
    for (int g = 1; g <= 10; ++g) {
      scale_radii((0.5 + 0.05 * g) / (0.5 + 0.05 * (g - 1)));
      settle(1e-2, 300);
    }
    settle(1e-3, 20000);
  }

  // The isotropic stress is brought to σ0 by changing all radii uniformly, the walls staying put (Potyondy &
  // Cundall 2004): with linear contacts the stress follows the mean overlap, so each round removes the share
  // of it that is too much, and the packing settles again. The scale of the radii is bracketed: a scale that
  // left the stress above σ0 bounds it from above, one that left it below from below; the mean-overlap estimate
  // is taken when it falls inside the bracket, else its middle. False when 30 rounds do not reach σ0 ± 2 %.
  bool relieve() {
    const double mean_r = 0.5 * (a_ + b_);
    double scale_now = 1, scale_hi = kInf, scale_lo = 0;
    for (int round = 0; round <= 30; ++round) {
      const double sigma = mean_stress();
      if (std::abs(sigma - s_.stress) <= 0.02 * s_.stress) return true;
      if (round == 30) return false;
      (sigma > s_.stress ? scale_hi : scale_lo) = scale_now;
      // Overlap to remove per contact, ½ from each radius (negative: to add, when the packing came apart).
      const double u = mean_overlap();
      const double du = sigma > 0 ? u * (1 - s_.stress / sigma) : -1e-3 * mean_r;
      double next = scale_now * (1 - 0.5 * du / mean_r);
      if (!(next > scale_lo && next < scale_hi)) next = scale_lo > 0 ? 0.5 * (scale_lo + scale_hi) : 0.999 * scale_hi;
      scale_radii(next / scale_now);
      scale_now = next;
      settle(1e-2, 20000);
    }
    return false;
  }

  // Near neighbours (closer than 1e-3 R_min: touching, or bondable with a small gap tolerance) of each
  // particle, the floaters among them and the coordination numbers.
  ContactCensus census(int n_f) const {
    const std::vector<int> n = near_neighbours();
    ContactCensus c;
    std::int64_t all = 0, held = 0;
    for (int k : n) {
      all += k;
      if (k < n_f)
        ++c.floaters;
      else
        held += k;
    }
    const double count = static_cast<double>(n.size());
    c.floater_share = c.floaters / count;
    c.coordination = all / count;
    c.coordination_held = c.floaters < static_cast<int>(n.size()) ? held / (count - c.floaters) : 0.0;
    return c;
  }

  // Potyondy & Cundall 2004, genesis step 4 (floater elimination): each floater is enlarged until it touches
  // n_f ≤ D + 1 near neighbours, then the packing is cycled to equilibrium. Here a floater takes the largest
  // ball its cage holds (touching D + 1 of its neighbours and the box walls, without overlap), so the stress
  // of the packing stays σ0: growing it in place would press it into its nearest neighbours (by up to half a
  // radius in wide cages), and relieving that stress by shrinking all radii again opens as many new floaters
  // (measured: 9.5 % → 4 % after 12 rounds in 2D). Two passes (a neighbour grown in the first may have
  // closed a cage of the second); the settling that follows relaxes the packing a little further than
  // relieve() had (−4 % of σ0 in 2D), so the stress is brought back. Floaters touching a wall are left when
  // their cage is full (the wall is their third contact). Returns how many particles were grown; false in `ok`
  // when the stress is not brought back.
  int remove_floaters(int n_f, bool& ok) {
    std::vector<char> grown(w_.particles.size(), 0);
    for (int pass = 0; pass < 2; ++pass)
      if (fill_cages(n_f, grown) > 0) settle(1e-3, 2000);
    ok = relieve();
    return static_cast<int>(std::count(grown.begin(), grown.end(), 1));
  }

  double mean_stress() const {
    double st = 0;
    for (const auto& wl : w_.walls) st += wl.normal_stress() / (2 * D);
    return st;
  }

  // 1 − (particle volume) / (box volume).
  double porosity(double volume) const {
    double solids = 0;
    for (double r : w_.particles.radius) solids += Dim<D>::volume(r);
    return 1 - solids / volume;
  }

  // The particles, those outside the inscribed cylinder left out for a cylinder.
  Packing<D> carve() const {
    Packing<D> out;
    const Vec<D> centre = 0.5 * (s_.lo + s_.hi), size = s_.hi - s_.lo;
    const double rc = 0.5 * std::min(size[0], size[1]);
    for (int i = 0; i < w_.particles.size(); ++i) {
      const Vec<D>& x = w_.particles.x[i];
      if (s_.shape == DensePackingSpec<D>::Shape::Cylinder && (x - centre).template head<2>().norm() > rc) continue;
      out.x.push_back(x);
      out.radius.push_back(w_.particles.radius[i]);
    }
    return out;
  }

  std::int64_t steps() const { return steps_; }

 private:
  // Two walls per axis, each measuring its area between the walls of the other axes.
  void add_box_walls(const WallMaterial& wm) {
    for (int k = 0; k < D; ++k) {
      const Vec<D> e = Vec<D>::Unit(k);
      w_.walls.push_back(Wall<D>::plane(s_.lo, e));
      w_.walls.push_back(Wall<D>::plane(s_.hi, -e));
    }
    for (auto& wl : w_.walls) wl.material = wm;
    for (int k = 0; k < D; ++k)
      for (int j = 0; j < D; ++j)
        if (j != k)
          for (int side = 0; side < 2; ++side) w_.walls[2 * k + side].area_between.push_back({2 * j, 2 * j + 1});
  }

  // Cycled until the unbalanced force ratio is below `ratio` (looked at every 100 steps), or max_steps.
  void settle(double ratio, std::int64_t max_steps) {
    for (std::int64_t n = 0; n < max_steps; ++n) {
      w_.step();
      ++steps_;
      if (n % 100 == 99 && unbalanced_ratio(w_) < ratio) return;
    }
  }

  void scale_radii(double f) {
    for (int i = 0; i < w_.particles.size(); ++i) set_radius(w_.particles, i, w_.particles.radius[i] * f, s_.density);
    w_.init();  // radii changed: lists and timestep anew
  }

  // Near neighbours of each particle: other particles closer than 1e-3 R_min.
  std::vector<int> near_neighbours() const {
    const auto& p = w_.particles;
    std::vector<int> n(p.size(), 0);
    for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, kNear * a_))
      if (gap(pr[0], pr[1]) < kNear * a_) ++n[pr[0]], ++n[pr[1]];
    return n;
  }

  double gap(int i, int j) const {
    const auto& p = w_.particles;
    return (p.x[j] - p.x[i]).norm() - p.radius[i] - p.radius[j];
  }

  // One pass over the particles in order (deterministic): each with fewer than n_f near neighbours is moved
  // and grown to the largest ball of its cage, unless that ball is larger than the largest radius of the
  // packing (Potyondy & Cundall grow floaters, they do not make new grain sizes) or smaller than the floater.
  // Marks the grown ones; returns how many grew in this pass.
  int fill_cages(int n_f, std::vector<char>& grown) {
    auto& p = w_.particles;
    const double cap = *std::max_element(p.radius.begin(), p.radius.end());
    const std::vector<int> n = near_neighbours();
    std::vector<std::vector<int>> around(p.size());
    for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, 2 * cap))
      around[pr[0]].push_back(pr[1]), around[pr[1]].push_back(pr[0]);
    int count = 0;
    for (int i = 0; i < p.size(); ++i) {
      if (n[i] >= n_f) continue;
      std::vector<Obstacle<D>> cage;
      for (int j : around[i]) cage.push_back({p.x[j], p.radius[j], Vec<D>::Zero()});
      for (int k = 0; k < D; ++k) {
        cage.push_back({s_.lo, 0.0, Vec<D>::Unit(k)});
        cage.push_back({s_.hi, 0.0, -Vec<D>::Unit(k)});
      }
      Vec<D> x = p.x[i];
      double r = p.radius[i];
      if (!largest_ball(cage, x, r) || r > cap || r <= p.radius[i] || (x - p.x[i]).norm() > p.radius[i]) continue;
      p.x[i] = x;
      p.v[i].setZero();
      set_radius(p, i, r, s_.density);
      grown[i] = 1;
      ++count;
    }
    if (count > 0) w_.init();  // radii changed: lists and timestep anew
    return count;
  }

  double mean_overlap() const {
    const auto& p = w_.particles;
    double u = 0;
    int n = 0;
    for (const Pair& pr : w_.sets[0]->pairs()) {
      const double o = p.radius[pr[0]] + p.radius[pr[1]] - (p.x[pr[1]] - p.x[pr[0]]).norm();
      if (o > 0) u += o, ++n;
    }
    return n > 0 ? u / n : 0.0;
  }

  static constexpr double kNear = 1e-3;  // near neighbours: gap below kNear R_min

  const DensePackingSpec<D>& s_;
  const double a_, b_;  // R_min, R_max
  World<D> w_;
  std::int64_t steps_ = 0;
};

}  // namespace

template <int D>
Packing<D> dense_packing(const DensePackingSpec<D>& s, PackingReport* report) {
  check_spec(s);
  const double volume = box_volume<D>(s.lo, s.hi);
  Genesis<D> genesis(s, half_size_packing(s, volume));
  genesis.grow();
  const double grown = genesis.porosity(volume);
  const auto not_settled = [&](const std::string& when) {
    std::ostringstream m;
    m << "the genesis did not reach the isotropic stress " << s.stress << " Pa within 2 % in 30 rounds of radius "
      << "change" << when << " (" << genesis.steps() << " steps; the mean wall stress is " << genesis.mean_stress()
      << " Pa)";
    return InputError(m.str());
  };
  if (!genesis.relieve()) throw not_settled("");
  const int n_f = s.floater_contacts > 0 ? s.floater_contacts : D + 1;
  const ContactCensus before = genesis.census(n_f);
  bool relieved = true;
  const int floaters_grown = s.floater_contacts > 0 ? genesis.remove_floaters(n_f, relieved) : 0;
  if (!relieved) throw not_settled(" after the floaters were grown");
  const ContactCensus after = s.floater_contacts > 0 ? genesis.census(n_f) : before;
  Packing<D> out = genesis.carve();
  if (report) {
    const auto count = static_cast<std::int64_t>(out.x.size());
    *report = {count,  grown, genesis.porosity(volume), genesis.mean_stress(), n_f,
               before, after, floaters_grown,           genesis.steps()};
  }
  return out;
}

template Packing<2> dense_packing<2>(const DensePackingSpec<2>&, PackingReport*);
template Packing<3> dense_packing<3>(const DensePackingSpec<3>&, PackingReport*);

}  // namespace mc
