// Fibres bridging the cracks between rigid cells, through the real `mesocrack` command on the scenes of Květoň
// §6.1-6.2: one fibre across a cracked contact follows the crossing's law (fibre_pullout.hpp) through debonding, the
// drop and the slide; fibres across an intact contact lift the load above the matrix's peak only beyond a volume
// fraction; under central differences a free cell between two fibres holds each at its law; and bad fibre input
// is refused naming the key.
#include <algorithm>

#include "engine/crack.hpp"
#include "rigid_cell/fibre_pullout.hpp"
#include "tests/common/cli_harness.hpp"
#include "tests/common/relative.hpp"

namespace {

using mc::rigid_cell::FibreBridge;
using mc::rigid_cell::FibreMaterial;

std::string pullout_scene() { return slurp(kScenes / "fibre_pullout_two_sided_3d.toml"); }
std::string contact_scene() { return slurp(kScenes / "fibre_contact_volume_fraction_3d.toml"); }

struct Curve {
  std::vector<double> u, force;
  double final_pulled_out = 0, final_ruptured = 0;
};

Curve run_curve(const TempDir& d, const std::string& name, const std::string& text, std::vector<std::string> set = {}) {
  write_file(d / (name + ".toml"), text);
  std::vector<std::string> args = {"run", name + ".toml", "-o", name + ".h5"};
  for (const std::string& s : set) args.push_back("--set"), args.push_back(s);
  const Result r = mesocrack(args, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / (name + ".h5")).string(), mc::H5File::Mode::ReadOnly);
  Curve c{f.read_doubles("/history/group.right.disp_x"), f.read_doubles("/history/group.right.reaction_x")};
  c.final_pulled_out = f.read_doubles("/history/fibres.pulled_out").back();
  c.final_ruptured = f.read_doubles("/history/fibres.ruptured").back();
  return c;
}

// §6.1's fibre: E_f 30 GPa, d_f 40 µm, f_tf 1000 MPa, τ_0 2 MPa, G_d 5 N/m, β_f 0.
FibreMaterial kveton_fibre() {
  FibreMaterial f;
  f.modulus = 30e9, f.diameter = 40e-6, f.tensile_strength = 1000e6, f.friction_stress = 2e6, f.debonding_energy = 5;
  return f;
}

}  // namespace

TEST_CASE("two_sided_pullout_scene_follows_the_crossing_law_through_debonding_the_drop_and_the_slide") {
  const TempDir d;
  const Curve c = run_curve(d, "pullout", pullout_scene());
  // The fibre lies along the pull: the crossing opens by the plate's travel. The law alone, stepped alike.
  const FibreMaterial f = kveton_fibre();
  FibreBridge b;
  b.sides.embedment[0] = 6.5e-3, b.sides.embedment[1] = 3.5e-3;
  double peak = 0, peak_at = 0, largest_gap = 0;
  for (std::size_t i = 1; i < c.u.size(); ++i) {
    // The first step cracks the facet (the fibre joins from the next one): from there on the reaction is the
    // fibre's, plus what the facet's 1 kPa matrix still carries (at most 4 mN, and softening away).
    if (i >= 2) largest_gap = std::max(largest_gap, std::abs(c.force[i] - bridge_force(f, b, c.u[i], 0.0)));
    if (c.force[i] > peak) peak = c.force[i], peak_at = c.u[i];
  }
  MESSAGE("peak " << peak << " N at " << peak_at * 1e6 << " um; largest gap to the law " << largest_gap << " N");
  CHECK(largest_gap < 4e-3);
  // Květoň Fig. 6.1: the short side debonded whole at 2 v_d (v_d = 61.0 µm), 1.097 N; the drop to its friction
  // P_0 = π 3.5 mm d_f τ_0 = 0.880 N; pulled out after 3.5 mm more. A step is 2 µm: the peak is the step's.
  CHECK(peak == mc::test::relative(debonding_force(f, full_debonding_slip(f, 3.5e-3)), 1e-3));
  CHECK(peak_at == mc::test::relative(2 * full_debonding_slip(f, 3.5e-3), 0.02));
  const auto after = std::find_if(c.u.begin(), c.u.end(), [&](double u) { return u > peak_at + 1e-6; });
  const double dropped = c.force[static_cast<std::size_t>(after - c.u.begin())];
  CHECK(dropped == mc::test::relative(friction_force(f, 3.5e-3), 0.01));
  CHECK(c.force.back() == 0.0);
  CHECK(c.final_pulled_out == 1);
  CHECK(c.final_ruptured == 0);
}

