// What the engine requires of a contact model, checked when a ContactSet is made of it: a force law as a pure
// struct with its Params and their key table (engine/keys.hpp: what a scene may set, read by scene/), per-contact
// State (plain numbers: checkpoints copy it as bytes), the per-pair Coeffs it derives from both, and static functions
// of one contact (contact_models/ holds them).
//
// Optional traits, each asked for with `requires`:
//   BondModel: `bondable`, bonded(State), install(Params, geometry, State, PairRandom&): the model glues pairs;
//   `yields`: its bonds report first yields to the crack log too (softening, damage);
//   `only_3d`: a law for spheres only; interaction_radius(Params): it bonds by centre distance (CPM's R_I);
//   History<D> and Properties<D> that State<D> derives from: the contact set keeps them in two arrays, and a force
//   pass writes no byte of the properties (engine/state_columns.hpp).
#pragma once
#include <concepts>

#include "engine/contact_geometry.hpp"
#include "engine/keys.hpp"
#include "engine/random.hpp"

namespace mc {

template <class M, int D>
concept ContactModel = requires(const typename M::Params& p, const WallMaterial& wall, const ContactGeometry<D>& g,
                                typename M::template State<D>& s, const typename M::template State<D>& cs,
                                const typename M::Coeffs& c, double r) {
  { M::name } -> std::convertible_to<const char*>;
  { M::keys() } -> std::same_as<const KeyTable&>;
  // The damping ratio ζ of its dashpots (0: none), which lowers the critical timestep (World::critical_timestep).
  { M::damping_ratio(p) } -> std::convertible_to<double>;
  // Coefficients of a pair of balls (radii, stiffness factors) and of a ball against a wall.
  { M::template pair<D>(p, r, r, r, r) } -> std::same_as<typename M::Coeffs>;
  { M::template wall<D>(p, wall, r, r) } -> std::same_as<typename M::Coeffs>;
  // Force on B of one step (State updated); Energy: also the energy dissipated in it.
  { M::template force<D, false>(c, g, s) } -> std::same_as<ContactForce<D>>;
  { M::template force<D, true>(c, g, s) } -> std::same_as<ContactForce<D>>;
  // Tangent stiffnesses for the timestep, Tang (3.22)–(3.24).
  { M::template stiffness<D>(c, g, cs) } -> std::same_as<ContactStiffness>;
  // Energy stored (Tang 3.75, 3.80), and what a contact that opens lets go.
  { M::template strain_energy<D>(c, g, cs) } -> std::convertible_to<double>;
  { M::template released_energy<D>(c, cs) } -> std::convertible_to<double>;
  // A persistent contact keeps its pair in the lists when the particles part (an intact bond).
  { M::template persistent<D>(cs) } -> std::convertible_to<bool>;
};

template <class M, int D>
concept BondModel = ContactModel<M, D> &&
    requires(const typename M::Params& p, const ContactGeometry<D>& g, typename M::template State<D>& s,
             const typename M::template State<D>& cs, PairRandom& rng) {
  M::bondable;
  { M::template bonded<D>(cs) } -> std::convertible_to<bool>;
  M::template install<D>(p, g, s, rng);
};

}  // namespace mc
