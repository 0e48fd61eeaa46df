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
  for (std::size_t s = 0; s < w.slot_count(); ++s) {
    const double f = w.slot_force(s).norm();
    if (f > 0) fc += f, ++nc;
  }
  if (nc == 0) return kInf;
  return (fp / w.particles.size()) / (fc / static_cast<double>(nc));
}

template <int D>
void set_radius(Particles<D>& p, int i, double r, double density) {
  p.radius[i] = r;
  p.mass[i] = density * Dim<D>::volume(r);
  p.inertia[i] = Dim<D>::inertia_factor * p.mass[i] * r * r;
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

  // Floaters: particles with fewer than D + 1 neighbours closer than 1e-3 R_min (touching, or bondable with a
  // small gap tolerance). Growing them until held (PFC) would press them into their neighbours by up to ~10 %
  // of a radius at this small isotropic stress, so they are counted and left as the jammed packing has them.
  int count_floaters() const {
    const auto& p = w_.particles;
    std::vector<int> n(p.size(), 0);
    for (const Pair& pr : candidate_pairs<D>(p.x, p.radius, 1e-3 * a_)) {
      const double g = (p.x[pr[1]] - p.x[pr[0]]).norm() - p.radius[pr[0]] - p.radius[pr[1]];
      if (g < 1e-3 * a_) ++n[pr[0]], ++n[pr[1]];
    }
    return static_cast<int>(std::count_if(n.begin(), n.end(), [](int c) { return c < D + 1; }));
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
      if constexpr (D == 3)
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
  if (!genesis.relieve()) {
    std::ostringstream m;
    m << "the genesis did not reach the isotropic stress " << s.stress << " Pa within 2 % in 30 rounds of radius "
      << "change (" << genesis.steps() << " steps; the mean wall stress is " << genesis.mean_stress() << " Pa)";
    throw InputError(m.str());
  }
  const int floaters = genesis.count_floaters();
  Packing<D> out = genesis.carve();
  if (report) {
    const auto count = static_cast<std::int64_t>(out.x.size());
    *report = {count, grown, genesis.porosity(volume), genesis.mean_stress(), floaters, genesis.steps()};
  }
  return out;
}

template Packing<2> dense_packing<2>(const DensePackingSpec<2>&, PackingReport*);
template Packing<3> dense_packing<3>(const DensePackingSpec<3>&, PackingReport*);

}  // namespace mc
