#include "preprocess/aggregate_placement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <utility>

#include "engine/errors.hpp"
#include "preprocess/convex_body.hpp"
#include "preprocess/status_grid.hpp"

namespace mc {

namespace {

// Relocations by translation after an overlap before a fresh position is drawn.
constexpr int kShifts = 3;

template <int D>
double measure(const Vec<D>& lo, const Vec<D>& hi) {
  double m = 1;
  for (int k = 0; k < D; ++k) m *= hi[k] - lo[k];
  return m;
}

template <int D>
ConvexShape<D> random_turn(const ConvexShape<D>& s, RandomStream& rng) {
  ConvexShape<D> out = s;
  if constexpr (D == 2)
    rotate(out, rng.uniform(0, 2 * M_PI));
  else
    rotate(out, random_rotation(rng));
  return out;
}

template <int D>
Vec<D> random_direction(RandomStream& rng) {
  Vec<D> w;
  do {
    for (int k = 0; k < D; ++k) w[k] = rng.uniform(-1, 1);
  } while (w.squaredNorm() > 1 || w.squaredNorm() < 1e-4);
  return w.normalized();
}

template <int D>
void check_spec(const PlacementSpec<D>& s) {
  std::ostringstream m;
  for (int k = 0; k < D; ++k)
    if (!(s.hi[k] > s.lo[k]) || !std::isfinite(s.lo[k]) || !std::isfinite(s.hi[k])) {
      m << "aggregate placement: the domain must have hi > lo along every axis (axis " << k << ": " << s.lo[k] << " to "
        << s.hi[k] << ")";
      throw InputError(m.str());
    }
  if (!(s.fraction > 0 && s.fraction < 1)) {
    m << "aggregate placement: fraction = " << s.fraction << " must be in (0, 1)";
    throw InputError(m.str());
  }
  check_grading(s.grading);
  if (!(s.cells_per_dmin >= 5 && s.cells_per_dmin <= 10)) {
    m << "aggregate placement: cells_per_dmin = " << s.cells_per_dmin
      << " must be in [5, 10] (Tang 4.6: grid cell between D_min/10 and D_min/5)";
    throw InputError(m.str());
  }
  if (s.attempts < 1) throw InputError("aggregate placement: attempts must be at least 1");
  for (const auto& b : s.keep_out_boxes)
    for (int k = 0; k < D; ++k)
      if (!(b.hi[k] > b.lo[k]))
        throw InputError("aggregate placement: a keep-out box must have hi > lo along every axis");
  for (const auto& b : s.keep_out_balls)
    if (!(b.radius > 0)) throw InputError("aggregate placement: a keep-out ball must have a positive radius");
}

// What a test found: nothing (placed), a wall (shift back in), or an obstacle to move away from.
template <int D>
struct Verdict {
  enum Kind { ok, wall, obstacle, hopeless } kind = ok;
  Vec<D> move = Vec<D>::Zero();  // wall: the shift back in; obstacle: its centre
};

// An aggregate in one orientation. Checks 1 and 2 need only its vertices (about the centroid) and their bounding
// box lo–hi; the exact body, needed for the rest, is built for the first position that gets that far and then
// only translated.
template <int D>
struct Trial {
  explicit Trial(ConvexShape<D> turned) : shape(std::move(turned)), lo(shape.v[0]), hi(shape.v[0]) {
    for (const auto& x : shape.v) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }

  // The exact body at position c, written into `out`.
  const Body<D>& body_at(const Vec<D>& c, Body<D>& out) {
    if (!built) {
      body = make_body(shape);
      built = true;
    }
    move_body(body, c, out);
    return out;
  }

