// [pullout]: the single-shear pull test of an FRP sheet bonded to a concrete prism (Tang §8.1; 2D, y up, the
// sheet on top, pulled along x). It records the pulling load, the slip at the loaded end (an opening probe along
// x) and the strains of equally spaced gauges along the bonded FRP, and gives the capacity and the slip there
// (also × β_w of (8.1)), the strain profiles at declared loads beside ε₀ of (8.5), the cracks per phase pair at
// 31, 60, 90 and 100 % of the capacity and at the end, the failure mode, and the energy balance. Keys and
// summary block: README, "[pullout]".
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scene/analysis.hpp"

namespace mc {

// The failure of a pull test, named from the crack log: breaks of the adhesive (pairs with the FRP phase)
// against breaks in the concrete, and how deep below the interface the concrete broke.
struct PulloutFailure {
  long adhesive_breaks = 0, concrete_breaks = 0;
  double depth_median = kNaN, depth_p90 = kNaN, depth_max = kNaN;  // of the concrete breaks [m]
  std::string mode;  // "adhesive", "thin concrete layer" or "concrete wedge"
};

class PulloutAnalysis final : public Analysis {
 public:
  int pulled_group = -1;     // index into Scene::groups: the driven FRP end
  std::vector<double> pull;  // unit vector of its velocity
  int slip_gauge = -1;       // index into World::gauges
  std::string slip_probe;
  int frp_phase = -1;
  std::vector<std::string> phase_names;
  double bonded_from = 0, bonded_to = 0;  // the bonded length's ends along x [m]; `bonded_from` the loaded one
  int gauges = 10;
  double width = 0, prism_width = 0;          // b_f, b_c [m] of the reported specimen (β_w of (8.1))
  double frp_modulus = 0, frp_thickness = 0;  // E_p [Pa], t_p [m] for ε₀ of (8.5)
  std::vector<double> load_levels;            // [N] of the reported width: where the strain profiles are taken
  double interface_stiffness = kNaN;          // K [Pa/m]: where given, the final profile against the shear lag
  std::string scene_file;

  std::string name() const override;  // its key table's
  void add_histories(std::vector<Series>& out, const Observed<2>& o) const override;
  void add_histories(std::vector<Series>& out, const Observed<3>& o) const override;
  void check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const override;
  std::string summary_json(const RunRecord& run) const override;

  double bonded_length() const { return std::abs(bonded_to - bonded_from); }
  // Chen & Teng's (2001) width factor (8.1).
  double beta_w() const;
  // The centre of gauge k, from the bonded length's loaded end [m].
  double gauge_position(int k) const { return (k + 0.5) * bonded_length() / gauges; }
  PulloutFailure failure(const std::vector<LoggedCrack>& cracks, double interface_y, double bottom_y) const;
  // The gauges' strains at the run's end beside the linear shear-lag solution for interface_stiffness (JSON).
  std::string shear_lag_json(const Histories& h) const;
};

const KeyTable& pullout_keys();
std::shared_ptr<const Analysis> read_pullout(const KeyReader& k, const Scene& s);

}  // namespace mc
