#include "studies/runner.hpp"

#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "engine/archive_bytes.hpp"
#include "engine/errors.hpp"
#include "io/h5_file.hpp"
#include "io/run_output.hpp"
#include "scene/make_system.hpp"
#include "scene/resume_check.hpp"
#include "studies/interrupt.hpp"

namespace mc {

namespace {

using Clock = std::chrono::steady_clock;

const std::string kInterrupted = "interrupted";

// The scene a run builds its system from. A resumed Packing specimen is read back from the output file instead of
// made again (its genesis can take minutes; the checkpoint restores everything after it), when the file is one
// `mesocrack run` wrote. A split run makes it again on every process: a process reading the file while process 0
// opens it for writing would hold HDF5's file lock against it.
Scene scene_to_build(const Scene& s, const RunOptions& o) {
  Scene built = s;
  if (!o.resume || s.specimen.kind != SpecimenSpec::Kind::Packing || (o.exchange && o.exchange->size() > 1))
    return built;
  try {
    const H5File f(o.output, H5File::Mode::ReadOnly);
    if (f.has_attr("/", "format") && f.attr_string("/", "format") == "mesocrack-1" && f.exists("/specimen/id"))
      built.specimen.genesis_from = o.output;
  } catch (const IoError&) {
    // Not a file to resume: the resume itself says why, after the build.
  }
  return built;
}

// A stop condition and what it remembers (the peak, for post-peak conditions).
struct StopState {
  StopSpec spec;
  int column;
  double peak = -kInf;
  double value = kNaN, time = kNaN;            // its quantity in the newest row, and when
  double seen_value = kNaN, seen_time = kNaN;  // the same at the previous progress line (its rate, for time left)
};

// Steps a system, records what its scene declares, writes the output file, checkpoints, and stops on the
// scene's conditions or on an instability.
class Runner {
 public:
  Runner(const Scene& s, const RunOptions& o)
      : scene_(scene_to_build(s, o)),
        opt_(o),
        split_(o.exchange && o.exchange->size() > 1 ? o.exchange : nullptr),
        writer_(!split_ || split_->rank() == 0),
        system_(make_system(scene_, split_, o.imbalance_limit)) {
    for (const auto& st : s.stops) stops_.push_back({st, column_of(st.quantity)});
    buffer_.resize(system_->histories().size());
  }
  Runner(const Runner&) = delete;  // the system refers to scene_
  Runner& operator=(const Runner&) = delete;

  RunResult run() {
    start_or_resume();
    if (opt_.catch_interrupts) catch_interrupts();
    const auto t0 = Clock::now();
    RunResult r;
    try {
      r.status = loop(t0);
      if (r.status == kInterrupted)
        interrupt();
      else
        finish(r.status);
    } catch (const InstabilityError& e) {
      end_with("unstable", e.what());
      throw;
    } catch (const std::exception& e) {
      if (writer_ && out_->file().abandoned())
        throw IoError(std::string(e.what()) + "; " + opt_.output +
                      " keeps the run as last flushed: `summary` reads it, `run --resume` continues it from its last "
                      "checkpoint");
      end_with("failed", e.what());
      throw;
    }
    r.steps = system_->step_count();
    r.time = system_->time();
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    r.balance = system_->balance_report();
    r.cost = system_->cost_report(r.wall_seconds);
    if (r.status == kInterrupted) r.signal = interrupt_signal();
    return r;
  }

 private:
  // The end of a run that went to its end: the final state is checked like every guard_every-th one, and is always
  // in the histories and the frames, once (the loop may have written it already, and a resumed run that had
  // already ended writes nothing new).
  void finish(const std::string& status) {
    if (system_->step_count() % scene_.guard_every != 0) system_->check_stability();
    if (last_record_step_ != system_->step_count()) record();
    if (last_frame_step_ != system_->step_count()) frame();
    checkpoint();
    if (!writer_) return;
    out_->end_with_status(status == "finished" ? "finished" : "stopped", status);
    out_->write_csv();
    if (progress_shown_) std::fputc('\n', stderr);
  }

  // A run a signal asked to end: its rows and frames as they are (an extra row off the scene's cadence would make the
  // resumed run differ from an uninterrupted one), and a checkpoint at the step it ended, which the resume starts
  // from.
  void interrupt() {
    checkpoint();
    if (!writer_) return;
    std::ostringstream m;
    m << "interrupted by " << (interrupt_signal() == SIGTERM ? "SIGTERM" : "SIGINT") << " at step "
      << system_->step_count() << " (t = " << system_->time() << " s); `mesocrack run --resume " << opt_.output
      << "` continues it";
    out_->end_with_status("interrupted", m.str());
    out_->write_csv();
    if (progress_shown_) std::fputc('\n', stderr);
  }

