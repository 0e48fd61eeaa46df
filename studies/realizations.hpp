// Realizations (Tang §5.4, Figs. 5.9–5.12): the same uniaxial test on N random packings, to see how much the
// macro-properties depend on the draw. Realization k runs the scene with seed + k, so the set is reproducible.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "studies/stored_run.hpp"  // UniaxialResult

namespace mc {

struct Statistic {
  double mean = kNaN, std = kNaN, cv = kNaN;  // std with n − 1; cv = std / |mean|
};
Statistic statistic(const std::vector<double>& x);

struct RealizationSet {
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> files;  // one output file per realization
  std::vector<UniaxialResult> results;
  std::vector<double> wall_seconds;
};

// "out/u.h5" → "out/u_r3.h5"
std::string realization_file(const std::string& output, int k);

// Runs N realizations of a scene with a [uniaxial] analysis, printing one line per realization to `log`. Under
// mpirun the realizations are spread over the ranks (studies/ranks.hpp); every rank returns the whole set.
RealizationSet run_realizations(const std::string& scene_file, const std::vector<std::string>& overrides, int n,
                                const std::string& output, std::FILE* log);

// Per realization and mean / std / CV of E, ν, UCS, the strain at the peak and the crack-initiation ratio.
std::string realizations_json(const RealizationSet& set);

}  // namespace mc
