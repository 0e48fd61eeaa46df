// The same state writes the same checkpoint: the crack log's records carry padding between their members, which
// must not carry whatever the memory held before.
#include <doctest/doctest.h>

#include <cstring>
#include <new>
#include <vector>

#include "engine/world.hpp"

using namespace mc;

namespace {

// A crack record built in memory filled with `fill`, as a crack made on a dirty stack would be.
Crack<2> crack_on_dirty_memory(unsigned char fill) {
  alignas(Crack<2>) unsigned char buffer[sizeof(Crack<2>)];
  std::memset(buffer, fill, sizeof buffer);
  auto* c = new (buffer) Crack<2>;
  c->step = 7, c->time = 1e-3, c->a = 1, c->b = 2;
  c->position = Vec<2>(0.01, 0.02), c->normal = Vec<2>(1, 0);
  c->mode = CrackMode::Tensile, c->kind = CrackKind::Break;
  c->set = 0, c->phase_a = 0, c->phase_b = 0;
  Crack<2> out;
  std::memcpy(static_cast<void*>(&out), buffer, sizeof out);  // padding and all
  return out;
}

std::vector<std::uint8_t> saved_cracks(unsigned char fill) {
  World<2> w;
  w.cracks.push_back(crack_on_dirty_memory(fill));
  Archive a;
  w.save(a);
  return a.bytes.at("cracks");
}

}  // namespace

TEST_CASE("checkpoint_of_the_same_crack_log_is_the_same_bytes_whatever_the_memory_held") {
  const auto a = saved_cracks(0xAB), b = saved_cracks(0xCD);
  REQUIRE(a.size() == sizeof(Crack<2>));
  CHECK(a == b);
}