  // A run cut short by an exception: what it recorded so far goes to the file, with the status saying why. When
  // that fails too, the file error is what the command reports (exit 3), naming the first failure as well.
  // A split run's instabilities are found by all its processes together (each is agreed within the step): the
  // others then wait until process 0 has written why, as the launch ends when the first of them exits with it.
  // Any other failure is one process's own, and ends the launch as it stands.
  void end_with(const std::string& status, const std::string& why) {
    if (progress_shown_) std::fputc('\n', stderr);
    try {
      if (writer_ && out_) {
        flush_history();
        out_->end_with_status(status, why);
        out_->write_csv();
      }
    } catch (const IoError& e) {
      throw IoError(std::string(e.what()) + " (while recording that the run " + status + ": " + why + ")");
    }
    if (status == "unstable") any(false);
  }

  // Whether any process says yes (a split run's processes call it together); this process's answer alone.
  bool any(bool mine) const {
    if (!split_) return mine;
    std::vector<double> v{mine ? 1.0 : 0.0};
    split_->max(v);
    return v[0] > 0;
  }

 private:
  // Steps until the run ends; returns why. Output goes out on the scene's cadences, and at least every 2 s of
  // wall time (flush) and every 60 s (checkpoint, unless the scene sets a cadence).
  std::string loop(Clock::time_point t0) {
    auto last_flush = t0, last_checkpoint = t0, last_progress = t0;
    while (true) {
      if (const std::string why = finished(); !why.empty()) return why;
      system_->step();
      const std::int64_t s = system_->step_count();
      if (s % scene_.guard_every == 0) system_->check_stability();
      if (s % scene_.history_every == 0) record();
      if (frame_every_ > 0 && s % frame_every_ == 0) frame();
      if ((s & 63) == 0) {
        const auto now = Clock::now();
        // A checkpoint by the wall clock: when process 0's says so (the processes save together).
        const bool due = scene_.checkpoint_every > 0 ? s % scene_.checkpoint_every == 0
                                                     : any(writer_ && now - last_checkpoint > std::chrono::seconds(60));
        if (due) checkpoint(), last_checkpoint = now, last_flush = now;
        if (writer_ && now - last_flush > std::chrono::seconds(2)) flush_history(), out_->flush(), last_flush = now;
        if (now - last_progress > std::chrono::milliseconds(500)) progress(t0, now), last_progress = now;
      } else if (scene_.checkpoint_every > 0 && s % scene_.checkpoint_every == 0) {
        checkpoint(), last_checkpoint = last_flush = Clock::now();
      }
      // After the step's rows and frames, so that the resume starts with the next step. A split run's processes
      // hear the signal at different steps: they agree every 64 steps, as on checkpoints.
      if (split_ ? (s & 63) == 0 && any(interrupt_signal() != 0) : interrupt_signal() != 0) return kInterrupted;
    }
  }

  int column_of(const std::string& name) const {
    const auto& series = system_->histories();
    for (std::size_t i = 0; i < series.size(); ++i)
      if (series[i].name == name) return static_cast<int>(i);
    return -1;  // unreachable: read_scene checked the names
  }

  void start_or_resume() {
    std::vector<std::string> names, units;
    for (const auto& s : system_->histories()) names.push_back(s.name), units.push_back(s.unit);
    if (opt_.resume) {
      resume(names, units);
      return;
    }
    // The system may refuse the scene here (a fixed timestep above the estimate): before the output file exists.
    system_->start();
    try {
      start_output(names, units);
    } catch (const IoError& e) {
      out_.reset();  // removes the partial file
      throw IoError(named_as_output(e.what()) + "; " + opt_.output + " was not written");
    }
  }

