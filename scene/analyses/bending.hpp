// [bending]: the three-point bending test of a (notched) beam (Tang §7.1; RILEM 50-FMC). It records the load on
// the loading wall, the crack-mouth opening (an opening probe) and the deflection of the loading point relative
// to the supports, and gives the peak load with the CMOD and deflection there, the fracture energy G_F by the work
// of fracture, and the initial stiffness; from the crack log, the crack path's tortuosity and the cracks per phase
// pair at the peak and at the end; with energy tracing, the energy balance. Keys and summary block: README,
// "[bending]".
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/dim.hpp"
#include "scene/analysis.hpp"

namespace mc {

// What a bending test gives; NaN where the curve does not tell. Loads as simulated (2D: per metre of the discs'
// unit thickness); BendingAnalysis::load_scale turns them into the reported thickness's.
struct BendingResult {
  double peak_load = kNaN;           // [N]
  bool peak_passed = false;          // the load fell past its peak (passed_peak): else peak_load is the largest so far
  double peak_time = kNaN;           // [s]
  double cmod_at_peak = kNaN;        // [m]
  double deflection_at_peak = kNaN;  // [m]
  double work = kNaN;                // W0: area under load–deflection to the end of the record [J]
  double self_weight_work = 0;       // m g δ0 of RILEM 50-FMC [J]; 0 without gravity
  double fracture_energy = kNaN;     // G_F = (W0 + m g δ0) / ligament area [J/m²]
  double stiffness = kNaN;           // secant of load–deflection between 10 % and 40 % of the peak, pre-peak [N/m]
  double final_load_ratio = kNaN;    // load at the end of the record over the peak
  double final_deflection = kNaN;    // δ0, where the record ends [m]
};

// The main crack as a line through the ligament: the median position along the beam of the broken bonds in each
// of `kBands` height bands (those within half a depth of mid-span), joined from band to band.
struct CrackPath {
  static constexpr int kBands = 20;
  int bands = 0;              // bands with broken bonds
  double length = kNaN;       // of the line [m]
  double height = kNaN;       // the height it spans, first band's centre to last's [m]
  double tortuosity = kNaN;   // length / height
};

class BendingAnalysis final : public Analysis {
 public:
  int dimension = 3;
  int load_wall = -1;                          // index into Scene::walls
  std::array<int, 2> supports = {-1, -1};      // walls (the default deflection)
  std::array<int, 3> deflection_groups = {-1, -1, -1};  // mid, left, right: a yoke on the beam; −1: walls
  int cmod_gauge = -1;                         // index into World::gauges
  std::string cmod_probe;
  double span = 0, depth = 0, ligament = 0;    // [m]
  double thickness = 0;                        // [m] of the reported beam (2D: the real one; discs: 1 m)
  std::optional<std::vector<double>> gravity;  // the scene's, for the self-weight correction
  std::vector<std::string> phase_names;
  // The beam's frame, from the walls: the top of mid-span (the loading wall's centre), the unit vector from the
  // left support to the right one, and the loading wall's normal (down, into the beam).
  std::array<double, 3> top{}, along{}, down{};
  std::string scene_file;

  std::string name() const override;  // its key table's
  void add_histories(std::vector<Series>& out, const Observed<2>& o) const override;
  void add_histories(std::vector<Series>& out, const Observed<3>& o) const override;
  void check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const override;
  std::string summary_json(const RunRecord& run) const override;

  BendingResult result(const Histories& h) const;
  // The crack path of the breaks logged up to `until` [s].
  CrackPath crack_path(const std::vector<LoggedCrack>& cracks, double until) const;
  // Simulated loads to the reported beam's: 2D discs stand for 1 m of thickness, the report for `thickness`.
  double load_scale() const { return dimension == 2 ? thickness / 1.0 : 1.0; }
  // The ligament's area in the simulation [m²] (2D: times the discs' 1 m).
  double ligament_area() const { return ligament * (dimension == 2 ? 1.0 : thickness); }

 private:
  template <int D>
  void add(std::vector<Series>& out, const Observed<D>& o) const;
};

const KeyTable& bending_keys();
std::shared_ptr<const Analysis> read_bending(const KeyReader& k, const Scene& s);

}  // namespace mc