  ConvexShape<D> shape;
  Vec<D> lo, hi;
  Body<D> body;
  bool built = false;
};

// The take and place of Tang §4.2: the layout being built (status grid, bins, placed aggregates), the free cells
// positions are drawn from, the exact bodies of the keep-out zones and of the placed aggregates, and the one
// random stream the whole placement draws from, in a fixed order.
template <int D>
class Placer {
 public:
  explicit Placer(const PlacementSpec<D>& spec) : spec_(spec), rng_(spec.seed) {
    out_.lo = spec.lo;
    out_.hi = spec.hi;
    domain_ = measure<D>(spec.lo, spec.hi);
    for (const auto& r : spec.grading.ranges) d_min_ = std::min(d_min_, r.lo);
    out_.ranges.resize(spec.grading.ranges.size());
    for (std::size_t k = 0; k < spec.grading.ranges.size(); ++k) {
      const auto& r = spec.grading.ranges[k];
      out_.ranges[k].lo = r.lo;
      out_.ranges[k].hi = r.hi;
      out_.ranges[k].target_share = r.share;
      out_.ranges[k].target_fraction = r.share * spec.fraction;
    }
    out_.target_fraction = spec.fraction;
  }

  // Stage 1, the aggregate database: a random shape for each size fill_grading draws, centred on its centroid.
  std::vector<SizedAggregate> make_database() {
    return fill_grading(
        spec_.grading, spec_.fraction * domain_, D,
        [&](double d) {
          ConvexShape<D> s = random_shape<D>(d, spec_.shape, rng_);
          translate(s, Vec<D>(-centroid(s)));
          made_.push_back(std::move(s));
          return content(made_.back());
        },
        rng_, spec_.size_draw, spec_.fuller_n);
  }

  // The background grid, Tang (4.6): cells of D_min / cells_per_dmin, rounded per axis to fit the domain.
  void build_grid() {
    StatusGrid<D>& grid = out_.grid;
    grid.lo = spec_.lo;
    const double h0 = d_min_ / spec_.cells_per_dmin;
    double cells = 1;
    for (int k = 0; k < D; ++k) {
      const double len = spec_.hi[k] - spec_.lo[k];
      cells *= std::max(1.0, std::ceil(len / h0));
    }
    if (cells > 2147483647.0) {
      std::ostringstream m;
      m << "aggregate placement: the background grid would have " << cells << " cells (cell D_min/"
        << spec_.cells_per_dmin << " = " << h0 << "); enlarge D_min or shrink the domain";
      throw InputError(m.str());
    }
    for (int k = 0; k < D; ++k) {
      const double len = spec_.hi[k] - spec_.lo[k];
      grid.n[k] = static_cast<int>(std::max(1.0, std::ceil(len / h0)));
      grid.h[k] = len / grid.n[k];
    }
    grid.status.assign(grid.cells(), 0);
  }

  // Keep-out zones: exact bodies, and the cells whose centres they hold marked, so no position is drawn there.
  void mark_keep_out() {
    StatusGrid<D>& grid = out_.grid;
    for (const auto& b : spec_.keep_out_boxes) keep_bodies_.push_back(make_body(box_shape(b)));
    const std::int64_t n_cells = grid.cells();
    for (std::int64_t c = 0; c < n_cells; ++c) {
      const Vec<D> x = grid.centre(c);
      bool kept = false;
      for (const auto& b : keep_bodies_) kept = kept || inside(b, x);
      for (const auto& b : spec_.keep_out_balls) kept = kept || (x - b.centre).norm() <= b.radius;
      if (kept) grid.status[c] = StatusGrid<D>::kKeepOut;
    }
  }

  // The free cells, for drawing positions: swap-removed as they are taken.
  void list_free_cells() {
    const StatusGrid<D>& grid = out_.grid;
    const std::int64_t n_cells = grid.cells();
    where_.assign(n_cells, -1);
    free_cells_.reserve(n_cells);
    for (std::int64_t c = 0; c < n_cells; ++c)
      if (grid.status[c] == 0) {
        where_[c] = static_cast<std::int32_t>(free_cells_.size());
        free_cells_.push_back(static_cast<std::int32_t>(c));
      }
  }

