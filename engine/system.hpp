// What the runner (studies/runner.cpp) needs of a solver family: advance in time, tell where it is, sample the
// histories its scene declares, describe its specimen and frames, report its cracks, save and restore its state.
// The explicit particle world implements it (scene/explicit_system.hpp), and so does the rigid-cell model. It is
// dimension-free, so the runner, the output and the studies are written once for every solver and dimension.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "engine/archive.hpp"
#include "engine/crack.hpp"

namespace mc {

// A named time series the scene records, sampled when a history row is written.
struct Series {
  std::string name, unit;
  std::function<double()> sample;  // empty when only the names are wanted
};

// Polygons over a list of points: polygon k has the points corner[start[k]] .. corner[start[k + 1] − 1], in order
// around it (a 2D facet: its two ends).
struct Polygons {
  std::vector<std::int64_t> start{0}, corner;
  std::size_t size() const { return start.size() - 1; }
  void add(const std::vector<std::int64_t>& corners) {
    corner.insert(corner.end(), corners.begin(), corners.end());
    start.push_back(static_cast<std::int64_t>(corner.size()));
  }
};

// The cells of a specimen of rigid cells, as built (README, "Output file", /specimen/cells): each cell's own copy of
// its corners, so that a cell drawn from them moves with the cell; the facets (between two cells, then on the
// specimen's surface) as polygons over their first cell's corners; and each cell's surface as polygons (3D: its
// facets; 2D: its outline). Empty for a specimen of particles.
struct CellGeometry {
  std::vector<double> corner;                  // C·D, cell after cell
  Polygons facets;                             // over the corners of the facet's cell a
  std::vector<std::int64_t> facet_a, facet_b;  // per facet, its two cells (b = −1: the specimen's surface)
  std::size_t contacts = 0;                    // facets [0, contacts) join two cells
  Polygons faces;                              // each cell's surface, cell after cell
  std::vector<std::int64_t> face_cell;         // per face, its cell
  bool empty() const { return corner.empty(); }
};

// The short fibres of a specimen of rigid cells (README, "Output file", /specimen/fibres), as placed: each a polyline
// from its end a through the points where it crosses contact facets, in order, to its end b; its family and how
// many facets it crosses. Empty without fibres.
struct FibreGeometry {
  std::vector<double> point;  // P·3
  Polygons lines;             // over point, fibre after fibre
  std::vector<std::int32_t> family, crossings;
  bool empty() const { return family.empty(); }
};

// What a fibre does in a frame, its most advanced crossing's (CellFrame::fibre_state).
enum class FibreState { Idle = 0, Bridging = 1, PulledOut = 2, Ruptured = 3 };

// One frame of the cells: their corners (C·D, as CellGeometry::corner) moved with them, and each contact facet's
// damage; and per fibre its state (FibreState as a number), the largest force any of its crossings carries [N] and
// the largest pull-out of a side [m].
struct CellFrame {
  std::vector<double> corner, damage;
  std::vector<double> fibre_state, fibre_force, fibre_slip;
};

// The contacts between particles in one frame (README, "Output file", /contacts): each pair that touches or holds a
// bond, its two bodies' rows, its normal force (positive in compression) and the magnitude of its shear force [N],
// whether a bond holds it, and the branch vector x_B − x_A [m], D per contact. `recorded` is false when the scene
// keeps no contacts in its frames.
struct ContactFrame {
  bool recorded = false;
  std::vector<std::int64_t> pair, bonded;  // pair: 2 per contact
  std::vector<double> normal_force, shear_force, branch;
  std::size_t size() const { return normal_force.size(); }
};

// The specimen as built, as the output file keeps it (README, "Output file").
struct SpecimenData {
  int dimension;
  std::vector<double> x, radius;  // x: N·D
  std::vector<std::int32_t> phase;
  std::vector<std::string> phase_names;
  std::vector<std::int64_t> id;                       // the specimen's own ids (bodies may be renumbered for locality)
  std::vector<std::pair<std::string, double>> facts;  // what generating it measured (porosity, bonds per phase pair …)
  std::vector<std::vector<std::array<double, 2>>> outlines;  // aggregate outlines in the picture plane
  CellGeometry cells;                                        // a specimen of rigid cells: their polygons
  FibreGeometry fibres;                                      // and its fibres
};

// Rows of the crack log: one per bond break or first yield (README, "Output file", /cracks).
struct CrackRows {
  std::vector<std::int64_t> step, mode, kind, phase_a, phase_b, model, id_a, id_b;
  std::vector<double> time, position, normal;  // position, normal: D per row
  std::size_t size() const { return step.size(); }