TEST_CASE("two_sided_pullout_of_a_fibre_too_long_breaks_it_while_it_debonds") {
  const TempDir d;
  // §6.1's 20 mm fibre, 7 mm on the right: the force of both sides debonding reaches f_tf π d_f²/4 = 1.2566 N at an
  // opening of 2 (P²/k − G_d)/τ_0 = 161.6 µm, before the short side is debonded (2 v_d = 2 × 123 µm).
  std::string s = pullout_scene();
  s = edit(s, "ends = [\"8.5 mm\", \"1 mm\", \"1 mm\", \"18.5 mm\", \"1 mm\", \"1 mm\"]",
           "ends = [\"2 mm\", \"1 mm\", \"1 mm\", \"22 mm\", \"1 mm\", \"1 mm\"]");
  const Curve c = run_curve(d, "long", s, {"run.steps=100"});
  const double peak = *std::max_element(c.force.begin(), c.force.end());
  const auto broken = std::find(c.force.begin() + 2, c.force.end(), 0.0);
  REQUIRE(broken != c.force.end());
  const double at = c.u[static_cast<std::size_t>(broken - c.force.begin())];
  MESSAGE("peak " << peak << " N; broken at " << at * 1e6 << " um");
  CHECK(peak < 1000e6 * 0.25 * M_PI * 40e-6 * 40e-6);
  CHECK(at == mc::test::relative(161.6e-6, 0.02));  // within the 2 µm step
  CHECK(c.final_ruptured == 1);
}

TEST_CASE("fibres_lift_the_load_of_a_cracked_contact_above_its_first_peak_only_beyond_one_percent") {
  const TempDir d;
  // Květoň §6.2: the matrix's elastic limit, then a drop (the fibres' force depends on the opening, still near zero),
  // then the fibres' own rise. V_f = n π d_f²/4 / (2 mm × 2 mm).
  for (const int n : {1, 2, 10, 20, 40}) {
    CAPTURE(n);
    const Curve c = run_curve(d, "n" + std::to_string(n), contact_scene(),
                              {"rigid_cell.fibres[0].count=" + std::to_string(n), "output.history_every=1"});
    std::size_t i = 0;
    while (i + 1 < c.force.size() && c.force[i + 1] >= c.force[i]) ++i;
    const double first = c.force[i];
    std::size_t j = i + 1;
    while (j + 1 < c.force.size() && c.force[j + 1] <= c.force[j]) ++j;
    const double trough = c.force[j], second = *std::max_element(c.force.begin() + static_cast<std::ptrdiff_t>(j), c.force.end());
    const double vf = n * 0.25 * M_PI * 40e-6 * 40e-6 / 4e-6;
    MESSAGE("n " << n << " (V_f " << 100 * vf << " %): first peak " << first << " N, drop to " << trough
                 << " N, second peak " << second << " N");
    CHECK(trough < 0.9 * first);  // the sudden drop
    // "only for V_f > 1 % the force exceeds the initial peak" (§6.2), measured, not set: with 20 fibres (0.63 %)
    // the second peak is 0.69 of the first, with 40 (1.26 %) 1.10 of it. The first peak grows with n, as the
    // thesis says of G_d > 0: each fibre starts at P(0) = 0.22 N once the facet cracks.
    CHECK((second > first) == (vf > 0.01));
    CHECK(c.final_pulled_out + c.final_ruptured == n);  // all out in the end
  }
}