  // Everything up to the step-0 checkpoint goes into the partial file; the file appears under its name only then,
  // complete, so that a run killed at any moment leaves either no file or one that can be read and resumed.
  void start_output(const std::vector<std::string>& names, const std::vector<std::string>& units) {
    const std::vector<std::string> models = system_->crack_models();
    crack_log_ = !models.empty();
    if (writer_) {
      out_ = std::make_unique<RunOutput>(opt_.output, scene_.text, scene_.file, system_->specimen());
      out_->create_histories(names, units);
      if (!models.empty()) out_->create_crack_log(system_->dimension(), models);
      if (!scene_.xy_plots.empty()) out_->set_xy_plots(scene_.xy_plots);
    }
    record();
    frame();
    set_frame_cadence(false);
    checkpoint();
    if (writer_) out_->publish();
  }

  // The steps between frames: the scene's frame_every, or `frames` spread over what is left of the run (sized by the
  // frames' size from the last one written), or as the file says where a resume goes on with the same `frames`. A
  // split run's processes take process 0's. Stored in the file as /frames' attributes `every` and `frames`.
  void set_frame_cadence(bool resumed) {
    double every = 0;
    if (writer_) {
      H5File& f = out_->file();
      const bool stored = resumed && f.has_attr("/frames", "every") && f.has_attr("/frames", "frames") &&
                          f.attr_int("/frames", "frames") == scene_.frames;
      every = scene_.frame_every > 0 ? static_cast<double>(scene_.frame_every)
              : stored               ? static_cast<double>(f.attr_int("/frames", "every"))
                                     : static_cast<double>(spread_frames());
    }
    if (split_) {
      std::vector<double> v{every};
      split_->max(v);
      every = v[0];
    }
    frame_every_ = static_cast<std::int64_t>(every);
    if (!writer_) return;
    out_->file().set_attr("/frames", "every", frame_every_);
    out_->file().set_attr("/frames", "frames", scene_.frames);
  }

  // Steps between `frames` frames over the rest of the run, in steps of the current timestep (0: the first and
  // last only). A stop condition may end the run long before its steps or duration (a post-peak stop cannot be
  // foreseen): then also a frame at least every 20 history rows. Never more frames over the run's steps or duration
  // than 1 GiB holds.
  std::int64_t spread_frames() const {
    if (scene_.frames <= 2) return 0;
    double left = -1;  // steps to the run's end; −1: no end but its stop conditions
    if (scene_.steps > 0) left = static_cast<double>(scene_.steps - system_->step_count());
    if (scene_.duration > 0 && system_->timestep() > 0) {
      const double by_time = (scene_.duration - system_->time()) / system_->timestep();
      left = left < 0 ? by_time : std::min(left, by_time);
    }
    const double by_rows = 20.0 * static_cast<double>(scene_.history_every);
    if (left < 0) return static_cast<std::int64_t>(by_rows);
    left = std::max(left, 1.0);
    constexpr double kFrameBudget = 1024.0 * 1024.0 * 1024.0;  // bytes
    const double affordable = std::max(2.0, std::floor(kFrameBudget / std::max(frame_bytes_, 1.0)));
    double every = std::ceil(left / static_cast<double>(scene_.frames - 1));
    if (!stops_.empty()) every = std::min(every, by_rows);
    return static_cast<std::int64_t>(std::max(every, std::ceil(left / (affordable - 1))));
  }

  // An error message about the partial file, naming the output file the user gave instead.
  std::string named_as_output(std::string message) const {
    const std::string partial = RunOutput::partial_path(opt_.output);
    for (auto at = message.find(partial); at != std::string::npos; at = message.find(partial, at + 1))
      message.replace(at, partial.size(), opt_.output);
    return message;
  }

