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
  // Builds the world (a generated specimen is generated here). The scene must outlive the system.
  explicit ExplicitSystem(const Scene& scene);
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
  SpecimenData specimen() const override;
  void frame(std::vector<double>& x, std::vector<double>& v, std::vector<double>& force) const override;
  std::vector<std::string> crack_models() const override;
  std::size_t crack_count() const override { return world_.cracks.size(); }
  CrackRows cracks(std::size_t first) const override;
  void save(Archive& a) const override;
  void restore(const Archive& a) override;

  const World<D>& world() const { return world_; }
  const SpecimenInfo& info() const { return info_; }

 private:
  void check_probes() const;
  void install_bonds();

  const Scene& scene_;
  SpecimenInfo info_;
  World<D> world_;
  Observers<D> obs_;
  std::vector<Series> series_;
};

}  // namespace mc