TEST_CASE("fibre_bad_input_names_the_key_and_what_it_allows") {
  const TempDir d;
  const std::string s = contact_scene();
  check_edits_refused(
      d.dir, s,
      {{"count = 20", "volume_fraction = 0", {"rigid_cell.fibres[0].volume_fraction", "0", "out of range"}},
       {"count = 20", "volume_fraction = 1", {"rigid_cell.fibres[0].volume_fraction", "1", "out of range"}},
       {"length = \"10 mm\"", "length = \"30 mm\"", {"rigid_cell.fibres[0].length", "longer than the specimen"}},
       {"diameter = \"0.04 mm\"", "diameter = 0", {"rigid_cell.fibres[0].diameter", "out of range"}},
       {"orientation = \"aligned\"", "orientation = \"random\"", {"rigid_cell.fibres[0].orientation", "random", "isotropic"}},
       {"count = 20", "count = 20\nvolume_fraction = 0.01", {"volume_fraction", "count"}},
       {"kind = \"voronoi_cells\"", "kind = \"random_packing\"", {"rigid_cell.fibres", "voronoi_cells"}},
       {"nodes = [\"5 mm\", \"1 mm\", \"1 mm\", \"15 mm\", \"1 mm\", \"1 mm\"]",
        "nodes = [\"5 mm\", \"1 mm\", \"1 mm\", \"25 mm\", \"1 mm\", \"1 mm\"]",
        {"specimen.nodes", "node 1", "outside"}}});
  // A 2D scene: its specimen read, its fibres refused.
  std::string flat = edit(s, "dimension = 3", "dimension = 2");
  flat = edit(flat, "size = [\"20 mm\", \"2 mm\", \"2 mm\"]", "size = [\"20 mm\", \"2 mm\"]");
  flat = edit(flat, "nodes = [\"5 mm\", \"1 mm\", \"1 mm\", \"15 mm\", \"1 mm\", \"1 mm\"]",
              "nodes = [\"5 mm\", \"1 mm\", \"15 mm\", \"1 mm\"]");
  write_file(d / "scene.toml", flat);
  check_refused(d.dir, {"run", "scene.toml"}, 2, {"rigid_cell.fibres[0]", "3D", "scene.toml"});
}

TEST_CASE("fibre_prism_is_the_same_for_any_thread_count_and_resumed_gives_the_same_bits") {
  const TempDir d;
  const std::string scene = (kScenes / "fibre_prism_tension_3d.toml").string();
  // Eight 5 µm steps on cells twice as coarse (l_min 5 mm): the first crack and the fibres across it taking part.
  const std::vector<std::string> steps = {"--set", "run.steps=8",          "--set", "output.checkpoint_every=5",
                                          "--set", "output.frame_every=5", "--set", "specimen.l_min=0.005"};
  auto run = [&](std::vector<std::string> args) {
    args.insert(args.end(), steps.begin(), steps.end());
    const Result r = mesocrack(args, d.dir);
    REQUIRE_MESSAGE(r.code == 0, r.describe());
  };
  run({"run", scene, "-o", "one.h5", "--threads", "1"});
  run({"run", scene, "-o", "two.h5", "--threads", "2"});
  const mc::H5File f((d / "one.h5").string(), mc::H5File::Mode::ReadOnly);
  REQUIRE(f.read_doubles("/history/fibres.bridging").back() > 100);
  check_same_run(d / "one.h5", d / "two.h5");
  const Result first = mesocrack({"run", scene, "-o", "parts.h5", "--set", "run.steps=5", "--set",
                                  "output.checkpoint_every=5", "--set", "output.frame_every=5", "--set",
                                  "specimen.l_min=0.005"},
                                 d.dir);
  REQUIRE_MESSAGE(first.code == 0, first.describe());
  run({"run", scene, "--resume", "parts.h5"});
  check_same_run(d / "one.h5", d / "parts.h5");
}

