// The explicit particle world as a System (engine/system.hpp): built from a scene (scene/build_world.hpp), with
// the histories, the measurement regions and the crack log the scene declares.
#pragma once
#include "engine/system.hpp"
#include "engine/world.hpp"
#include "scene/build_world.hpp"
#include "scene/histories.hpp"
#include "scene/scene.hpp"

namespace mc {

template <int D>
class ExplicitSystem final : public System {
 public:
  // Builds the world (a generated specimen is generated here). The scene must outlive the system. With an
  // exchange of more than one process, every process builds the whole world and splits it once it starts or is
  // restored (World::split): the processes then step, observe and save together, and process 0 gets the frames
  // and the checkpoints. The exchange must outlive the system. imbalance_limit: World::imbalance_limit.
  explicit ExplicitSystem(const Scene& scene, const Exchange* exchange = nullptr, double imbalance_limit = 0);
  ExplicitSystem(const ExplicitSystem&) = delete;  // the history samplers point into it
  ExplicitSystem& operator=(const ExplicitSystem&) = delete;

  int dimension() const override { return D; }
  void start() override;
  void step() override;
  std::int64_t step_count() const override { return world_.step_count; }
  double time() const override { return world_.time; }
  double timestep() const override { return world_.dt; }
  void check_stability() const override { world_.check_stability(); }
  const std::vector<Series>& histories() const override { return series_; }
  void before_row() override;
  SpecimenData specimen() const override;
  void frame(std::vector<double>& x, std::vector<double>& v, std::vector<double>& force) const override;
  ContactFrame contact_frame() const override;
  std::vector<std::string> crack_models() const override;
  std::size_t crack_count() const override { return world_.cracks.size(); }
  CrackRows cracks(std::size_t first) const override;
  void save(Archive& a) const override;
  void restore(const Archive& a) override;
  std::string balance_report() const override;

  const World<D>& world() const { return world_; }
  const SpecimenInfo& info() const { return info_; }

 private:
  void check_probes() const;
  void install_bonds();
  bool splits() const { return exchange_ && exchange_->size() > 1; }
  // The whole world at the start (or at a restore), then split: the whole view starts as a copy of it.
  void split();
  std::vector<std::int64_t> own_counts() const;

  const Scene& scene_;
  const Exchange* exchange_;
  SpecimenInfo info_;
  World<D> world_;
  Observers<D> obs_;
  // A split world's whole view of what groups, probes and analyses read (their particles by whole-world index),
  // brought up to date before each row (before_row), and its specimen as it started.
  Particles<D> view_;
  std::vector<OpeningGauge<D>> view_gauges_;
  SpecimenData specimen_;
  std::vector<std::int64_t> split_counts_;  // the particles each process owned when the world was split
  std::vector<Series> series_;
};

}  // namespace mc
