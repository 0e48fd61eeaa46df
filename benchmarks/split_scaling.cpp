// One bonded 3D block split across the ranks of an MPI launch (World::split), timed: the cost per particle-step of
// the whole machine, the share of each rank's wall time spent exchanging (ghost motion, migration, the step's
// agreement), and each rank's own and ghost particles. Launched once per layout, e.g.
//   mpirun -np 2 build/benchmarks/split_scaling --threads 1      (2 ranks × 1 thread)
//   build/benchmarks/split_scaling --threads 2                   (1 rank × 2 threads: the whole world, not split)
// It prints one row of the table in README ("One specimen across ranks"). The block is the bonded-scaling one of
// `throughput` (parallel bonds that do not break, the particles near the faces held); with --specimen n10k (or
// n50k) and --model parallel (or cpm, linear), the shared specimen loaded as `throughput` loads it.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "benchmarks/bonded_block.hpp"
#include "benchmarks/options.hpp"
#include "benchmarks/run_timing.hpp"
#include "benchmarks/throughput_shared.hpp"
#include "benchmarks/throughput_world.hpp"
#include "studies/ranks.hpp"

using namespace mc;
using namespace mc::bench;

namespace {

// The launch's exchange, with the wall time spent in it and the bytes this rank sent to the others.
class TimedExchange final : public Exchange {
 public:
  explicit TimedExchange(const Exchange& inner) : inner_(inner) {}
  int rank() const override { return inner_.rank(); }
  int size() const override { return inner_.size(); }
  std::vector<Bytes> all_to_all(const std::vector<Bytes>& out) const override {
    count_sent(out);
    return timed([&] { return inner_.all_to_all(out); });
  }
  std::vector<Bytes> swap(const std::vector<Bytes>& out, const std::vector<std::size_t>& in_sizes) const override {
    count_sent(out);
    return timed([&] { return inner_.swap(out, in_sizes); });
  }
  std::vector<Bytes> all_gather(const Bytes& mine) const override {
    return timed([&] { return inner_.all_gather(mine); });
  }
  void max(std::vector<double>& v) const override {
    timed([&] { return inner_.max(v), 0; });
  }
  void sum(std::vector<std::int64_t>& v) const override {
    timed([&] { return inner_.sum(v), 0; });
  }
  mutable double seconds = 0, sent = 0;

 private:
  template <class F>
  std::invoke_result_t<F&> timed(F&& f) const {
    const auto t0 = Clock::now();
    auto result = f();
    seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    return result;
  }
  void count_sent(const std::vector<Bytes>& out) const {
    for (const auto& b : out) sent += static_cast<double>(b.size());
  }
  const Exchange& inner_;
};

// The shared specimen `name` (benchmarks/specimens) under the shared loading, with the README's step when the
// engine accepts it, as `throughput` runs it.
World<3> shared(const std::string& name, const std::string& model) {
  Material mat;
  mat.bonded = model == "parallel";
  mat.cpm = model == "cpm";
  const SphereList<3> s = read_in_morton_order(std::string(MESOCRACK_SPECIMEN_DIR) + "/" + name + ".spheres");
  const SharedSize size = shared_size(s);
  std::vector<int> top;
  try {
    return shared_world(s, mat, size.dt_readme(mat), size.height, &top);
  } catch (const InputError&) {
    top.clear();
    return shared_world(s, mat, 0.0, size.height, &top);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Ranks::start(&argc, &argv);
  const Ranks& ranks = Ranks::world();
  int target = 1000000, threads = 1, steps = 200;
  std::string specimen, model = "parallel";
  CLI::App app{"split_scaling: a bonded block (or a shared specimen) split across the ranks of a launch, timed"};
  app.add_option("--particles", target, "the bonded block's particles")->check(CLI::Range(1000, 100000000));
  app.add_option("--threads", threads, "OpenMP threads per rank")->check(CLI::Range(1, 256));
  app.add_option("--steps", steps, "timed steps")->check(CLI::Range(1, 1000000));
  app.add_option("--specimen", specimen, "a shared specimen instead of the block")
      ->check(CLI::IsMember({"n10k", "n50k"}));
  app.add_option("--model", model, "the shared specimen's contacts")
      ->check(CLI::IsMember({"parallel", "cpm", "linear"}));
  if (const auto code = read_options(app, argc, argv, "split_scaling", ranks.root())) return *code;
  omp_set_num_threads(threads);
  World<3> w = specimen.empty() ? bonded_block(target) : shared(specimen, model);
  const int n = w.particles.size();
  const RanksExchange launch(ranks);
  const TimedExchange exchange(launch);
  if (ranks.size() > 1) w.split(exchange);
  for (int s = 0; s < 5; ++s) w.step();
  exchange.seconds = exchange.sent = 0;
  const std::int64_t rebuilds = w.rebuilds;
  const auto t0 = Clock::now();
  for (int s = 0; s < steps; ++s) w.step();
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  // Every rank's figures to the root: own, held, wall, exchange seconds, bytes sent per step.
  const std::vector<double> mine{double(w.own_count()), double(w.held_count()), wall, exchange.seconds,
                                 exchange.sent / steps};
  // What leaves the split world whole, as the run command writes it: a checkpoint gathered on the root (the whole
  // world's archive; whole, the plain save) and a frame's positions, velocities and forces gathered there.
  const auto c0 = Clock::now();
  Archive checkpoint;
  w.save(checkpoint);
  const auto c1 = Clock::now();
  const auto frame = w.gather_whole({&w.particles.x, &w.particles.v, &w.particles.f});
  const auto c2 = Clock::now();
  std::size_t archive_bytes = 0;
  for (const auto& [k, v] : checkpoint.reals) archive_bytes += v.size() * sizeof(double);
  for (const auto& [k, v] : checkpoint.bytes) archive_bytes += v.size();
  if (ranks.root())
    std::fprintf(stderr, "checkpoint gathered in %.3f s (%.1f MB), frame gathered in %.3f s (%zu particles)\n",
                 std::chrono::duration<double>(c1 - c0).count(), archive_bytes / 1e6,
                 std::chrono::duration<double>(c2 - c1).count(), frame[0].size());
  Bytes b;
  for (double x : mine) put_bytes(b, x);
  const auto all = launch.all_gather(b);
  if (!ranks.root()) return 0;
  double slowest = 0, share_max = 0, ghost_max = 0, sent_max = 0;
  std::string own;
  for (const Bytes& r : all) {
    std::size_t at = 0;
    const double o = take_bytes<double>(r, at), h = take_bytes<double>(r, at), t = take_bytes<double>(r, at),
                 c = take_bytes<double>(r, at), s = take_bytes<double>(r, at);
    slowest = std::max(slowest, t);
    share_max = std::max(share_max, c / t);
    ghost_max = std::max(ghost_max, (h - o) / o);
    sent_max = std::max(sent_max, s);
    own += (own.empty() ? "" : " / ") + std::to_string(static_cast<long>(o));
  }
  std::printf("| %d × %d | %d | %.0f | %.1f | %.3f | %.1f %% | %s | %.1f %% | %.0f | %lld |\n", ranks.size(), threads,
              n, 1e9 * slowest / (static_cast<double>(n) * steps) * ranks.size() * threads,
              1e9 * slowest / (static_cast<double>(n) * steps), slowest / steps * 1e3, 100 * share_max, own.c_str(),
              100 * ghost_max, sent_max / 1024, static_cast<long long>(w.rebuilds - rebuilds));
  std::fprintf(stderr, "%s, %d steps\n", specimen.empty() ? "bonded block" : (specimen + ", " + model).c_str(), steps);
  return 0;
}