  // Process 0 reads the checkpoint (and where the file's histories and frames end) and the others receive it;
  // then every process restores it, a split world splitting it afresh over however many processes there are now.
  void resume(const std::vector<std::string>& names, const std::vector<std::string>& units) {
    SceneChange change;
    Archive a;
    if (writer_) {
      change = scene_change();  // before the file is opened for writing: a refusal leaves it as is
      out_ = std::make_unique<RunOutput>(opt_.output);
      a = out_->read_checkpoint();
      const std::int64_t hrows = static_cast<std::int64_t>(a.reals.at("runner").at(0));
      const std::int64_t frows = static_cast<std::int64_t>(a.reals.at("runner").at(1));
      a.reals["runner_last"] = {
          hrows > 0 ? out_->file().read_leading_doubles("/history/step").at(static_cast<std::size_t>(hrows - 1)) : -1.0,
          frows > 0 ? out_->file().read_leading_doubles("/frames/step").at(static_cast<std::size_t>(frows - 1)) : -1.0,
          change.stops_changed ? 1.0 : 0.0};
    }
    if (split_) a = archive_of(split_->all_gather(writer_ ? archive_bytes(a) : Bytes{})[0]);
    change.stops_changed = a.reals.at("runner_last")[2] > 0;
    try {
      system_->restore(a);
    } catch (const InputError& e) {
      throw InputError(opt_.output + ": " + e.what());
    } catch (const IoError& e) {
      throw IoError(opt_.output + ": " + e.what());
    }
    const auto& rs = a.reals.at("runner");
    std::size_t k = 0;
    const auto hrows = static_cast<std::int64_t>(rs[k++]), frows = static_cast<std::int64_t>(rs[k++]);
    const auto crows = static_cast<std::int64_t>(rs[k++]);
    // A run that stopped on a condition stays stopped (resuming it only closes the file again), unless the
    // conditions changed: then they start afresh, a post-peak condition from the peak after the resume.
    if (!change.stops_changed) {
      for (auto& st : stops_) st.peak = rs[k++];
      const auto& why = a.bytes.at("stop_reason");
      stop_reason_.assign(why.begin(), why.end());
    }
    cracks_written_ = static_cast<std::size_t>(crows);
    crack_log_ = !system_->crack_models().empty();
    // The steps of the newest row and frame in the file (those of the checkpoint's, or later ones dropped now).
    const auto& last = a.reals.at("runner_last");
    if (hrows > 0) last_record_step_ = static_cast<std::int64_t>(last[0]);
    if (frows > 0) last_frame_step_ = static_cast<std::int64_t>(last[1]);
    first_step_ = system_->step_count();
    if (!writer_) {
      set_frame_cadence(true);
      return;
    }
    if (opt_.progress)
      std::fprintf(stderr, "resumed %s at step %lld, t = %.6g s\n", opt_.output.c_str(),
                   static_cast<long long>(first_step_), system_->time());
    out_->resume_at(hrows, frows, crows);
    out_->create_histories(names, units);
    set_frame_cadence(true);
    out_->set_status("running");
    out_->flush();
  }

  // The scene stored in the output against the one resuming it: anything but the run's end, its stop
  // conditions and the output cadences would continue the checkpoint under other rules.
  SceneChange scene_change() const {
    const std::string stored = RunOutput::stored_scene(opt_.output);
    SceneChange c = compare_for_resume(stored, scene_.text);
    if (!c.refused.empty())
      throw InputError(scene_.file + ": cannot resume " + opt_.output + " with this scene: " + c.refused +
                       " (a resume may change only " + keys_a_resume_may_change() + "); the file is left as it was");
    return c;
  }

  // "" while the run goes on; else why it ends.
  std::string finished() const {
    if (scene_.steps > 0 && system_->step_count() >= scene_.steps) return "finished";
    if (scene_.duration > 0 && system_->time() >= scene_.duration) return "finished";
    return stop_reason_;
  }

  // One history row. A non-finite value is an instability: it never reaches the file (nor does its row).
  void record() {
    system_->before_row();
    const auto& series = system_->histories();
    std::vector<double> row(series.size());
    for (std::size_t i = 0; i < series.size(); ++i) {
      row[i] = series[i].sample();
      if (!std::isfinite(row[i])) {
        std::ostringstream m;
        m << "unstable at step " << system_->step_count() << " (t = " << system_->time() << " s): history '"
          << series[i].name << "' is " << row[i]
          << "; likely cause: a quantity divided by zero or the state blowing up between two stability checks "
             "(lower output.guard_every to find where)";
        throw InstabilityError(m.str());
      }
    }
    last_record_step_ = system_->step_count();
    if (writer_)
      for (std::size_t i = 0; i < series.size(); ++i) buffer_[i].push_back(row[i]);
    for (auto& st : stops_) check_stop(st, row[st.column]);
  }

  void check_stop(StopState& st, double v) {
    st.value = v, st.time = system_->time();
    if (system_->time() < st.spec.after_time) return;
    // A post-peak stop follows the magnitude: a load may be a positive or a negative reaction.
    st.peak = std::max(st.peak, st.spec.kind == StopSpec::Kind::PostPeak ? std::abs(v) : v);
    std::ostringstream m;
    m << "stopped: " << st.spec.quantity;
    if (st.spec.kind == StopSpec::Kind::Below && v < st.spec.value)
      m << " = " << v << " < " << st.spec.value;
    else if (st.spec.kind == StopSpec::Kind::Above && v > st.spec.value)
      m << " = " << v << " > " << st.spec.value;
    else if (st.spec.kind == StopSpec::Kind::MagnitudeAbove && std::abs(v) > st.spec.value)
      m << " = " << v << ", beyond ±" << st.spec.value;
    else if (st.spec.kind == StopSpec::Kind::PostPeak && st.peak > 0 && std::abs(v) < st.spec.value * st.peak)
      m << " fell to " << std::abs(v) / st.peak << " of its peak magnitude " << st.peak;
    else
      return;
    if (stop_reason_.empty()) stop_reason_ = m.str();
  }

