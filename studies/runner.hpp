// Runs a scene: builds its system (the explicit world, or another solver family behind engine/system.hpp), steps
// it, records what the scene declares, writes the output file, checkpoints, and stops on the scene's conditions
// or on an instability.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "engine/exchange.hpp"
#include "scene/scene.hpp"
#include "studies/run_files.hpp"

namespace mc {

struct RunOptions {
  std::string output;    // OUT.h5
  bool resume = false;   // continue `output` from its last checkpoint
  bool progress = true;  // progress line on stderr (only when it is a terminal)
  // SIGINT and SIGTERM end the run with a checkpoint once its output file exists (studies/interrupt.hpp); before
  // that they kill it as they would any program (nothing is lost: the file is not yet there).
  bool catch_interrupts = false;
  // The processes of a launch that run one specimen split across them (more than one; World::split): each calls
  // run_scene alike, and process 0 writes the output. Null: this process runs the scene alone.
  const Exchange* exchange = nullptr;
  // A split run draws its regions afresh when the most loaded process owns more than (1 + imbalance_limit) times
  // the mean particle count (0: never; World::imbalance_limit).
  double imbalance_limit = 0;
};

struct RunResult {
  std::string status;  // "finished", "stopped: <condition>", "interrupted" (studies/interrupt.hpp)
  std::int64_t steps = 0;
  double time = 0, wall_seconds = 0;
  std::string balance;  // a split run's System::balance_report
  std::string cost;     // System::cost_report
  int signal = 0;       // the signal that interrupted the run, or 0
};

// Throws InputError / IoError before anything runs; InstabilityError after recording it in the file.
RunResult run_scene(const Scene& scene, const RunOptions& options);

// Builds the scene's specimen (for kind = "packing": the genesis) and writes it to `output` as a finished run
// with one frame at rest, which scenes load with kind = "output". Returns what the generation measured.
std::vector<std::pair<std::string, double>> generate_specimen(const Scene& scene, const std::string& output);

}  // namespace mc
