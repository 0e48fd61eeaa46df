#include "scene/specimen_build.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/machine_memory.hpp"
#include "io/h5_file.hpp"
#include "io/sphere_list.hpp"
#include "preprocess/aggregate_placement.hpp"
#include "preprocess/dense_packing.hpp"
#include "preprocess/random_box.hpp"
#include "preprocess/regular_packing.hpp"
#include "preprocess/spatial_order.hpp"

namespace mc {

namespace {

template <int D>
void add_inline(const Scene& s, Particles<D>& p, std::vector<int>& tags) {
  for (const auto& ip : s.specimen.particles) {
    const int i = p.add(vec_of<D>(ip.x), ip.radius, s.phases[ip.phase].density, ip.phase);
    p.v[i] = vec_of<D>(ip.v);
    p.w[i] = rot_of<D>(ip.w);
    tags.push_back(0);
  }
}

template <int D>
void add_sphere_list(const Scene& s, Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids) {
  const SpecimenSpec& sp = s.specimen;
  SphereList<D> list;
  try {
    list = read_sphere_list<D>(sp.file);
  } catch (const IoError& e) {  // name the scene and its key, not only the resolved path
    throw IoError(s.file + ": key 'specimen.file': " + e.what());
  }
  for (int i = 0; i < list.size(); ++i) {
    const int tag = list.tag[i];
    int phase = 0;
    if (!sp.tag_phase.empty()) {
      if (tag < 0 || tag >= static_cast<int>(sp.tag_phase.size())) {
        std::ostringstream m;
        m << sp.file << ": particle id " << list.id[i] << " has tag " << tag << ", but specimen.tag_phases names "
          << sp.tag_phase.size() << " tags (0.." << sp.tag_phase.size() - 1 << ")";
        throw InputError(m.str());
      }
      phase = sp.tag_phase[tag];
    }
    p.add(list.x[i], list.radius[i], s.phases[phase].density, phase);
    tags.push_back(tag);
    ids.push_back(list.id[i]);
  }
}

// The last frame of an earlier run (its final state), at rest.
template <int D>
void add_output(const Scene& s, Particles<D>& p, std::vector<int>& tags) {
  const SpecimenSpec& sp = s.specimen;
  std::vector<double> radius, x;
  std::vector<std::int64_t> phase;
  try {
    const H5File f(sp.file, H5File::Mode::ReadOnly);
    radius = f.read_doubles("/specimen/radius");
    phase = f.read_ints("/specimen/phase");
    if (f.exists("/frames/x") && f.rows("/frames/x") > 0) {
      std::vector<hsize_t> dims;
      const auto all = f.read_doubles("/frames/x", &dims);
      x.assign(all.end() - static_cast<std::ptrdiff_t>(dims[1]), all.end());
    } else {
      x = f.read_doubles("/specimen/x");
    }
  } catch (const IoError& e) {  // name the scene and its key, not only the resolved path
    throw IoError(s.file + ": key 'specimen.file': " + e.what());
  }
  if (x.size() != radius.size() * D)
    throw InputError(sp.file + ": the specimen has dimension other than the scene's (" + std::to_string(D) + ")");
  for (std::size_t i = 0; i < radius.size(); ++i) {
    const int ph = static_cast<int>(phase[i]);
    if (ph < 0 || ph >= static_cast<int>(s.phases.size()))
      throw InputError(sp.file + ": particle " + std::to_string(i) + " has phase " + std::to_string(ph) +
                       ", but the scene declares " + std::to_string(s.phases.size()) + " phases");
    p.add(Vec<D>(Eigen::Map<const Vec<D>>(x.data() + D * i)), radius[i], s.phases[ph].density, ph);
    tags.push_back(0);
  }
}

// What a Packing specimen's genesis made, read back from the output file of the run being resumed: its particles
// in the order the genesis made them (their ids; a cut's gaps stay), at their initial places. Cut again, sorted
// again and given their phases again, they become the run's specimen as it was; the genesis's facts are already in
// the file.
template <int D>
void add_stored_genesis(const Scene& s, Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids) {
  const SpecimenSpec& sp = s.specimen;
  std::vector<double> radius, x;
  std::vector<std::int64_t> stored_ids;
  {
    const H5File f(sp.genesis_from, H5File::Mode::ReadOnly);
    radius = f.read_doubles("/specimen/radius");
    x = f.read_doubles("/specimen/x");
    stored_ids = f.read_ints("/specimen/id");
  }
  if (x.size() != radius.size() * D || stored_ids.size() != radius.size())
    throw IoError(sp.genesis_from + ": /specimen: " + std::to_string(radius.size()) + " radii, " +
                  std::to_string(x.size()) + " coordinates and " + std::to_string(stored_ids.size()) +
                  " ids do not make one specimen in " + std::to_string(D) + "D");
  std::vector<std::size_t> order(radius.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return stored_ids[a] < stored_ids[b]; });
  const double density = s.phases[sp.phase].density;
  for (const std::size_t i : order) {
    p.add(Vec<D>(Eigen::Map<const Vec<D>>(x.data() + D * i)), radius[i], density, sp.phase);
    tags.push_back(0);
    ids.push_back(stored_ids[i]);
  }
}

// PFC material genesis (preprocess/dense_packing.hpp); what it measured goes to the facts.
template <int D>
Packing<D> genesis(const Scene& s, std::vector<std::pair<std::string, double>>& facts) {
  const SpecimenSpec& sp = s.specimen;
  DensePackingSpec<D> g;
  g.shape = sp.cylinder ? DensePackingSpec<D>::Shape::Cylinder : DensePackingSpec<D>::Shape::Box;
  g.lo = vec_of<D>(sp.box_lo), g.hi = vec_of<D>(sp.box_hi);
  g.radius_min = sp.radius_min, g.radius_ratio = sp.radius_ratio, g.porosity = sp.porosity;
  g.stress = sp.stress, g.modulus = sp.modulus, g.density = s.phases[sp.phase].density, g.seed = s.seed;
  g.floater_contacts = sp.floater_contacts;
  PackingReport rep;
  Packing<D> pk;
  try {
    pk = dense_packing<D>(g, &rep);
  } catch (const InputError& e) {
    throw InputError(s.file + ": [specimen] kind = \"packing\": " + e.what());
  }
  facts = {{"packing_porosity_grown", rep.porosity_grown},
           {"packing_porosity_final", rep.porosity_final},
           {"packing_stress_final", rep.stress_final},
           {"packing_floater_contacts", double(rep.floater_contacts)},
           {"packing_floaters_before", double(rep.before.floaters)},
           {"packing_floater_share_before", rep.before.floater_share},
           {"packing_coordination_before", rep.before.coordination},
           {"packing_floaters_grown", double(rep.floaters_grown)},
           {"packing_floaters", double(rep.after.floaters)},
           {"packing_floater_share", rep.after.floater_share},
           {"packing_coordination", rep.after.coordination},
           {"packing_coordination_held", rep.after.coordination_held},
           {"packing_steps", double(rep.steps)}};
  return pk;
}

// How many particles a generated specimen will hold, from its box and radii, before anything is allocated.
template <int D>
double expected_particles(const SpecimenSpec& sp) {
  double volume = 1;
  for (int k = 0; k < D; ++k) volume *= sp.box_hi[k] - sp.box_lo[k];
  const double r = sp.radius_min;
  if (sp.kind == SpecimenSpec::Kind::Lattice)  // hexagonal cell 2√3 r² per disc; fcc cube (2√2 r)³ per 4 spheres
    return D == 2 ? volume / (2 * std::sqrt(3.0) * r * r) : 4 * volume / std::pow(2 * std::sqrt(2.0) * r, 3);
  if (sp.kind == SpecimenSpec::Kind::Packing) {  // solid volume over the mean grain (radii uniform up to ratio·r)
    const double q = sp.radius_ratio;
    const double mean = D == 2 ? std::numbers::pi * r * r * (q * q + q + 1) / 3
                               : std::numbers::pi * r * r * r * (q * q * q + q * q + q + 1) / 3;
    return volume * (1 - sp.porosity) / mean;
  }
  return static_cast<double>(sp.count);
}

// Memory a run needs per particle, measured on lattices of unbonded linear contacts (the least a run needs:
// bonds and output add to it): 0.82 kB in 2D (1.15 M discs), 1.78 kB in 3D (1.4 M spheres, 12 contacts each).
// A specimen whose lower bound exceeds the machine's memory is refused with the estimate, not left to die of
// std::bad_alloc after minutes of genesis.
template <int D>
void check_memory(const Scene& s) {
  const SpecimenSpec& sp = s.specimen;
  const double n = expected_particles<D>(sp);
  const double need = n * (D == 2 ? 820.0 : 1780.0);
  const double have = physical_memory();
  if (!(need > have)) return;
  const std::string key = sp.kind == SpecimenSpec::Kind::Lattice   ? "specimen.radius"
                          : sp.kind == SpecimenSpec::Kind::Packing ? "specimen.radius_min"
                                                                   : "specimen.count";
  std::ostringstream m;
  m.precision(3);
  m << s.file << ": key '" << key << "': the specimen would hold about " << n << " particles, which need at least "
    << need / (1 << 30) << " GiB (" << (D == 2 ? 0.82 : 1.78) << " kB each); this machine has " << have / (1 << 30)
    << " GiB: use larger particles or a smaller box";
  throw InputError(m.str());
}

// The generated kinds: random box, PFC genesis, regular lattice (row by row or layer by layer: already local).
template <int D>
Packing<D> generated(const Scene& s, std::vector<std::pair<std::string, double>>& facts) {
  const SpecimenSpec& sp = s.specimen;
  check_memory<D>(s);
  if (sp.kind == SpecimenSpec::Kind::Packing) return genesis<D>(s, facts);
  if (sp.kind == SpecimenSpec::Kind::Lattice) {
    if constexpr (D == 2)
      return hexagonal_packing(vec_of<2>(sp.box_lo), vec_of<2>(sp.box_hi), sp.radius_min);
    else
      return fcc_packing(vec_of<3>(sp.box_lo), vec_of<3>(sp.box_hi), sp.radius_min);
  }
  try {
    return random_box_packing<D>(vec_of<D>(sp.box_lo), vec_of<D>(sp.box_hi), sp.count, sp.radius_min, sp.radius_max,
                                 s.seed);
  } catch (const InputError& e) {
    throw InputError(s.file + ": key 'specimen.count' = " + std::to_string(sp.count) + ": " + e.what());
  }
}

// Keeps the particles `order` lists, in that order; tags and ids travel with them.
template <int D>
void reorder(Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids, const std::vector<int>& order) {
  auto permute = [&](auto& v) {
    auto old = v;
    v.resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) v[k] = old[order[k]];
  };
  permute(p.x), permute(p.v), permute(p.f), permute(p.w);
  permute(p.radius), permute(p.mass), permute(p.inertia), permute(p.phase), permute(p.fix), permute(p.stiffness);
  permute(tags), permute(ids);
}

