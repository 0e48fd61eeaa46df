// What every section of the throughput benchmark (benchmarks/throughput.cpp) shares: its options, the thread
// counts it times, and the world it builds from a particle list with one contact model.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "contact_models/cpm.hpp"
#include "contact_models/linear.hpp"
#include "contact_models/parallel_bond.hpp"
#include "engine/world.hpp"

namespace mc::bench {

struct Options {
  bool quick = false;
  bool shared = true, scaling = true, effects = true, deposition = true;
  bool unbonded_scaling = true;      // the scaling section's unbonded 2D and 3D rows (--only bonded-scaling: without)
  bool unbonded = true;              // the shared specimen also without bonds (--only bonded: with bonds only)
  bool parallel = true, cpm = true;  // its parallel-bonded and CPM runs (--only bonded / cpm: that one alone)
  std::string specimen_dir = MESOCRACK_SPECIMEN_DIR;
  int reps = 3;
  bool reps_given = false;
  int max_bonded = 10000000;  // the largest bonded block of the scaling section (--max-bonded)
  // --one SPECIMEN:MODEL:THREADS (benchmarks/peers/peers_bench.py): that run alone, once, as one RESULT line.
  std::string one_specimen, one_model;
  int one_threads = 0;
};

inline constexpr int kThreads[] = {1, 2};

struct Material {
  double modulus = 30e9;  // contact modulus E_c [Pa]
  double density = 2600;  // [kg/m³]
  double kn_ks = 1.0;
  double friction = 0.5;
  double damping = 0.0;  // ζ of the contact dashpots
  bool bonded = false;  // parallel bonds (E̅_c = E_c, k̄_n/k̄_s = k_n/k_s, λ̄ = 1, unbreakable here) beside the contacts
  bool cpm = false;  // instead, CPM contacts (k_N = E_c), cohesive where d ≤ 1.05 (R_i + R_j)
};

// The CPM of the shared run: k_N = E_c, k_T/k_N = 0.2, the document's inelastic parameters, but ε_0 = 1e-3 so that
// no contact damages in the timed window (the README: no bond breaks there), as in the parallel-bond run; cohesive
// contacts on the README's bond pairs, R_I = 1.05.
inline CpmParams shared_cpm_params(double modulus) {
  CpmParams p;
  p.modulus = modulus;
  p.crack_onset_strain = 1e-3;
  p.relative_ductility = 30;
  p.cohesion = 3.5e6;
  p.tan_friction = 0.8;
  p.interaction_radius = 1.05;
  return p;
}

template <int D>
void add_contact_set(World<D>& w, const Material& mat) {
  LinearParams lp;
  lp.modulus = mat.modulus;
  lp.kn_ks_ratio = mat.kn_ks;
  lp.friction = mat.friction;
  lp.damping_ratio = mat.damping;
  if (mat.cpm) {
    w.sets.push_back(std::make_unique<ContactSet<Cpm, D>>(shared_cpm_params(mat.modulus)));
  } else if (mat.bonded) {
    ParallelBondParams bp;
    bp.contact = lp;
    bp.bond_modulus.mean = mat.modulus;
    bp.bond_kn_ks_ratio = mat.kn_ks;
    bp.bond_tensile_strength.mean = bp.bond_shear_strength.mean = 1e12;  // no bond breaks in the timed window (README)
    w.sets.push_back(std::make_unique<ContactSet<ParallelBond, D>>(bp));
  } else {
    w.sets.push_back(std::make_unique<ContactSet<Linear, D>>(lp));
  }
  w.model_of = {{0}};
}

template <int D>
World<D> make_world(const std::vector<Vec<D>>& x, const std::vector<double>& r, const Material& mat) {
  World<D> w;
  add_contact_set(w, mat);
  const int n = static_cast<int>(x.size());
  auto& p = w.particles;
  for (auto* v : {&p.x, &p.v, &p.f}) v->reserve(n);
  p.w.reserve(n), p.radius.reserve(n), p.mass.reserve(n), p.inertia.reserve(n);
  p.phase.reserve(n), p.fix.reserve(n);
  Vec<D> lo = Vec<D>::Constant(kInf), hi = Vec<D>::Constant(-kInf);
  for (int i = 0; i < n; ++i) {
    p.add(x[i], r[i], mat.density, 0);
    lo = lo.cwiseMin(x[i]);
    hi = hi.cwiseMax(x[i]);
  }
  const Vec<D> margin = Vec<D>::Constant((hi - lo).maxCoeff() + 1.0);
  w.domain_lo = lo - margin;
  w.domain_hi = hi + margin;
  return w;
}

}  // namespace mc::bench
