// The CPM's force pass (cpm.hpp) for kLanes 3D contacts at once (engine/lanes.hpp), used by the contact set on
// steps without energy tracing. What happens every step (pairs apart, cohesive or not, damaged, hardening,
// yielding in shear) is a per-lane choice; the damage function and the logarithmic yield radius are taken, one
// lane at a time, only by the lanes that need them. What is rare (a contact first cracking or breaking, passing
// through, a plane tilting by more than 1e-4 rad) and what this kernel does not carry (visco-damage,
// visco-plasticity) sends the contacts back to the one-contact law before anything is written. The same
// operations in the same order as Cpm::force: the same bits.
#pragma once
#include <cmath>
#include <cstddef>

#include "contact_models/cpm.hpp"
#include "engine/contact_set.hpp"
#include "engine/lanes.hpp"

namespace mc {

template <>
struct LaneLaw<Cpm, 3> {
  using State = Cpm::State<3>;
  static constexpr int kStride = sizeof(State) / sizeof(double);

  // Contacts [c, c + kLanes) of `pairs` and `states`, results as store_slots puts them. False: nothing written, run
  // them one at a time.
  [[gnu::flatten]] static bool force(const CpmParams& prm, const Particles<3>& p, const Pair* pairs, State* states,
                                     const NoProperties*, Slots<3>& s, BlockTarget& t, std::size_t record, double dt) {
    if (prm.damage_time > 0 || prm.plastic_time > 0) return false;
    const Lane length = load_lanes<kStride>(&states[0].length);
    const LaneMask cohesive = length > 0.0;
    LaneGeometry g;
    if (!lane_geometry(p, pairs, cohesive, dt, g)) return false;
    const LaneMask apart = g.apart;
    const Lane &ra = g.ra, &rb = g.rb, &reach = g.reach, &overlap = g.overlap;
    const Lane3 &n = g.n, &v_rel = g.v_rel;

    // Coefficients, as Cpm::pair.
    const Lane fa = gather(p.stiffness, g.ia), fb = gather(p.stiffness, g.ib);
    const Cpm::Section<Lane> sec = Cpm::section<3>(prm, ra, rb, fa, fb);
    const Lane &kn = sec.kn, &kt = sec.kt, &area = sec.area;
    const double eps_conf = Cpm::confinement_strain(prm);

    // Cpm::force. Non-cohesive and apart (within the touching reach): no force, the history starts anew.
    const LaneMask loaded = cohesive || !(overlap <= 0.0);
    const Lane len = pick(cohesive, length, reach);
    const Lane inv_len = 1.0 / len;
    const Lane vn = dot(v_rel, n);
    const Lane3 vs = v_rel - vn * n;
    LaneMask tilted = LaneMask::Constant(false);
    Lane3 et = carry_shear(load_lanes3<kStride>(states[0].eps_t.data()), n, g.angle, g.turn, loaded, tilted) +
               vs * (dt * inv_len);
    const Lane eps_raw = Cpm::normal_strain(cohesive, ra, rb, overlap, len, inv_len);
    const Lane eps = eps_raw + eps_conf;
    // 2. Normal stress and damage.
    const Lane eps_pl = load_lanes<kStride>(&states[0].eps_pl);
    const Lane el = eps - eps_pl;
    const Lane kappa_before = load_lanes<kStride>(&states[0].kappa);
    Lane kappa = kappa_before;
    Lane omega = 1.0;
    if (prm.never_damage) {
      omega = pick(cohesive, 0.0, omega);
    } else {
      const double e0 = prm.crack_onset_strain;
      const LaneMask grows = cohesive && el > kappa_before;
      if ((grows && el > e0 && kappa_before <= e0).any()) return false;  // first crack: the crack log's event
      kappa = pick(grows, el, kappa_before);
      Lane g = 0.0;
      if ((cohesive && kappa > e0).any())
        for (int l = 0; l < kLanes; ++l)
          if (cohesive[l] && kappa[l] > e0) g.set(l, Cpm::damage(prm, kappa[l]));
      omega = pick(cohesive, g, omega);
    }
    Lane sn = Cpm::normal_stress(el, omega, kn);
    // Compressive hardening.
    Lane new_eps_pl = eps_pl;
    if (prm.compression_hardening) {
      const Lane sns = Cpm::hardening_stress(prm, kn, eps);
      const LaneMask flows = el < prm.hardening_strain && sns > sn;
      new_eps_pl = pick(flows, eps_pl + (sn - sns) / kn, eps_pl);
      sn = pick(flows, sns, sn);
    }
    // 3. Shear: radial return onto r_pl(σ_N), the logarithm only where Cpm::may_yield lets it through.
    const Lane st2 = kt * kt * dot(et, et);
    const double coh0 = prm.cohesion, tan_phi = prm.tan_friction;
    Lane r_pl = Cpm::linear_radius(coh0, tan_phi, sn, omega);
    if (prm.compression_yield == CpmYield::Logarithmic && coh0 != 0) {
      const LaneMask compressed = !(sn >= 0.0);
      const Lane low = Cpm::log_radius_floor(coh0, tan_phi, prm.yield_log_speed, sn, omega);
      const LaneMask may = st2 > low * low;
      Lane r_log = kInf;
      if ((compressed && may).any())
        for (int l = 0; l < kLanes; ++l)
          if (compressed[l] && may[l])
            r_log.set(l, Cpm::yield_radius(Cpm::pair<3>(prm, ra[l], rb[l], fa[l], fb[l]), sn[l], omega[l]));
      r_pl = pick(compressed, r_log, r_pl);
    }
    const LaneMask yields = st2 > r_pl * r_pl;
    const Lane scale = r_pl / st2.sqrt();
    et = pick(yields, et * scale, et);
    if ((cohesive && omega >= prm.break_damage && el > 0.0).any()) return false;  // a break: the crack log's event
    if ((!apart && loaded && tilted).any()) return false;
    sn = sn - prm.confinement;
    const Lane3 force = pick(loaded, (-area) * (sn * n + kt * et), 0.0);

    // Apart (or non-cohesive and not touching): no force, and the state of a pair never touched (Cpm::State{}).
    const LaneMask kept = !apart && loaded;
    auto keep = [&](double* field, const Lane& now) { store_lanes<kStride>(field, pick(kept, now, 0.0)); };
    keep(states[0].eps_t.data(), et.x), keep(states[0].eps_t.data() + 1, et.y), keep(states[0].eps_t.data() + 2, et.z);
    keep(&states[0].length, length);
    keep(&states[0].kappa, kappa);
    keep(&states[0].eps_pl, new_eps_pl);
    keep(&states[0].eps_d, load_lanes<kStride>(&states[0].eps_d));
    store_slots(s, t, record, p, g, force, nullptr);
    return true;
  }
};

}  // namespace mc
