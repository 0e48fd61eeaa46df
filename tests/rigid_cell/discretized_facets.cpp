// Discretized facets (Květoň §3.3): a facet's law at the centroids of the triangles its vertices make with its
// centroid (2D: of its halves). On cubic cells the facets are squares, so the stiffness they keep has a closed form;
// in a specimen the parts only add rotational stiffness, which a cantilever must show.
#include <doctest/doctest.h>

#include <vector>

#include "rigid_cell/facet_discretization.hpp"
#include "rigid_cell/node_placement.hpp"
#include "rigid_cell/static_solver.hpp"
#include "tests/common/relative.hpp"
#include "tests/rigid_cell/cubic_grid.hpp"

using namespace mc;
using namespace mc::rigid_cell;

namespace {

constexpr double kE0 = 30e9, kAlpha = 0.29;

// The energy 2W/θ² of cell b rotating by θ about the axis `axis` through the contact's centroid, cell a at rest:
// the contact's rotational stiffness there, summed over every contact (the parts of one facet).
template <int D>
double rotational_stiffness(const Tessellation<D>& t, const Vec<D>& about, const Eigen::Vector3d& axis) {
  constexpr int n = CellAssembly<D>::kDofs;
  const CellAssembly<D> model(t, std::vector<FacetParams>(t.contacts, FacetParams{kE0, kAlpha, 0, 0}));
  Eigen::Matrix<double, 2 * n, 1> q = Eigen::Matrix<double, 2 * n, 1>::Zero();
  const Vec<D> r = about - t.cells[1].node;
  if constexpr (D == 2) {
    q.template segment<2>(n) = -Vec<2>(-r.y(), r.x());  // u_b = −θ e_z × r: the point `about` stays put
    q[n + 2] = 1;
  } else {
    q.template segment<3>(n) = -axis.cross(r);
    q.template segment<3>(n + 3) = axis;
  }
  double k = 0;
  for (std::size_t c = 0; c < model.contacts(); ++c) k += q.dot(model.element_stiffness(c) * q);
  return k;
}

// The same for cell b moving by the unit translation `move`.
template <int D>
double translational_stiffness(const Tessellation<D>& t, const Vec<D>& move) {
  constexpr int n = CellAssembly<D>::kDofs;
  const CellAssembly<D> model(t, std::vector<FacetParams>(t.contacts, FacetParams{kE0, kAlpha, 0, 0}));
  Eigen::Matrix<double, 2 * n, 1> q = Eigen::Matrix<double, 2 * n, 1>::Zero();
  q.template segment<D>(n) = move;
  double k = 0;
  for (std::size_t c = 0; c < model.contacts(); ++c) k += q.dot(model.element_stiffness(c) * q);
  return k;
}

// The tip deflection of the cantilever of Květoň §8.3 (200 × 20 × 20 mm, clamped at x = 0, a unit shear at its tip)
// on cells l_min = l apart, with simple facets or their parts.
double cantilever_deflection(double l, FacetIntegration integration) {
  const double L = 0.2, h = 0.02, F = 1.0;
  const FacetParams p{48e9, 0.29, 0, 0};
  const auto shape = SpecimenShape<3>::box(Vec<3>(L, h, h));
  Tessellation<3> t = tessellate(place_nodes(shape, l, 3, 3000), shape, 3 * l);
  if (integration == FacetIntegration::Discretized) t = discretize_facets(t).parts;
  const CellAssembly<3> model(t, std::vector<FacetParams>(t.contacts, p));
  constexpr int n = CellAssembly<3>::kDofs;
  std::vector<int> clamp, tip;
  Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(model.dofs());
  for (int c = 0; c < model.cells(); ++c) {
    const double x = t.cells[c].node[0];
    if (x < l)
      for (int j = 0; j < n; ++j) clamp.push_back(n * c + j);
    if (x > L - l) tip.push_back(c);
  }
  for (int c : tip) f_ext[n * c + 1] = -F / tip.size();
  StaticSolver<3> solver(model, clamp);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model.dofs());
  std::vector<double> damage(model.contacts(), 0.0);
  std::vector<FacetState> states(model.contacts());
  solver.solve(u, f_ext, damage, states);
  double deflection = 0;
  for (int c : tip) deflection -= u[n * c + 1] / tip.size();
  return deflection;
}

}  // namespace

