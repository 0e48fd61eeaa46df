#include "studies/runner.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "scene/build_world.hpp"
#include "engine/errors.hpp"
#include "scene/histories.hpp"
#include "io/run_output.hpp"

namespace mc {

namespace {

using Clock = std::chrono::steady_clock;

// A stop condition and what it remembers (the peak, for post-peak conditions).
struct StopState {
  StopSpec spec;
  int column;
  double peak = -kInf;
};

template <int D>
SpecimenData specimen_data(const World<D>& w, const Scene& s) {
  SpecimenData d{D, {}, w.particles.radius, {}, {}, w.ids, w.specimen_facts, w.outlines};
  for (const auto& x : w.particles.x) d.x.insert(d.x.end(), x.data(), x.data() + D);
  d.phase.assign(w.particles.phase.begin(), w.particles.phase.end());
  for (const auto& p : s.phases) d.phase_names.push_back(p.name);
  return d;
}

template <int D>
std::vector<std::pair<std::string, double>> generate(const Scene& s, const std::string& output) {
  const World<D> w = build_world<D>(s);  // the genesis happens here
  RunOutput out(output, s.text, s.file, specimen_data(w, s));
  std::vector<double> x, zero(static_cast<std::size_t>(w.particles.size()) * D, 0.0);
  for (const auto& p : w.particles.x) x.insert(x.end(), p.data(), p.data() + D);
  out.append_frame(0.0, 0, x, zero, zero);  // at rest: a scene loads it with kind = "output"
  out.set_status("finished", "generated specimen");
  out.flush();
  auto facts = w.specimen_facts;
  facts.insert(facts.begin(), {"particles", static_cast<double>(w.particles.size())});
  return facts;
}

template <int D>
class Run {
 public:
  Run(const Scene& s, const RunOptions& o) : scene_(s), opt_(o), world_(build_world<D>(s)), obs_(s) {
    check_probes();
    series_ = make_series<D>(s, &world_, &obs_);
    for (const auto& st : s.stops) stops_.push_back({st, column_of(st.quantity)});
    buffer_.resize(series_.size());
  }

  RunResult run() {
    start_or_resume();
    const auto t0 = Clock::now();
    auto last_flush = t0, last_checkpoint = t0, last_progress = t0;
    RunResult r;
    try {
      while (true) {
        if (const std::string why = finished(); !why.empty()) {
          r.status = why;
          break;
        }
        world_.step();
        if (!scene_.regions.empty()) obs_.every_step(world_, scene_);
        const std::int64_t s = world_.step_count;
        if (s % scene_.guard_every == 0) world_.check_stability();
        if (s % scene_.history_every == 0) record();
        if (scene_.frame_every > 0 && s % scene_.frame_every == 0) frame();
        if ((s & 63) == 0) {
          const auto now = Clock::now();
          const bool due = scene_.checkpoint_every > 0 ? s % scene_.checkpoint_every == 0
                                                       : now - last_checkpoint > std::chrono::seconds(60);
          if (due) checkpoint(), last_checkpoint = now, last_flush = now;
          if (now - last_flush > std::chrono::seconds(2)) flush_history(), out_->flush(), last_flush = now;
          if (now - last_progress > std::chrono::milliseconds(500)) progress(t0, now), last_progress = now;
        } else if (scene_.checkpoint_every > 0 && s % scene_.checkpoint_every == 0) {
          checkpoint(), last_checkpoint = last_flush = Clock::now();
        }
      }
    } catch (const InstabilityError& e) {
      flush_history();
      out_->set_status("unstable", e.what());
      out_->flush();
      out_->write_csv();
      if (progress_shown_) std::fputc('\n', stderr);
      throw;
    }
    // The final state is always in the histories and the frames, once: the loop may have written it already,
    // and a resumed run that had already ended writes nothing new.
    if (last_record_step_ != world_.step_count) record();
    if (last_frame_step_ != world_.step_count) frame();
    checkpoint();
    out_->set_status(r.status == "finished" ? "finished" : "stopped", r.status);
    out_->flush();
    out_->write_csv();
    if (progress_shown_) std::fputc('\n', stderr);
    r.steps = world_.step_count;
    r.time = world_.time;
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return r;
  }

 private:
  void check_probes() const {
    for (const auto& p : scene_.probes)
      for (std::int64_t id : p.particles)
        if (std::find(world_.ids.begin(), world_.ids.end(), id) == world_.ids.end())
          throw InputError(scene_.file + ": probe '" + p.name + "': particle " + std::to_string(id) +
                           " does not exist (the specimen has " + std::to_string(world_.particles.size()) +
                           " particles; probes name them by their specimen ids)");
  }

