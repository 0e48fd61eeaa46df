// The benchmarks read their options with CLI11, as the command does (app/main.cpp).
#pragma once
#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>
#include <string>

namespace mc::bench {

// A whole number in decimal digits, without leading zeros. CLI11 reads integers in C's notation: "-1" into an
// unsigned option as its largest value, "010" as eight, "0x10" as sixteen.
inline const CLI::Validator kWholeNumber(
    [](const std::string& v) {
      const bool digits = !v.empty() && v.find_first_not_of("0123456789") == std::string::npos;
      return digits && (v.size() == 1 || v[0] != '0') ? std::string()
                                                      : "'" + v + "': allowed a whole number in decimal digits";
    },
    "WHOLE");

// Reads argv into `app`. Empty when the run goes on; else its exit code: 0 after --help (printed), 2 after a bad
// option, whose message (the option, the value and what is allowed) goes to stderr after the benchmark's name.
// `speak` false prints nothing (the other ranks of a launch).
inline std::optional<int> read_options(CLI::App& app, int argc, char** argv, const char* name, bool speak = true) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return speak ? app.exit(e) : 0;
    if (speak) std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 2;
  }
}

}  // namespace mc::bench