  void flush_history() {
    if (!writer_) return;
    flush_cracks();
    if (buffer_.empty() || buffer_[0].empty()) return;
    out_->append_history(buffer_);
    for (auto& b : buffer_) b.clear();
  }

  void flush_cracks() {
    if (!crack_log_ || cracks_written_ == system_->crack_count()) return;
    out_->append_cracks(system_->cracks(cracks_written_));
    cracks_written_ = system_->crack_count();
  }

  // A split world's frame is gathered on process 0, which alone can find it non-finite: the others hear it.
  void frame() {
    last_frame_step_ = system_->step_count();
    flush_history();
    std::vector<double> x, v, f;
    system_->frame(x, v, f);
    const CellFrame cells = system_->cell_frame();
    const ContactFrame contacts = system_->contact_frame();
    const int d = system_->dimension();
    std::string why;
    if (writer_) {
      why = non_finite("position", x, d, "particle", "/specimen");
      if (why.empty()) why = non_finite("velocity", v, d, "particle", "/specimen");
      if (why.empty()) why = non_finite("force", f, d, "particle", "/specimen");
      if (why.empty()) why = non_finite("position", cells.corner, d, "cell corner", "/specimen/cells/corner");
      if (why.empty()) why = non_finite("damage", cells.damage, 1, "contact facet", "/specimen/cells/facet_a");
      if (why.empty()) why = non_finite("normal force", contacts.normal_force, 1, "contact", "this frame's contacts");
    }
    if (any(!why.empty()))
      throw InstabilityError(writer_ ? why
                                     : "unstable at step " + std::to_string(system_->step_count()) +
                                           ": process 0 found the frame non-finite (its message is in the output)");
    if (!writer_) return;
    frame_bytes_ = 8.0 * static_cast<double>(x.size() + v.size() + f.size() + cells.corner.size() +
                                             cells.damage.size() + 3 * cells.fibre_state.size() +
                                             (4 + system_->dimension()) * contacts.size());
    out_->append_frame(system_->time(), system_->step_count(), x, v, f, cells, contacts);
    out_->flush();
  }

  // "" when a frame's values are finite, else why the run is unstable (found before anything of the frame is
  // written). `width` values describe one `item`, row k of `table`.
  std::string non_finite(const char* what, const std::vector<double>& values, int width, const char* item,
                         const char* table) const {
    const auto bad = std::find_if(values.begin(), values.end(), [](double x) { return !std::isfinite(x); });
    if (bad == values.end()) return "";
    const auto k = (bad - values.begin()) / width;
    std::ostringstream m;
    m << "unstable at step " << system_->step_count() << " (t = " << system_->time() << " s): the " << what << " of "
      << item << " " << k << " (row " << k << " of " << table << ") is " << *bad
      << "; likely cause: the state blew up between two stability checks (lower output.guard_every to find where)";
    return m.str();
  }

  void checkpoint() {
    flush_history();
    Archive a;
    system_->save(a);  // a split world's processes save together, into process 0's archive
    if (!writer_) return;
    std::vector<double> rs = {static_cast<double>(out_->history_rows()), static_cast<double>(out_->frame_rows()),
                              static_cast<double>(cracks_written_)};
    for (const auto& st : stops_) rs.push_back(st.peak);
    a.reals["runner"] = rs;
    a.bytes["stop_reason"] = std::vector<std::uint8_t>(stop_reason_.begin(), stop_reason_.end());
    out_->write_checkpoint(a, system_->step_count());
  }