  // One crack as a row, its bodies named by the specimen's ids.
  template <int D>
  void add(const Crack<D>& c, std::int64_t body_a, std::int64_t body_b) {
    step.push_back(c.step);
    mode.push_back(static_cast<std::int64_t>(c.mode));
    kind.push_back(static_cast<std::int64_t>(c.kind));
    phase_a.push_back(c.phase_a);
    phase_b.push_back(c.phase_b);
    model.push_back(c.set);
    id_a.push_back(body_a);
    id_b.push_back(body_b);
    time.push_back(c.time);
    position.insert(position.end(), c.position.data(), c.position.data() + D);
    normal.insert(normal.end(), c.normal.data(), c.normal.data() + D);
  }
};

class System {
 public:
  virtual ~System() = default;
  virtual int dimension() const = 0;

  // A new run: contacts found, bonds installed, the energy origin set. A resumed run calls restore() instead.
  // Throws InputError when the scene asks for what the state refuses (a fixed timestep above the critical one).
  virtual void start() = 0;
  // One step, and what the scene observes every step. Throws InstabilityError when the state refuses to go on.
  virtual void step() = 0;
  virtual std::int64_t step_count() const = 0;
  virtual double time() const = 0;
  virtual double timestep() const = 0;
  // Throws InstabilityError naming the step, the body and the likely cause.
  virtual void check_stability() const = 0;

  // The scene's histories in its order; the samplers read this system and stay valid while it lives.
  virtual const std::vector<Series>& histories() const = 0;
  // Brings what the samplers read up to date; called before each row is sampled (a split world gathers the
  // particles they observe: its processes call it, and sample the row, together).
  virtual void before_row() {}
  virtual SpecimenData specimen() const = 0;
  // Positions, velocities and forces of every body, N·D values each: one frame of the output.
  virtual void frame(std::vector<double>& x, std::vector<double>& v, std::vector<double>& force) const = 0;
  // A specimen of cells (SpecimenData::cells): where its cells' corners are and the damage of its contact facets,
  // for the same frame. Nothing for a specimen of particles.
  virtual CellFrame cell_frame() const { return {}; }
  // The contacts for the same frame, when the scene keeps them (else not `recorded`). A split world's processes call
  // it together, and process 0 gets them all.
  virtual ContactFrame contact_frame() const { return {}; }

  // The crack log: the models that write to it (empty: the scene keeps no log), how many entries it has, and its
  // entries from `first` on.
  virtual std::vector<std::string> crack_models() const = 0;
  virtual std::size_t crack_count() const = 0;
  virtual CrackRows cracks(std::size_t first) const = 0;

  // The complete dynamic state: restoring it and stepping on gives the same bits as never stopping.
  virtual void save(Archive& a) const = 0;
  virtual void restore(const Archive& a) = 0;
  // A run split across processes: how many particles each owned when split and at the end, and how often the
  // regions were drawn afresh (for the closing line). "" for a run in one process. Every process calls it.
  virtual std::string balance_report() const { return ""; }
  // What a measured part of the run cost of its `wall_seconds` (the rigid cells' fibres: their evaluation, secants and
  // forces), for the closing line; "" when the system measures none.
  virtual std::string cost_report(double /*wall_seconds*/) const { return ""; }
};

}  // namespace mc
