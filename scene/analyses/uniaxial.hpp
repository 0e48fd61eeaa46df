// [uniaxial]: the virtual uniaxial compression or tension test (Tang §5.2; Šmilauer, "Simulation setup"). From
// the histories it names, or from those it records itself when two support groups strain the specimen, it gives
// E (secant between 25 % and 50 % of the peak), ν, the strength (UCS = f_c, or f_t), the strain at the peak, the
// crack-initiation stress and the crack counts, and in tension G_f. Keys and summary block: README, "[uniaxial]".
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "engine/dim.hpp"
#include "scene/analysis.hpp"

namespace mc {

// What a uniaxial test gives; NaN where the curve does not tell.
struct UniaxialResult {
  double modulus = kNaN;  // E [Pa], secant between 25 % and 50 % of the peak, in the declared reading (2D)
  double poisson = kNaN;  // ν, likewise
  // 2D: the disc assembly's own ratios (σ/ε and −ε_lat/ε_axial in its plane), before any plane reading.
  double modulus_raw_2d = kNaN, poisson_raw_2d = kNaN;
  // The same curve read with other windows: the secant from the start to 50 % of the peak, and the tangent at
  // 50 % (the secant between 45 % and 55 %), in the declared reading.
  double modulus_secant_0_50 = kNaN, modulus_tangent_50 = kNaN;
  // E and ν (secant 25–50 %, declared reading) from each axial strain: the platens' (or supports') and the
  // inside's.
  double modulus_platens = kNaN, modulus_inside = kNaN;
  double poisson_platens = kNaN, poisson_inside = kNaN;
  double ucs = kNaN;  // peak axial stress [Pa]: f_c, or in tension f_t
  bool peak_passed = false;  // the stress fell past its peak (passed_peak): else ucs is the largest so far
  double strain_at_peak = kNaN;
  double initiation_stress = kNaN;  // when the cracks reach 1 % of their count at the peak [Pa]
  double cracks_at_peak = kNaN, cracks_tensile = kNaN, cracks_shear = kNaN;
  bool cracks_by_yield = false;  // no break at all: the first yields (damage onsets) were counted instead
  // In tension (Šmilauer Fig. 19): G_f [J/m²], the gauge length [m] and the strain where the stress fell to 0.2 f_t.
  double fracture_energy = kNaN, gauge_length = kNaN, strain_at_02ft = kNaN;
};

class UniaxialAnalysis final : public Analysis {
 public:
  std::string stress, axial_strain;         // history names
  std::vector<std::string> lateral_strain;  // their mean is the lateral strain (3D: the two lateral axes)
  bool tension = false;                     // loading = "tension"
  int dimension = 3;
  // 2D: how the disc assembly's ratios are read as a material's E and ν. Plane strain (Tang ch. 5
  // introduction): ν = ν₂/(1 + ν₂), E = E₂(1 − ν²). Plane stress: the ratios as they are.
  bool plane_strain = true;
  // Straining by two support groups (supports = "bottom top") along `axis`: the analysis then records
  // uniaxial.stress (the mean of both supports' axial reactions over `area`), uniaxial.strain (their mean
  // displacements over their initial distance), uniaxial.length (that distance) and uniaxial.lateral_strain
  // (regression of the inner particles' lateral displacements on their positions), each positive in the loading
  // sense but the lateral strain (expansion positive), and reads them.
  std::array<int, 2> supports = {-1, -1};  // indices into Scene::groups; −1: not used
  std::array<std::string, 2> support_names;
  int axis = 2;
  // The axial strain E is read from: the platens' or supports' (`axial_strain`) or the inside's
  // (uniaxial.inside_strain: the regression of the axial displacements on the axial positions of the particles
  // of the middle half of the length, free of the give of the platen contacts). Both are recorded.
  bool strain_inside = false;
  double area = 0;         // [m²] (3D) or [m] (2D); 0: the specimen's bounding box
  std::string scene_file;  // for messages

  std::string name() const override;  // its key table's
  void add_histories(std::vector<Series>& out, const Observed<2>& o) const override;
  void add_histories(std::vector<Series>& out, const Observed<3>& o) const override;
  void check(const KeyReader& k, const Scene& s, const std::vector<std::string>& histories) const override;
  std::string summary_json(const RunRecord& run) const override;

  UniaxialResult result(const Histories& h) const;

 private:
  UniaxialResult result_from(const Histories& h, const std::string& axial) const;
  template <int D>
  void add_inside_strain(std::vector<Series>& out, const Observed<D>& o) const;
  template <int D>
  void add_support_histories(std::vector<Series>& out, const Observed<D>& o) const;
};

const KeyTable& uniaxial_keys();
std::shared_ptr<const Analysis> read_uniaxial(const KeyReader& k, const Scene& s);

}  // namespace mc