// Renumbers the particles along a Morton curve (cache locality).
template <int D>
void spatial_sort(Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids) {
  reorder<D>(p, tags, ids, morton_order<D>(p.x));
}

// [[specimen.cuts]]: the particles whose centres fall inside a box are removed (a notch, Tang §7.1); the others
// keep their ids, so probes and groups by id do not move when a notch is cut deeper.
template <int D>
void cut_specimen(const Scene& s, Particles<D>& p, std::vector<int>& tags, std::vector<std::int64_t>& ids) {
  std::vector<int> kept;
  for (int i = 0; i < p.size(); ++i) {
    bool inside_any = false;
    for (const auto& [lo, hi] : s.specimen.cuts) inside_any |= in_box<D>(p.x[i], lo, hi);
    if (!inside_any) kept.push_back(i);
  }
  reorder<D>(p, tags, ids, kept);
}

// [[specimen.regions]]: the particles whose centres fall inside a box join its phase, with that phase's density
// (Tang §8.1: the FRP rows on the prism); where boxes overlap, the later one wins.
template <int D>
void assign_regions(const Scene& s, Particles<D>& p) {
  for (const SpecimenSpec::Region& g : s.specimen.regions) {
    const double rho = s.phases[g.phase].density;
    for (int i = 0; i < p.size(); ++i) {
      if (!in_box<D>(p.x[i], g.lo, g.hi)) continue;
      p.phase[i] = g.phase;
      p.set_density(i, rho);
    }
  }
}

}  // namespace