  int column_of(const std::string& name) const {
    for (std::size_t i = 0; i < series_.size(); ++i)
      if (series_[i].name == name) return static_cast<int>(i);
    return -1;  // unreachable: read_scene checked the names
  }

  SpecimenData specimen() const { return specimen_data(world_, scene_); }

  void start_or_resume() {
    std::vector<std::string> names, units;
    for (const auto& s : series_) names.push_back(s.name), units.push_back(s.unit);
    if (opt_.resume) {
      out_ = std::make_unique<RunOutput>(opt_.output);
      const Archive a = out_->read_checkpoint();
      if (a.reals.at("x").size() != static_cast<std::size_t>(world_.particles.size() * D))
        throw InputError(opt_.output + ": its checkpoint holds a different specimen than the scene builds; resume with the scene that wrote it");
      world_.restore(a);
      const auto& rs = a.reals.at("runner");
      std::size_t k = 0;
      const auto hrows = static_cast<std::int64_t>(rs[k++]), frows = static_cast<std::int64_t>(rs[k++]);
      const auto crows = static_cast<std::int64_t>(rs[k++]);
      for (auto& st : stops_) st.peak = rs[k++];
      for (auto& si : obs_.strain)
        for (int i = 0; i < D * D; ++i) si.strain.data()[i] = rs[k++];
      // A run that stopped on a condition stays stopped: resuming it only closes the file again.
      const auto& why = a.bytes.at("stop_reason");
      stop_reason_.assign(why.begin(), why.end());
      out_->create_histories(names, units);
      out_->truncate(hrows, frows, crows);
      cracks_written_ = static_cast<std::size_t>(crows);
      if (hrows > 0) last_record_step_ = static_cast<std::int64_t>(out_->file().read_doubles("/history/step").back());
      if (frows > 0) last_frame_step_ = out_->file().read_ints("/frames/step").back();
      first_step_ = world_.step_count;
      out_->set_status("running");
      out_->flush();
      return;
    }
    // init() may refuse the scene (a fixed timestep above the estimate): before the output file exists.
    try {
      world_.init();
      if (scene_.bond_tolerance >= 0) {
        world_.install_bonds(scene_.bond_tolerance, scene_.seed);
        // Bonds per phase pair (mortar, aggregate, ITZ …): written with the specimen.
        for (std::size_t c = 0; c < scene_.contacts.size(); ++c)
          if (scene_.contacts[c].model.bonds)
            world_.specimen_facts.push_back({"bonds_" + scene_.phases[scene_.contacts[c].phase_a].name + "-" +
                                                 scene_.phases[scene_.contacts[c].phase_b].name,
                                             static_cast<double>(world_.sets[c]->bond_count())});
      }
    } catch (const InputError& e) {
      throw InputError(scene_.file + ": " + e.what());
    }
    out_ = std::make_unique<RunOutput>(opt_.output, scene_.text, scene_.file, specimen());
    out_->create_histories(names, units);
    if (scene_.crack_log) {
      std::vector<std::string> models;
      for (const auto& s : world_.sets) models.push_back(s->model());
      out_->create_crack_log(D, models);
    }
    if (!scene_.xy_plots.empty()) out_->set_xy_plots(scene_.xy_plots);
    if (scene_.energy) {
      world_.update_energy();
      world_.energy.initial = world_.energy.kinetic + world_.energy.strain;
    }
    record();
    frame();
    out_->flush();
  }

  // "" while the run goes on; else why it ends.
  std::string finished() const {
    if (scene_.steps > 0 && world_.step_count >= scene_.steps) return "finished";
    if (scene_.duration > 0 && world_.time >= scene_.duration) return "finished";
    return stop_reason_;
  }

  void record() {
    last_record_step_ = world_.step_count;
    if (scene_.energy) world_.update_energy();
    std::vector<double> row(series_.size());
    for (std::size_t i = 0; i < series_.size(); ++i) row[i] = series_[i].sample(), buffer_[i].push_back(row[i]);
    for (auto& st : stops_) {
      const double v = row[st.column];
      if (world_.time < st.spec.after_time) continue;
      st.peak = std::max(st.peak, v);
      std::ostringstream m;
      m << "stopped: " << st.spec.quantity;
      if (st.spec.kind == StopSpec::Kind::Below && v < st.spec.value) m << " = " << v << " < " << st.spec.value;
      else if (st.spec.kind == StopSpec::Kind::Above && v > st.spec.value) m << " = " << v << " > " << st.spec.value;
      else if (st.spec.kind == StopSpec::Kind::MagnitudeAbove && std::abs(v) > st.spec.value)
        m << " = " << v << ", beyond ±" << st.spec.value;
      else if (st.spec.kind == StopSpec::Kind::PostPeak && st.peak > 0 && v < st.spec.value * st.peak)
        m << " fell to " << v / st.peak << " of its peak " << st.peak;
      else continue;
      if (stop_reason_.empty()) stop_reason_ = m.str();
    }
  }