TEST_CASE("a_discretized_square_facet_keeps_two_thirds_of_its_bending_and_torsion_stiffness_and_all_its_axial") {
  const double h = 0.01;  // two cubes of side h side by side along x: one square facet of side h, L = h
  const Tessellation<3> simple =
      tessellate(mc::test::cubic_grid_nodes(h, 2, 1, 1), SpecimenShape<3>::box(Vec<3>(2 * h, h, h)), 3 * h);
  REQUIRE(simple.contacts == 1);
  const FacetParts<3> d = discretize_facets(simple);
  // A cube's face from CGAL may repeat a vertex (the eight nodes around a corner are cospherical): the slivers go,
  // four triangles of h²/4 remain.
  CHECK(d.parts.contacts == 4);
  CHECK(d.parts.facets.size() == simple.facets.size() + 3);
  for (std::size_t k = 0; k < d.parts.contacts; ++k) CHECK(d.parts.facets[k].area == mc::test::relative(h * h / 4, 1e-12));
  const Vec<3> c = simple.facets[0].centroid;
  // Bending about y: the law's normal stress E₀ θ z/L over the parts, Σ A z² = 2 (h²/4)(h/3)² = h⁴/18, against
  // the whole square's h⁴/12 (2/3); torsion about x: α E₀/L Σ A r² = α E₀ h⁴/(9L) against h⁴/6 (2/3). The simple
  // facet, all its area at c, has neither. Round-off of the vertices' circumcentres: 1e-9.
  CHECK(rotational_stiffness(simple, c, Eigen::Vector3d::UnitY()) < 1e-9 * kE0 * h * h * h);
  CHECK(rotational_stiffness(d.parts, c, Eigen::Vector3d::UnitY()) ==
        mc::test::relative(kE0 / h * h * h * h * h / 18, 1e-9));
  CHECK(rotational_stiffness(d.parts, c, Eigen::Vector3d::UnitX()) ==
        mc::test::relative(kAlpha * kE0 / h * h * h * h * h / 9, 1e-9));
  // A translation strains every part as it strains the centroid: the same E₀ A/L normal, α E₀ A/L shear.
  for (const Vec<3>& move : {Vec<3>(1, 0, 0), Vec<3>(0, 1, 0), Vec<3>(0.3, -0.5, 0.8)})
    CHECK(translational_stiffness(d.parts, move) == mc::test::relative(translational_stiffness(simple, move), 1e-12));
  CHECK(translational_stiffness(d.parts, Vec<3>(1, 0, 0)) == mc::test::relative(kE0 * h, 1e-12));
}

TEST_CASE("a_discretized_segment_facet_keeps_three_quarters_of_its_bending_stiffness_in_2d") {
  const double h = 0.01;
  const Tessellation<2> simple = tessellate(std::vector<Vec<2>>{{0.5 * h, 0.5 * h}, {1.5 * h, 0.5 * h}},
                                            SpecimenShape<2>::box(Vec<2>(2 * h, h)), 3 * h);
  REQUIRE(simple.contacts == 1);
  const FacetParts<2> d = discretize_facets(simple);
  REQUIRE(d.parts.contacts == 2);
  const Vec<2> c = simple.facets[0].centroid;
  // Σ A y² = 2 (h/2)(h/4)² = h³/16 per metre of thickness, against the whole segment's h³/12 (3/4).
  CHECK(rotational_stiffness(simple, c, Eigen::Vector3d::UnitZ()) < 1e-9 * kE0 * h * h);
  CHECK(rotational_stiffness(d.parts, c, Eigen::Vector3d::UnitZ()) ==
        mc::test::relative(kE0 / h * h * h * h / 16, 1e-9));
  CHECK(translational_stiffness(d.parts, Vec<2>(0.6, 0.8)) ==
        mc::test::relative(translational_stiffness(simple, Vec<2>(0.6, 0.8)), 1e-12));
  // Each point of the facet belongs to the half it lies in.
  CHECK(part_holding(d.parts, d.first, 0, Vec<2>(h, 0.2 * h)) == (d.parts.facets[0].centroid.y() < c.y() ? 0u : 1u));
  CHECK(part_holding(d.parts, d.first, 0, Vec<2>(h, 0.8 * h)) == (d.parts.facets[0].centroid.y() < c.y() ? 1u : 0u));
}

