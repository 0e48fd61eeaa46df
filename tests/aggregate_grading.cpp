// Aggregate grading (Tang 2013 §4.3–4.4): Table 4.1, Fuller's curve (4.7), Walraven's section transform (4.8) at
// its published coefficients, and the filling of a target fraction range by range.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/errors.hpp"
#include "preprocess/aggregate_shape.hpp"
#include "preprocess/grading.hpp"
#include "tests/common/relative.hpp"

using namespace mc;

TEST_CASE("walraven_transform_matches_published_coefficients_and_hand_computed_points") {
  // At D0 = D_max the bracket is 1.455 − 0.5 + 0.036 + 0.006 + 0.002 + 0.001 = 1.000: all of P_k.
  CHECK(walraven_passing(1.0, 0.75) == mc::test::relative(0.75, 1e-15));
  CHECK(walraven_passing(0.0, 0.75) == 0.0);
  // D0/D_max = 1/2 (P_k = 1), term by term:
  //   1.455·√½ = 1.0288404, −0.5·¼ = −0.125, 0.036/16 = 0.00225, 0.006/64 = 0.00009375,
  //   0.002/256 = 0.0000078, 0.001/1024 = 0.0000010  → 0.9061929
  CHECK(walraven_passing(0.5, 1.0) == mc::test::relative(0.9061929, 1e-7));
  // D0/D_max = 1/4: 1.455·½ = 0.7275, −0.5/16 = −0.03125, 0.036/256 = 0.0001406, 0.006/4096 = 0.0000015,
  //   the rest < 1e-7  → 0.6963921
  CHECK(walraven_passing(0.25, 1.0) == mc::test::relative(0.6963921, 1e-7));
  // Linear in P_k.
  CHECK(walraven_passing(0.25, 0.6) == mc::test::relative(0.6 * 0.6963921, 1e-7));

  // The Table 4.1 sieves 4, 8, 16, 32, 64 mm at P_k = 0.75: each range's area fraction of a section is
  // P_c(hi) − P_c(lo); together P_c(1) − P_c(1/16) = 0.75 (1 − 0.3617974) (1.455/4 − 0.5/256 + … = 0.3617974).
  const SectionGrading s = walraven_section({4, 8, 16, 32, 64}, 0.75);
  REQUIRE(s.grading.ranges.size() == 4);
  CHECK(s.fraction == mc::test::relative(0.75 * (1 - 0.3617974), 1e-7));
  CHECK(s.grading.ranges[3].share * s.fraction == mc::test::relative(0.75 * (1 - 0.9061929), 1e-7));
  CHECK(s.grading.ranges[2].share * s.fraction == mc::test::relative(0.75 * (0.9061929 - 0.6963921), 1e-7));
  double sum = 0;
  for (const auto& r : s.grading.ranges) sum += r.share;
  CHECK(sum == mc::test::relative(1.0, 1e-14));
  CHECK_NOTHROW(check_grading(s.grading));
  CHECK_THROWS_AS(walraven_section({4, 8}, 1.5), InputError);
}

TEST_CASE("fuller_shares_sum_to_one_and_table_4_1_is_2_2_3_3") {
  const Grading f = fuller_grading({4, 8, 16, 32, 64}, 0.5);
  REQUIRE(f.ranges.size() == 4);
  double sum = 0;
  for (const auto& r : f.ranges) sum += r.share;
  CHECK(sum == mc::test::relative(1.0, 1e-14));
  // √(d/64) at the sieves: ¼, √2/4, ½, √2/2, 1; normalised over 1 − ¼ = ¾.
  CHECK(f.ranges[0].share == mc::test::relative((std::sqrt(2.0) / 4 - 0.25) / 0.75, 1e-14));
  CHECK(f.ranges[3].share == mc::test::relative((1 - std::sqrt(2.0) / 2) / 0.75, 1e-14));
  CHECK(fuller_passing(16, 64, 0.5) == mc::test::relative(0.5, 1e-5));
  const Grading t = tang_table_4_1();
  REQUIRE(t.ranges.size() == 4);
  const double lo[] = {4, 8, 16, 32}, share[] = {0.2, 0.2, 0.3, 0.3};
  for (int k = 0; k < 4; ++k) {
    CHECK(t.ranges[k].lo == lo[k]);
    CHECK(t.ranges[k].hi == 2 * lo[k]);
    CHECK(t.ranges[k].share == share[k]);
  }
  CHECK(tang_table_4_1(1e-3).ranges[3].hi == mc::test::relative(0.064, 1e-5));
  CHECK_THROWS_AS(check_grading(Grading{{{4, 8, 0.5}, {6, 16, 0.5}}}), InputError);  // overlapping ranges
  CHECK_THROWS_AS(check_grading(Grading{{{4, 8, 0.5}, {8, 16, 0.4}}}), InputError);  // shares sum to 0.9
  CHECK_THROWS_AS(fuller_grading({8, 4}, 0.5), InputError);
}

TEST_CASE("filling_a_grading_puts_the_exact_share_of_shape_areas_in_each_range") {
  for (int dim = 2; dim <= 3; ++dim)
    for (const SizeDraw draw : {SizeDraw::uniform, SizeDraw::fuller}) {
      const Grading g = tang_table_4_1();
      const double target = dim == 2 ? 0.7 * 400 * 100 : 0.5 * 100 * 100 * 100;
      RandomStream rng(11);
      std::vector<double> made;  // the exact content of each shape made
      const auto list = fill_grading(
          g, target, dim,
          [&](double d) {
            made.push_back(dim == 2 ? area(random_polygon(d, ShapeParams{}, rng))
                                    : volume(random_polyhedron(d, ShapeParams{}, rng)));
            return made.back();
          },
          rng, draw);
      std::vector<double> per(4, 0.0);
      for (std::size_t i = 0; i < list.size(); ++i) {
        const auto& a = list[i];
        CHECK(a.size >= g.ranges[a.range].lo);
        CHECK(a.size < g.ranges[a.range].hi);
        CHECK(a.content == mc::test::relative(made[a.made] * std::pow(a.scale, dim), 1e-12));
        if (i > 0) CHECK(a.size <= list[i - 1].size);
        per[a.range] += a.content;
      }
      double total = 0;
      for (int k = 0; k < 4; ++k) {
        CHECK(per[k] == mc::test::relative(g.ranges[k].share * target, 1e-9));
        total += per[k];
      }
      CHECK(total == mc::test::relative(target, 1e-9));
    }
  // The planning variant, with discs (content π d²/4): half of 2000 mm² filled exactly.
  const auto sizes = aggregate_sizes(Grading{{{4, 8, 1.0}}}, 0.5, 2000, 2, M_PI / 4, 3);
  double sum = 0;
  for (const auto& a : sizes) sum += a.content;
  CHECK(sum == mc::test::relative(1000, 1e-12));
  CHECK_THROWS_AS(aggregate_sizes(tang_table_4_1(), 1.5, 2000, 2, 0.5, 3), InputError);
}
