// The parallel bond's force pass (parallel_bond.hpp) for kLanes 3D contacts at once (engine/lanes.hpp), used by the
// contact set on steps without energy tracing. Every branch of the one-contact law that happens every step (pairs
// apart, touching or not, slipping, bonded or not) is a per-lane choice; what is rare (a bond breaking, a contact
// passing through, a plane tilting by more than 1e-4 rad) and what this kernel does not carry (dashpots, particle
// stiffness factors) sends them back to the one-contact law before anything is written. The same
// operations in the same order as ParallelBond::force: the same bits.
#pragma once
#include <cmath>
#include <cstddef>

#include "contact_models/parallel_bond.hpp"
#include "engine/contact_set.hpp"
#include "engine/lanes.hpp"

namespace mc {

template <>
struct LaneLaw<ParallelBond, 3> {
  using History = ParallelBond::History<3>;
  using Properties = ParallelBond::Properties<3>;
  static constexpr int kStride = sizeof(History) / sizeof(double);
  static constexpr int kStrideP = sizeof(Properties) / sizeof(double), kStridePF = sizeof(Properties) / sizeof(float);

  // Contacts [c, c + kLanes) of `pairs`, `states` and `props`, results as store_slots puts them. False: nothing
  // written, run them one at a time. The properties are only read: an unbonded pair's are the defaults
  // (ParallelBond::unbonded), so a pair found apart keeps them as they are.
  [[gnu::flatten]] static bool force(const ParallelBondParams& prm, const Particles<3>& p, const Pair* pairs,
                                     History* states, const Properties* props, Slots<3>& s, BlockTarget& t,
                                     std::size_t record, double dt) {
    if (prm.contact.damping_ratio > 0) return false;
    const Lane tensile = load_lanes<kStridePF>(&props[0].tensile);
    const Lane shear = load_lanes<kStridePF>(&props[0].shear);
    const LaneMask bonded = tensile > 0.0;
    LaneGeometry g;
    if (!lane_geometry(p, pairs, bonded, dt, g)) return false;
    const LaneMask apart = g.apart;
    if ((!apart && (gather(p.stiffness, g.ia) != 1.0 || gather(p.stiffness, g.ib) != 1.0)).any()) return false;
    const Lane &ra = g.ra, &rb = g.rb, &overlap = g.overlap, &angle = g.angle, &turn = g.turn;
    const Lane3 &n = g.n, &v_rel = g.v_rel;
    const Lane3 w_rel = g.wb - g.wa;

    // Coefficients, as ParallelBond::pair with unit stiffness factors.
    const Lane inv_sum = 1.0 / g.reach;
    const ParallelBond::Beam<Lane> beam = ParallelBond::beam(prm, ra, rb, inv_sum);
    const Lane kn_c = 4.0 * prm.contact.modulus * (ra * rb * inv_sum), ks_c = kn_c * (1.0 / prm.contact.kn_ks_ratio);

    // The grain contact with Coulomb slip (Linear::force), Tang (3.5), (3.9), (3.10), (3.36).
    LaneMask tilted = LaneMask::Constant(false);
    const LaneMask touching = !(overlap <= 0.0);
    const Lane vn = dot(v_rel, n);
    const Lane3 vs = v_rel - vn * n;
    const Lane fn = kn_c * overlap;
    const Lane3 fs_trial =
        carry_shear(load_lanes3<kStride>(states[0].fs.data()), n, angle, turn, touching, tilted) - ks_c * vs * dt;
    const Lane fs_max = prm.contact.friction * fn;
    const Lane fs2 = dot(fs_trial, fs_trial);
    const Lane3 fs_slid = fs_trial * (fs_max / fs2.sqrt());
    const Lane3 fs = pick(touching, pick(fs2 > fs_max * fs_max, fs_slid, fs_trial), 0.0);
    const Lane3 grain = pick(touching, fn * n + fs, 0.0);

    // The bond, Tang (3.37), its stresses (3.41).
    const Lane kdt = load_lanes<kStrideP>(&props[0].stiffness) * dt;
    Lane bfn = load_lanes<kStride>(&states[0].bond_fn), bmn = load_lanes<kStride>(&states[0].bond_mn);
    Lane3 bfs = load_lanes3<kStride>(states[0].bond_fs.data()), bms = load_lanes3<kStride>(states[0].bond_ms.data());
    ParallelBond::load_beam(beam, n, vn, vs, w_rel, kdt, bfn, bfs, bmn, bms,
                            [&](const Lane3& v) { return carry_shear(v, n, angle, turn, bonded, tilted); });
    const LaneMask breaks = ParallelBond::exceeds(tensile + bfn * beam.inv_a, dot(bms, bms), beam.r_i) ||
                            ParallelBond::exceeds(shear - abs_of(bmn) * beam.r_j, dot(bfs, bfs), beam.inv_a);
    if ((!apart && ((bonded && breaks) || tilted)).any()) return false;

    const Lane3 force = pick(bonded, grain + (bfn * n + bfs), grain);
    const Lane3 moment = pick(bonded, 0.0 + (bmn * n + bms), 0.0);  // ContactForce's zero moment, plus the bond's
    const LaneMask kept = !apart;
    // Apart and unbonded: no force, and the state of a pair never touched (ParallelBond::State{}).
    auto keep = [&](double* field, const Lane& now, const LaneMask& changed, double apart_value) {
      store_lanes<kStride>(field, pick(kept, pick(changed, now, load_lanes<kStride>(field)), apart_value));
    };
    auto keep3 = [&](double* field, const Lane3& now, const LaneMask& changed) {
      keep(field, now.x, changed, 0.0), keep(field + 1, now.y, changed, 0.0), keep(field + 2, now.z, changed, 0.0);
    };
    keep3(states[0].fs.data(), fs, kept);
    keep3(states[0].bond_fs.data(), bfs, bonded);
    keep3(states[0].bond_ms.data(), bms, bonded);
    keep(&states[0].bond_fn, bfn, bonded, 0.0);
    keep(&states[0].bond_mn, bmn, bonded, 0.0);
    store_slots(s, t, record, p, g, force, &moment);
    return true;
  }
};

}  // namespace mc