  // Bins of bounding boxes (about 2 D_min, at most 2²⁰ bins), for the exact tests and aggregate_at.
  void build_bins() {
    double b = 2 * d_min_, count;
    do {
      count = 1;
      for (int k = 0; k < D; ++k) count *= std::max(1.0, std::floor((spec_.hi[k] - spec_.lo[k]) / b));
      if (count > (1 << 20)) b *= 1.25;
    } while (count > (1 << 20));
    std::int64_t total = 1;
    for (int k = 0; k < D; ++k) {
      const double len = spec_.hi[k] - spec_.lo[k];
      out_.bins_n[k] = static_cast<int>(std::max(1.0, std::floor(len / b)));
      out_.bin_size[k] = len / out_.bins_n[k];
      total *= out_.bins_n[k];
    }
    out_.bins.assign(total, {});
  }

  // Stages 2–4 for one aggregate, counted in its size range.
  void place(const SizedAggregate& sa) {
    RangeOutcome& ro = out_.ranges[sa.range];
    if (try_place(sa)) {
      ++ro.placed;
      ro.achieved_fraction += sa.content / domain_;
    } else {
      ++ro.failed;
    }
  }

  // The fractions reached, per range and in all.
  AggregateLayout<D> outcome() {
    double total = 0;
    bool all = true;
    for (const auto& r : out_.ranges) {
      total += r.achieved_fraction;
      all = all && r.failed == 0;
    }
    for (auto& r : out_.ranges) r.achieved_share = total > 0 ? r.achieved_fraction / total : 0;
    out_.achieved_fraction = total;
    out_.reached = all;
    return std::move(out_);
  }

 private:
  // Up to `attempts` fresh positions (a random point of a random free cell), each with a random orientation;
  // placed at the first that passes.
  bool try_place(const SizedAggregate& sa) {
    ConvexShape<D> local = made_[sa.made];
    if (sa.scale != 1) scale(local, sa.scale);
    for (int a = 0; a < spec_.attempts && !free_cells_.empty(); ++a) {
      const std::int64_t cell = free_cells_[rng_.below(free_cells_.size())];
      Vec<D> c = out_.grid.centre(cell);
      for (int k = 0; k < D; ++k) c[k] += rng_.uniform(-0.5, 0.5) * out_.grid.h[k];
      Trial<D> trial(random_turn<D>(local, rng_));
      if (try_position(trial, c, sa.size)) {
        record(trial.shape, c, sa);
        return true;
      }
    }
    return false;
  }

  // One fresh position c, tested; after a wall it is shifted back in, after an obstacle relocated by translation
  // away from it by a random distance up to half the aggregate's size, up to kShifts times.
  bool try_position(Trial<D>& trial, Vec<D>& c, double size) {
    for (int shift = 0; shift <= kShifts; ++shift) {
      ++out_.attempts;
      const Verdict<D> v = test(trial, c);
      if (v.kind == Verdict<D>::ok) return true;
      if (v.kind == Verdict<D>::hopeless) return false;
      if (v.kind == Verdict<D>::wall) {
        c += v.move;
        continue;
      }
      Vec<D> away = c - v.move;
      away = away.norm() > 1e-9 * size ? Vec<D>(away.normalized()) : random_direction<D>(rng_);
      c += rng_.uniform(0, 0.5) * size * away;
    }
    return false;
  }

  // The five checks of the header, in order; the exact body is built only for positions that pass 1 and 2.
  Verdict<D> test(Trial<D>& trial, const Vec<D>& c) {
    if (const Verdict<D> v = inside_domain(trial, c); v.kind != Verdict<D>::ok) return v;
    if (const std::int32_t s = hit_at_points(trial.shape.v, c)) return obstacle(s);
    const Body<D>& b = trial.body_at(c, body_);
    if (const Verdict<D> v = clear_of_keep_out(b); v.kind != Verdict<D>::ok) return v;
    std::int32_t hit = 0;
    if (!rasterise(out_.grid, b, covered_, hit)) {  // check 4
      if (hit > 0) return obstacle(hit);
      return Verdict<D>{Verdict<D>::obstacle, c + random_direction<D>(rng_)};
    }
    if (const int id = clash_with_neighbours(b)) return obstacle(id);
    return {};
  }