TEST_CASE("a_point_of_a_discretized_facet_belongs_to_the_triangle_that_holds_it") {
  const double h = 0.01;
  const Tessellation<3> simple =
      tessellate(mc::test::cubic_grid_nodes(h, 2, 1, 1), SpecimenShape<3>::box(Vec<3>(2 * h, h, h)), 3 * h);
  const FacetParts<3> d = discretize_facets(simple);
  // The fan of a square about its centre: the triangle towards +y has its centroid h/3 from the centre along y.
  for (const Vec<3>& towards : {Vec<3>(0, 1, 0), Vec<3>(0, -1, 0), Vec<3>(0, 0, 1), Vec<3>(0, 0, -1)}) {
    const Vec<3> c = simple.facets[0].centroid, x = c + 0.4 * h * towards + 0.05 * h * Vec<3>(0, 1, 1);
    const std::size_t k = part_holding(d.parts, d.first, 0, x);
    CHECK((d.parts.facets[k].centroid - (c + h / 3 * towards)).norm() < 1e-9 * h);
    CHECK(facet_of_part(d.first, k) == 0);  // the way back, as a fibre crossing found on any part takes it
  }
}

// K_discretized = K_simple + Σ A_i (R Δ_i)ᵀ E (R Δ_i), Δ_i the rotation terms of the parts' offsets c_i − c: the
// cross terms vanish because Σ A_i (c_i − c) = 0. So the parts only add a positive semi-definite stiffness, and under
// the same load the cantilever deflects less, never more. What they add is the facets' own bending, a rigidity of
// the order of their second moments against the beam's, (l/h)²: it fades as the cells get finer (Květoň §3.3: "when
// the finer discretization is used, the influence of rotational stiffness decreases").
TEST_CASE("discretized_facets_only_add_rotational_stiffness_whose_effect_on_a_cantilever_fades_with_finer_cells") {
  const double L = 0.2, h = 0.02, F = 1.0;
  const Elastic e = macroscopic(3, 48e9, 0.29);
  const double I = h * h * h * h / 12, G = e.E / (2 * (1 + e.nu)), kappa = 10 * (1 + e.nu) / (12 + 11 * e.nu);
  const double beam = F * L * L * L / (3 * e.E * I) + F * L / (kappa * G * h * h);
  double stiffening[2], parts_deflection = 0;
  const double sizes[2] = {5e-3, 2.5e-3};
  for (int k = 0; k < 2; ++k) {
    const double simple = cantilever_deflection(sizes[k], FacetIntegration::Simple);
    const double parts = cantilever_deflection(sizes[k], FacetIntegration::Discretized);
    MESSAGE("l_min " << sizes[k] << " m: tip deflection simple " << simple << " m, discretized " << parts
                     << " m, beam theory " << beam << " m");
    CHECK(parts < simple);
    stiffening[k] = simple / parts - 1;
    parts_deflection = parts;
  }
  // Halving the cells must more than halve the stiffening ((l/h)² quarters it; the two packings differ).
  CHECK(stiffening[1] < 0.5 * stiffening[0]);
  // With eight cells over the depth the discretized beam is Timoshenko's within 10 %: the simple facets' beam reads
  // 4 % stiff on this packing (6.00 against 6.27 µm), the parts stiffen it by 3 % more, of the order of
  // (l/h)² = 1.6 %; a wrong kinematics of the parts is off by far more.
  CHECK(parts_deflection == mc::test::relative(beam, 0.10));
}