  void flush_history() {
    flush_cracks();
    if (buffer_.empty() || buffer_[0].empty()) return;
    out_->append_history(buffer_);
    for (auto& b : buffer_) b.clear();
  }

  void flush_cracks() {
    if (!scene_.crack_log || cracks_written_ == world_.cracks.size()) return;
    RunOutput::CrackRows r;
    for (std::size_t k = cracks_written_; k < world_.cracks.size(); ++k) {
      const Crack<D>& c = world_.cracks[k];
      r.step.push_back(c.step);
      r.mode.push_back(static_cast<std::int64_t>(c.mode));
      r.kind.push_back(static_cast<std::int64_t>(c.kind));
      r.phase_a.push_back(c.phase_a);
      r.phase_b.push_back(c.phase_b);
      r.model.push_back(c.set);
      r.id_a.push_back(world_.ids[c.a]);
      r.id_b.push_back(world_.ids[c.b]);
      r.time.push_back(c.time);
      r.position.insert(r.position.end(), c.position.data(), c.position.data() + D);
      r.normal.insert(r.normal.end(), c.normal.data(), c.normal.data() + D);
    }
    out_->append_cracks(r);
    cracks_written_ = world_.cracks.size();
  }

  void frame() {
    last_frame_step_ = world_.step_count;
    flush_history();
    const auto& p = world_.particles;
    std::vector<double> x, v, f;
    const int width = D == 2 ? 2 : 3;
    for (int i = 0; i < p.size(); ++i)
      for (int k = 0; k < width; ++k) x.push_back(p.x[i][k]), v.push_back(p.v[i][k]), f.push_back(p.f[i][k]);
    out_->append_frame(world_.time, world_.step_count, x, v, f);
    out_->flush();
  }

  void checkpoint() {
    flush_history();
    Archive a;
    world_.save(a);
    std::vector<double> rs = {static_cast<double>(out_->history_rows()), static_cast<double>(out_->frame_rows()),
                              static_cast<double>(cracks_written_)};
    for (const auto& st : stops_) rs.push_back(st.peak);
    for (const auto& si : obs_.strain) rs.insert(rs.end(), si.strain.data(), si.strain.data() + D * D);
    a.reals["runner"] = rs;
    a.bytes["stop_reason"] = std::vector<std::uint8_t>(stop_reason_.begin(), stop_reason_.end());
    out_->write_checkpoint(a, world_.step_count);
  }

  void progress(Clock::time_point t0, Clock::time_point now) {
    if (!opt_.progress || !isatty(STDERR_FILENO)) return;
    const double el = std::chrono::duration<double>(now - t0).count();
    const double rate = (world_.step_count - first_step_) / std::max(el, 1e-9);
    double left = -1;
    if (scene_.steps > 0) left = (scene_.steps - world_.step_count) / std::max(rate, 1e-9);
    else if (scene_.duration > 0 && world_.dt > 0) left = (scene_.duration - world_.time) / world_.dt / std::max(rate, 1e-9);
    std::fprintf(stderr, "\rstep %lld  t = %.4g s  %.0f steps/s", static_cast<long long>(world_.step_count), world_.time, rate);
    if (left >= 0) std::fprintf(stderr, "  left %d:%02d:%02d", int(left / 3600), int(left / 60) % 60, int(left) % 60);
    std::fprintf(stderr, "   ");
    progress_shown_ = true;
  }

  const Scene& scene_;
  RunOptions opt_;
  World<D> world_;
  Observers<D> obs_;
  std::vector<Series> series_;
  std::vector<std::vector<double>> buffer_;
  std::vector<StopState> stops_;
  std::string stop_reason_;
  std::unique_ptr<RunOutput> out_;
  std::int64_t first_step_ = 0;
  std::size_t cracks_written_ = 0;  // entries of world_.cracks already in the file
  std::int64_t last_record_step_ = -1, last_frame_step_ = -1;  // step of the newest history row and frame
  bool progress_shown_ = false;
};

}  // namespace

std::vector<std::pair<std::string, double>> generate_specimen(const Scene& scene, const std::string& output) {
  try {
    return scene.dimension == 2 ? generate<2>(scene, output) : generate<3>(scene, output);
  } catch (const InputError& e) {
    std::remove(output.c_str());  // never a half-written file
    throw;
  }
}

RunResult run_scene(const Scene& scene, const RunOptions& options) {
  if (scene.dimension == 2) return Run<2>(scene, options).run();
  return Run<3>(scene, options).run();
}

}  // namespace mc