  Verdict<D> obstacle(int id) const { return Verdict<D>{Verdict<D>::obstacle, out_.aggregates[id - 1].centroid}; }

  // Check 1: inside the domain, or the shift back in by what sticks out (hopeless when wider than the domain).
  Verdict<D> inside_domain(const Trial<D>& trial, const Vec<D>& c) const {
    Verdict<D> v;
    for (int k = 0; k < D; ++k) {
      const double under = spec_.lo[k] - (trial.lo[k] + c[k]), over = trial.hi[k] + c[k] - spec_.hi[k];
      if (under > 0 && over > 0) return Verdict<D>{Verdict<D>::hopeless, {}};
      const double slack = 1e-12 * (spec_.hi[k] - spec_.lo[k]);
      if (under > 0) v.move[k] = under + slack;
      if (over > 0) v.move[k] = -over - slack;
    }
    if (v.move != Vec<D>::Zero()) v.kind = Verdict<D>::wall;
    return v;
  }

  // Check 2, initial determination: the id of a placed aggregate that holds the centroid, a vertex or a midpoint
  // between them (the status matrix's answer, confirmed exactly); 0 for none.
  std::int32_t hit_at_points(const std::vector<Vec<D>>& tv, const Vec<D>& c) const {
    std::int32_t s = held_by(c);
    for (std::size_t i = 0; i < tv.size() && s == 0; ++i) {
      s = held_by(Vec<D>(tv[i] + c));
      if (s == 0) s = held_by(Vec<D>(0.5 * tv[i] + c));
    }
    return s;
  }

  std::int32_t held_by(const Vec<D>& x) const {
    const std::int32_t s = out_.grid.at(x);
    return s > 0 && inside(placed_bodies_[s - 1], x) ? s : 0;
  }

  // Check 3: the keep-out zones, exactly.
  Verdict<D> clear_of_keep_out(const Body<D>& b) const {
    for (const auto& k : keep_bodies_)
      if (!separated(b, k)) return Verdict<D>{Verdict<D>::obstacle, Vec<D>(0.5 * (k.lo + k.hi))};
    for (const auto& k : spec_.keep_out_balls)
      if (distance(b, k.centre) < k.radius) return Verdict<D>{Verdict<D>::obstacle, k.centre};
    return {};
  }

  // Check 5: exact separating-axis tests against the placed aggregates whose bins the bounding box meets, each
  // looked at once per test (stamped with its number), so no overlap slips between grid nodes; the id of the
  // first that overlaps, 0 for none.
  int clash_with_neighbours(const Body<D>& b) {
    ++test_no_;
    int clash = 0;
    for_bins_of(b.lo, b.hi, [&](const std::vector<int>& ids) {
      for (int id : ids) {
        if (clash || stamp_[id - 1] == test_no_) continue;
        stamp_[id - 1] = test_no_;
        if (!separated(b, placed_bodies_[id - 1])) clash = id;
      }
    });
    return clash;
  }

  // f(bin) for each bin that the box lo–hi meets.
  template <class F>
  void for_bins_of(const Vec<D>& lo, const Vec<D>& hi, F&& f) {
    std::array<int, D> b0, b1;
    for (int k = 0; k < D; ++k) {
      b0[k] = std::clamp(static_cast<int>(std::floor((lo[k] - spec_.lo[k]) / out_.bin_size[k])), 0, out_.bins_n[k] - 1);
      b1[k] = std::clamp(static_cast<int>(std::floor((hi[k] - spec_.lo[k]) / out_.bin_size[k])), 0, out_.bins_n[k] - 1);
    }
    std::array<int, 3> i{0, 0, 0};
    const int z0 = D == 3 ? b0[D - 1] : 0, z1 = D == 3 ? b1[D - 1] : 0;
    for (i[2] = z0; i[2] <= z1; ++i[2])
      for (i[1] = b0[1]; i[1] <= b1[1]; ++i[1])
        for (i[0] = b0[0]; i[0] <= b1[0]; ++i[0]) {
          std::int64_t idx = i[0] + static_cast<std::int64_t>(out_.bins_n[0]) * i[1];
          if constexpr (D == 3) idx += static_cast<std::int64_t>(out_.bins_n[0]) * out_.bins_n[1] * i[2];
          f(out_.bins[idx]);
        }
  }