  void progress(Clock::time_point t0, Clock::time_point now) {
    if (!writer_ || !opt_.progress || !isatty(STDERR_FILENO)) return;
    const double el = std::chrono::duration<double>(now - t0).count();
    const double rate = (system_->step_count() - first_step_) / std::max(el, 1e-9);
    const double sim_rate = rate * system_->timestep();  // simulated seconds per wall second
    double bound = -1;  // to the run's end (its steps or duration)
    if (scene_.steps > 0)
      bound = (scene_.steps - system_->step_count()) / std::max(rate, 1e-9);
    else if (scene_.duration > 0 && sim_rate > 0)
      bound = (scene_.duration - system_->time()) / sim_rate;
    std::fprintf(stderr, "\rstep %lld  t = %.4g s  %.0f steps/s", static_cast<long long>(system_->step_count()),
                 system_->time(), rate);
    auto clock = [](double s) {
      char b[32];
      std::snprintf(b, sizeof b, "%d:%02d:%02d", int(s / 3600), int(s / 60) % 60, int(s) % 60);
      return std::string(b);
    };
    if (stops_.empty()) {
      if (bound >= 0) std::fprintf(stderr, "  left %s", clock(bound).c_str());
    } else {
      // A stop condition may end the run sooner: the run's end is then a bound, and a threshold the quantity moves
      // toward is reached, at its rate since the last line, in `soon` (a post-peak stop cannot be foreseen).
      double soon = kInf;
      for (auto& st : stops_) {
        const double dv = st.value - st.seen_value, dt = st.time - st.seen_time;
        const auto kind = st.spec.kind;
        if (dt > 0 && sim_rate > 0 && kind != StopSpec::Kind::PostPeak) {
          const double target =
              kind == StopSpec::Kind::MagnitudeAbove ? std::copysign(st.spec.value, dv) : st.spec.value;
          const double to_go = (target - st.value) / (dv / dt);  // simulated seconds; negative: moving away
          if (to_go > 0 && std::isfinite(to_go))
            soon = std::min(soon, std::max(to_go, st.spec.after_time - system_->time()) / sim_rate);
        }
        st.seen_value = st.value, st.seen_time = st.time;
      }
      if (std::isfinite(soon) && (bound < 0 || soon < bound))
        std::fprintf(stderr, "  left ~%s", clock(soon).c_str());
      else
        std::fprintf(stderr, "  left unknown");
      if (bound >= 0) std::fprintf(stderr, " (at most %s)", clock(bound).c_str());
    }
    std::fprintf(stderr, "   ");
    progress_shown_ = true;
  }

  const Scene scene_;  // the scene as run (scene_to_build); the system refers to it
  RunOptions opt_;
  const Exchange* split_;  // the processes of a split world (null: this one alone)
  bool writer_;            // this process writes the output (process 0 of a split world)
  std::unique_ptr<System> system_;
  std::vector<std::vector<double>> buffer_;
  std::vector<StopState> stops_;
  std::string stop_reason_;
  std::unique_ptr<RunOutput> out_;
  std::int64_t first_step_ = 0;
  bool crack_log_ = false;
  std::size_t cracks_written_ = 0;                             // entries of the crack log already in the file
  std::int64_t last_record_step_ = -1, last_frame_step_ = -1;  // step of the newest history row and frame
  std::int64_t frame_every_ = 0;                               // steps between frames (set_frame_cadence)
  double frame_bytes_ = 0;                                     // the newest frame's size in the file
  bool progress_shown_ = false;
};

}  // namespace

RunResult run_scene(const Scene& scene, const RunOptions& options) {
  refuse_unsafe_outputs(scene, run_files(options.output));
  return Runner(scene, options).run();
}

std::vector<std::pair<std::string, double>> generate_specimen(const Scene& scene, const std::string& output) {
  refuse_unsafe_outputs(scene, run_files(output));
  const auto system = make_system(scene);  // the genesis happens here, before the file exists
  const SpecimenData d = system->specimen();
  RunOutput out(output, scene.text, scene.file, d);  // complete under its name, or absent
  const std::vector<double> zero(d.x.size(), 0.0);
  const std::vector<double> fibres_idle(d.fibres.family.size(), 0.0);  // FibreState::Idle, no force, no slip
  const CellFrame cells_at_rest{d.cells.corner, std::vector<double>(d.cells.contacts, 0.0), fibres_idle, fibres_idle,
                                fibres_idle};
  out.append_frame(0.0, 0, d.x, zero, zero, cells_at_rest);  // at rest: a scene loads it with kind = "output"
  out.set_status("finished", "generated specimen");
  out.publish();
  auto facts = d.facts;
  facts.insert(facts.begin(), {"particles", static_cast<double>(d.radius.size())});
  return facts;
}

}  // namespace mc
