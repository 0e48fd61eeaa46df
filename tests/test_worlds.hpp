// Small worlds built in code for the physics tests (the scene files are tested separately).
#pragma once
#include <memory>

#include "contact_models/hertz_mindlin.hpp"
#include "contact_models/linear.hpp"
#include "engine/world.hpp"

namespace mc::test {

// A world whose single phase 0 interacts through one model; the domain is wide open.
template <int D, class Model>
World<D> single_model_world(const typename Model::Params& params) {
  World<D> w;
  w.sets.push_back(std::make_unique<ContactSet<Model, D>>(params));
  w.model_of = {{0}};
  w.domain_lo = Vec<D>::Constant(-1e3);
  w.domain_hi = Vec<D>::Constant(1e3);
  return w;
}

}  // namespace mc::test