template <int D>
void add_specimen(const Scene& s, Particles<D>& p, std::vector<int>& tags, SpecimenInfo& info) {
  using K = SpecimenSpec::Kind;
  const SpecimenSpec& sp = s.specimen;
  if (sp.kind == K::Particles) {
    add_inline<D>(s, p, tags);
  } else if (sp.kind == K::SphereList) {
    add_sphere_list<D>(s, p, tags, info.ids);
  } else if (sp.kind == K::Output) {
    add_output<D>(s, p, tags);
  } else if (sp.kind == K::Packing && !sp.genesis_from.empty()) {
    add_stored_genesis<D>(s, p, tags, info.ids);
  } else {
    const Packing<D> pk = generated<D>(s, info.facts);
    const double density = s.phases[sp.phase].density;
    for (std::size_t i = 0; i < pk.x.size(); ++i) p.add(pk.x[i], pk.radius[i], density, sp.phase), tags.push_back(0);
  }
  if (p.size() == 0) throw InputError(s.file + ": the specimen holds no particle");
  if (info.ids.empty()) {
    info.ids.resize(p.size());
    for (int i = 0; i < p.size(); ++i) info.ids[i] = i;
  }
  if (!sp.cuts.empty()) cut_specimen<D>(s, p, tags, info.ids);
  if (p.size() == 0) throw InputError(s.file + ": [[specimen.cuts]] remove every particle of the specimen");
  assign_regions<D>(s, p);
  // Inline particles keep the order the scene gives them, lattices are local already.
  if (sp.kind == K::SphereList || sp.kind == K::RandomBox || sp.kind == K::Packing) spatial_sort<D>(p, tags, info.ids);
}

template void add_specimen<2>(const Scene&, Particles<2>&, std::vector<int>&, SpecimenInfo&);
template void add_specimen<3>(const Scene&, Particles<3>&, std::vector<int>&, SpecimenInfo&);

}  // namespace mc