TEST_CASE("aligned_fibres_harden_the_prism_after_its_first_crack_and_it_cracks_again_elsewhere") {
  const TempDir d;
  // Květoň §6.3's prism (scenes/fibre_prism_tension_3d.toml) to 80 µm, 16 steps of 5 µm: the first crack at the
  // matrix's strength, a drop, then the fibres across the cracks carry more and more, and new cracks open.
  const Result r = mesocrack({"run", (kScenes / "fibre_prism_tension_3d.toml").string(), "-o", "prism.h5", "--set",
                              "run.steps=16", "--set", "rigid_cell.crack_log=true"},
                             d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "prism.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto load = f.read_doubles("/history/group.right.reaction_x");
  std::size_t i = 0;
  while (i + 1 < load.size() && load[i + 1] >= load[i]) ++i;
  const double first = load[i];
  std::size_t j = i + 1;
  while (j + 1 < load.size() && load[j + 1] <= load[j]) ++j;
  const double last = load.back();
  MESSAGE("first crack " << first << " N, drop to " << load[j] << " N, at 80 um " << last << " N");
  // The matrix alone: f_t A = 3.8 MPa × 200 mm² = 760 N at most; measured 600 N, 478 N, 1446 N.
  CHECK(first < 760);
  CHECK(load[j] < first);
  // Strain hardening is last > first; 1.5 keeps room below the measured 2.2 for another machine's last bits.
  CHECK(last > 1.5 * first);
  // Cracking spread, not one crack: one crack across this prism breaks 82 facets (measured with the prism held at its
  // last 2.5 mm only, where it cracked once and softened); here more than twice as many break, over a stretch longer
  // than a fibre.
  const auto kind = f.read_ints("/cracks/kind");
  std::vector<hsize_t> dims;
  const auto position = f.read_doubles("/cracks/position", &dims);
  std::vector<double> x;
  for (std::size_t k = 0; k < kind.size(); ++k)
    if (kind[k] == static_cast<int>(mc::CrackKind::Break)) x.push_back(position[3 * k]);
  REQUIRE(!x.empty());
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  MESSAGE(x.size() << " facets broken, from x = " << *lo * 1e3 << " to " << *hi * 1e3 << " mm");
  CHECK(x.size() > 2 * 82);
  CHECK(*hi - *lo > 10e-3);
}

TEST_CASE("two_sided_pullout_under_newmark_steps_is_the_static_one_when_inertia_is_negligible") {
  const TempDir d;
  // The §6.1 scene in Newmark steps of 1 s: the cells' mass (0.13 g) at a 2 µm/s pull has no say, so the reaction
  // is the static one: the fibres' secants in the effective stiffness (8.4) reach the same equilibrium.
  const std::string dynamic = edit(pullout_scene(), "[rigid_cell]\n", "[rigid_cell]\n\n[rigid_cell.dynamics]\n");
  const Curve s = run_curve(d, "static", pullout_scene(), {"run.steps=200"});
  const Curve n = run_curve(d, "newmark", dynamic, {"run.steps=200"});
  REQUIRE(s.force.size() == n.force.size());
  double largest = 0;
  for (std::size_t i = 2; i < s.force.size(); ++i) largest = std::max(largest, std::abs(s.force[i] - n.force[i]));
  MESSAGE("largest difference " << largest << " N");
  // Against forces of 0.3-1.1 N: the inertial force m a of cells moving at a constant 2 µm/s is nil, and the two
  // iterations stop at the same 1e-6 tolerances, so they differ by the tolerance at most.
  CHECK(largest < 1e-6);
  CHECK(*std::max_element(n.force.begin(), n.force.end()) > 1.0);
}

TEST_CASE("central_differences_hold_a_free_cell_between_two_fibres_each_at_its_crossing_law") {
  const TempDir d;
  // Three cells in a row, 10 mm each: the left held, the right pulled at 10 mm/s, the middle free, held only by two
  // fibres of §6.1 once its pre-cracked facets have let go: one across x = 10 mm (6 mm on the left, 4 mm in the
  // middle), its mirror across x = 20 mm. Explicit steps of 0.8 of the critical step; light mass damping (a_M
  // 2000/s: a damping ratio of 0.05 on the 2·10⁴ rad/s the fibres hold the middle cell at) lets the ringing after
  // each facet cracks die out. Each fibre's force is then the law's at its own facet's opening: the left one at
  // the middle cell's travel, the right one at the plate's less that.
  std::string text = pullout_scene();
  text = edit(text, "ends = [\"8.5 mm\", \"1 mm\", \"1 mm\", \"18.5 mm\", \"1 mm\", \"1 mm\"]",
              "ends = [\"4 mm\", \"1 mm\", \"1 mm\", \"14 mm\", \"1 mm\", \"1 mm\", \"16 mm\", \"1 mm\", \"1 mm\", "
              "\"26 mm\", \"1 mm\", \"1 mm\"]");
  text = edit(text, "nodes = [\"7.5 mm\", \"1 mm\", \"1 mm\", \"22.5 mm\", \"1 mm\", \"1 mm\"]",
              "nodes = [\"5 mm\", \"1 mm\", \"1 mm\", \"15 mm\", \"1 mm\", \"1 mm\", \"25 mm\", \"1 mm\", \"1 mm\"]");
  text = edit(text, "box_hi = [\"15 mm\", \"2 mm\", \"2 mm\"]", "box_hi = [\"10 mm\", \"2 mm\", \"2 mm\"]");
  text = edit(text, "box_lo = [\"15 mm\", 0, 0]", "box_lo = [\"20 mm\", 0, 0]");
  text = edit(text, "velocity = [\"2 um/s\", 0, 0]", "velocity = [\"10 mm/s\", 0, 0]");
  text = edit(text, "[rigid_cell]\n",
              "[rigid_cell]\n\n[rigid_cell.dynamics]\nscheme = \"central_difference\"\nmass_damping = \"2000 1/s\"\n");
  text = edit(text, "fixed = \"1 s\"", "safety = 0.8");
  text = edit(text, "steps = 1900", "duration = \"50 ms\"");
  text = edit(text, "history_every = 1", "history_every = 20");
  text += "\n[[groups]]\nname = \"middle\"\nbox_lo = [\"10 mm\", 0, 0]\nbox_hi = [\"20 mm\", \"2 mm\", \"2 mm\"]\n";
  write_file(d / "row.toml", text);
  const Result r = mesocrack({"run", "row.toml", "-o", "row.h5"}, d.dir);
  REQUIRE_MESSAGE(r.code == 0, r.describe());
  const mc::H5File f((d / "row.h5").string(), mc::H5File::Mode::ReadOnly);
  const auto u = f.read_doubles("/history/group.right.disp_x"), m = f.read_doubles("/history/group.middle.disp_x");
  const auto right = f.read_doubles("/history/group.right.reaction_x"),
             left = f.read_doubles("/history/group.left.reaction_x");
  const FibreMaterial fibre = kveton_fibre();
  FibreBridge a, b;
  a.sides.embedment[0] = 6e-3, a.sides.embedment[1] = 4e-3;
  b.sides.embedment[0] = 4e-3, b.sides.embedment[1] = 6e-3;
  // The right plate's reaction also holds its own cell's mass damping, a_M ρ V v (2000/s · 2100 kg/m³ · 40 mm³ ·
  // 10 mm/s = 1.68 mN), which a static solve has not.
  const double plate_damping = 2000 * 2100 * 40e-9 * 0.01;
  const std::size_t top = static_cast<std::size_t>(std::max_element(right.begin(), right.end()) - right.begin());
  double largest_gap = 0, largest_asymmetry = 0;
  for (std::size_t i = 1; i <= top; ++i) {
    const double fa = bridge_force(fibre, a, m[i], 0.0), fb = bridge_force(fibre, b, u[i] - m[i], 0.0);
    if (u[i] > 2e-6)
      largest_gap = std::max({largest_gap, std::abs(-left[i] - fa), std::abs(right[i] - plate_damping - fb)});
    largest_asymmetry = std::max(largest_asymmetry, std::abs(2 * m[i] - u[i]));
  }
  MESSAGE("peak " << right[top] << " N at " << u[top] * 1e6 << " um; largest gap to the law before it " << largest_gap
                  << " N, largest |2 u_middle - u| " << largest_asymmetry * 1e6 << " um; at the end the middle cell at "
                  << m.back() * 1e6 << " of " << u.back() * 1e6 << " um");
  // Up to the peak both fibres load: each force is its law's at its facet's opening, but for what the facets' 1 kPa
  // matrix still carries on the exponential tail of its softening (3.11): 4 mN at first, 5e-8 N measured past 2 µm.
  CHECK(largest_gap < 1e-6);
  // The middle cell halfway: the two fibres open alike but for its damping, a_M m v/2 = 0.84 mN over the fibres'
  // secant stiffness of some 10⁴ N/m (0.1 µm), and the ringing after the facets crack. 1 µm is 1 % of the openings.
  CHECK(largest_asymmetry < 1e-6);
  // The peak: the 4 mm sides debonded whole at 2 v_d (Květoň Fig. 6.1), the step's sampling within 1 %.
  const double debonded = debonding_force(fibre, full_debonding_slip(fibre, 4e-3));
  CHECK(right[top] - plate_damping == mc::test::relative(debonded, 0.01));
  // Past it two softening links in series: one opens on, the other unloads along its secant (the middle cell goes
  // back towards it), and the two forces stay equal but for the middle cell's inertia and damping.
  const double opened = std::max(m.back(), u.back() - m.back());
  CHECK(opened > 0.75 * u.back());
  CHECK(u.back() > 2 * 2 * full_debonding_slip(fibre, 4e-3));
  CHECK(std::abs(-left.back() - (right.back() - plate_damping)) < 1e-3);
}