  // The aggregate passed at c (body_ holds it there): its id written into the cells it covers (Tang 4.5), which
  // leave the free cells, and into the bins its bounding box meets.
  void record(const ConvexShape<D>& turned, const Vec<D>& c, const SizedAggregate& sa) {
    const int id = static_cast<int>(out_.aggregates.size()) + 1;
    for (std::int32_t cc : covered_) {
      out_.grid.status[cc] = id;
      const std::int32_t w = where_[cc];
      if (w >= 0) {
        const std::int32_t last = free_cells_.back();
        free_cells_[w] = last;
        where_[last] = w;
        free_cells_.pop_back();
        where_[cc] = -1;
      }
    }
    PlacedAggregate<D> pa;
    pa.shape = turned;
    translate(pa.shape, c);
    pa.centroid = c;
    pa.lo = body_.lo;
    pa.hi = body_.hi;
    pa.size = sa.size;
    pa.content = sa.content;
    pa.range = sa.range;
    out_.aggregates.push_back(std::move(pa));
    placed_bodies_.push_back(body_);
    stamp_.push_back(0);
    for_bins_of(body_.lo, body_.hi, [&](std::vector<int>& ids) { ids.push_back(id); });
  }

  const PlacementSpec<D>& spec_;
  RandomStream rng_;
  AggregateLayout<D> out_;
  double domain_ = 0, d_min_ = kInf;
  std::vector<ConvexShape<D>> made_;              // the aggregate database, as fill_grading made it
  std::vector<Body<D>> keep_bodies_;              // the keep-out boxes
  std::vector<std::int32_t> free_cells_, where_;  // where_[cell]: its index in free_cells_, −1 once taken
  std::vector<Body<D>> placed_bodies_;            // per aggregate id − 1
  std::vector<int> stamp_;                        // per aggregate: the last check 5 that looked at it
  int test_no_ = 0;
  std::vector<std::int32_t> covered_;  // the cells of the last body rasterised
  Body<D> body_;                       // the body of the last position tested
};

}  // namespace

template <int D>
int AggregateLayout<D>::status_at(const Vec<D>& x) const {
  return std::max(0, grid.at(x));
}

template <int D>
int AggregateLayout<D>::aggregate_at(const Vec<D>& x) const {
  std::int64_t idx = 0, stride = 1;
  for (int k = 0; k < D; ++k) {
    if (!(x[k] >= lo[k] && x[k] <= hi[k])) return 0;  // every aggregate lies in the domain
    const double f = std::floor((x[k] - lo[k]) / bin_size[k]);
    idx += static_cast<std::int64_t>(std::clamp(f, 0.0, bins_n[k] - 1.0)) * stride;
    stride *= bins_n[k];
  }
  for (int id : bins[idx]) {
    const auto& a = aggregates[id - 1];
    bool in_box = true;
    for (int k = 0; k < D; ++k) in_box = in_box && x[k] >= a.lo[k] && x[k] <= a.hi[k];
    if (in_box && contains(a.shape, x)) return id;
  }
  return 0;
}

template <int D>
AggregateLayout<D> place_aggregates(const PlacementSpec<D>& spec) {
  check_spec(spec);
  Placer<D> placer(spec);
  const std::vector<SizedAggregate> sized = placer.make_database();  // stage 1
  placer.build_grid();
  placer.mark_keep_out();
  placer.list_free_cells();
  placer.build_bins();
  for (const SizedAggregate& sa : sized) placer.place(sa);  // stages 2–4, largest first
  return placer.outcome();
}

template struct AggregateLayout<2>;
template struct AggregateLayout<3>;
template AggregateLayout<2> place_aggregates<2>(const PlacementSpec<2>&);
template AggregateLayout<3> place_aggregates<3>(const PlacementSpec<3>&);

}  // namespace mc
