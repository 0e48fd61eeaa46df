// One fibre pulled out of one side of a crack (Květoň §5.1–5.3, after Naaman et al. 1991 and Schauffert & Cusatis
// 2012): the bond debonds while the pull-out v grows to v_d, the force then slides on friction over the embedment
// L_e, with slip hardening or softening β_f, until the fibre is out; at an inclined exit point the matrix spalls,
// the fibre snubs (more force) and breaks sooner (less strength). Pure functions of one side: the two sides of a
// crack, the fibre's history and its coupling to the cells are built on them.
#pragma once

namespace mc::rigid_cell {

// A fibre's material: its keys, units and ranges are those of [rigid_cell.fibres].
struct FibreMaterial {
  double modulus = 0;             // E_f [Pa]
  double diameter = 0;            // d_f [m]
  double tensile_strength = 0;    // f_tf [Pa]
  double friction_stress = 0;     // τ_0 [Pa] (> 0), the frictional bond stress once debonded
  double debonding_energy = 0;    // G_d [N/m], the chemical bond's fracture energy
  double slip_hardening = 0;      // β_f [-]: > 0 the friction grows as the fibre slides, < 0 it falls
  double spalling_coefficient = 0;  // k_sp [-] (5.8); 0: no spalling
  double snubbing_coefficient = 0;  // k_sn [-] (5.9)
  double rupture_coefficient = 0;   // k_rup [-] (5.10)
};

// (5.1), v ≤ v_d: the force while the bond debonds, P = √(π² E_f d_f³ (τ_0 v + G_d)/2); at v = 0 it is already
// √(π² E_f d_f³ G_d/2), the force that starts debonding.
double debonding_force(const FibreMaterial& f, double v);
// (5.2): the pull-out at which an embedment L_e is debonded whole, v_d = 2τ_0 L_e²/(E_f d_f) + √(8 G_d L_e²/(E_f d_f)).
// The thesis writes D_f in the first term; d_f it must be: only then is (5.1) continuous at v_d for G_d = 0.
double full_debonding_slip(const FibreMaterial& f, double embedment);
// (5.3): the frictional force over the whole embedment, P_0 = π L_e d_f τ_0.
double friction_force(const FibreMaterial& f, double embedment);
// (5.1), v > v_d: P_0 (1 − s/L_e)(1 + β_f s/d_f), s = v − v_d the slide; 0 once the fibre is out (s ≥ L_e) or
// once slip softening has worn the friction away (1 + β_f s/d_f ≤ 0: from there on it stays 0).
double sliding_force(const FibreMaterial& f, double embedment, double v);
// Both branches of (5.1) over an embedment L_e.
double pullout_force(const FibreMaterial& f, double embedment, double v);
// (5.5): the length debonded at a pull-out v ≤ v_d, L_d = √(2 E_f d_f)/(2τ_0) (√(G_d + τ_0 v) − √G_d), the root of
// the quadratic (5.4) with v for v_d; evaluated as √(2 E_f d_f) v/(2(√(G_d + τ_0 v) + √G_d)), the same number
// without the cancellation where τ_0 v ≪ G_d.
double debonded_length(const FibreMaterial& f, double v);
// The work of pulling one side out whole, ∫₀^{v_d + L_e} P dv, in closed form: the debonding branch
// (2/3)√(π² E_f d_f³/2) ((τ_0 v_d + G_d)^{3/2} − G_d^{3/2})/τ_0, and the sliding one P_0 L_e (1/2 + β_f L_e/(6 d_f))
// (β_f ≥ −d_f/L_e, where the friction lasts to the end).
double pullout_work(const FibreMaterial& f, double embedment);

// (5.8): the spalling length at an exit point where the fibre is inclined θ from the facet normal and carries the
// normal force P_N, s_f = P_N sin(θ/2)/(k_sp f_t d_f cos²(θ/2)), f_t the matrix's tensile strength; 0 without
// spalling (k_sp = 0).
double spalling_length(const FibreMaterial& f, double normal_force, double theta, double matrix_strength);
// (5.9): the snubbing factor exp(k_sn φ'_f) on the force, φ'_f the angle between the fibre and the straining
// direction (5.6)–(5.7).
double snubbing_factor(const FibreMaterial& f, double phi);
// (5.10): the inclined fibre's strength f_tf exp(−k_rup φ'_f).
double inclined_strength(const FibreMaterial& f, double phi);

// One fibre across one crack (§5.1, Fig. 5.1): the crack's opening along the fibre, w = v_a + v_b, shared between the
// pull-outs of its two sides, each with its embedment. Pull-out is slip: it never goes back.
struct TwoSidedPullout {
  double embedment[2] = {0, 0};  // L_e of each side [m]
  double pullout[2] = {0, 0};    // v of each side [m]
  double force = 0;              // the force the fibre carries [N]
};

// What a side resists further pull-out with at v: the debonding force below v_d, the sliding force from v_d on (at
// v_d itself P_0: the bond is gone).
double pullout_resistance(const FibreMaterial& f, double embedment, double v);

// Opens the crack to w along the fibre (w at least the pull-outs' sum) and returns the force. The weaker side slides,
// the one that resists further pull-out less, while the other holds; both slide at one force while both resist more
// as they slide. So the two sides debond together (one law, v_a = v_b) until the shorter is debonded whole; its
// resistance then drops to P_0, or falls as it slides, and it pulls out while the longer side holds (Květoň Fig. 5.1);
// a side whose slide hardens (β_f > 0) may load the other again past its debonding, and both move on together. Found
// piece by piece between the points where a side's resistance turns (v_d, the top of a hardening slide), each piece by
// a closed form or bisection on a bracket. A crack closed below the pull-outs' sum leaves the fibre slack: force 0.
double open_crack(const FibreMaterial& f, TwoSidedPullout& t, double w);

// The length of a side debonded at pull-out v: (5.5) while it debonds, its whole embedment once debonded.
double side_debonded_length(const FibreMaterial& f, double embedment, double v);
// The bonded fibre's stiffness across a closed crack, E_f (π d_f²/4)/d_f: the stretch of one diameter of fibre at the
// exit points. (5.1) starts at P(0) > 0 with no opening, a rigid start no secant stiffness can follow; the fibre
// opens elastically at this stiffness until (5.1) is reached (P(0)/k: 0.23 µm for the fibre of §6.1, against
// v_d = 61 µm).
double bonded_stiffness(const FibreMaterial& f);

// One fibre across one crack with its history: the two sides' pull-outs, the opening the crack last loaded it to and
// the force there, and whether it has broken.
struct FibreBridge {
  TwoSidedPullout sides;
  double opening = 0;  // the largest opening along the fibre so far [m]
  double force = 0;    // the force at it [N]
  bool ruptured = false;
};

// The force a fibre bridges a crack with at the opening w along it, inclined φ'_f to the straining direction.
// Loading (w at or past the largest opening so far): the two-sided pull-out force times the snubbing factor (5.9),
// at most the bonded stiffness times w (the rigid start); where that reaches the inclined fibre's strength (5.10)
// over its section π d_f²/4 the fibre breaks: elasto-brittle (§5.4), it carries nothing from then on, whatever the
// crack does. Unloading and reloading (w below it): along the secant to the origin, the fibre's pull-outs kept, the
// same rule as the facets' damage (3.11). The debonded fibre's elastic spring-back (2 E_f A_f/(L_d^a + L_d^b), the
// slip staying) would be closer to a cyclic pull-out test, but its stiff branch below the largest opening meets the
// law's falling one above it at a sharp peak of the secant F/w, where the secant iteration of the implicit solvers
// swings without end (measured on the prism of §6.3: crossings whose side between two cracks is a few tens of µm,
// sliding, cycled by 1 % of the fibres' force through 5000 iterations). Below the largest opening the secant is
// constant: the iteration settles as it does for the facets.
double bridge_force(const FibreMaterial& f, FibreBridge& b, double w, double phi);
// The unloading stiffness of a bridge below its largest opening, the secant there [N/m].
double unloading_stiffness(const FibreBridge& b);

}  // namespace mc::rigid_cell
