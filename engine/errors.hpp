// Error kinds that reach the user. Each carries a complete, self-explaining message;
// the command line prints it and exits non-zero (InputError: 2, IoError: 3, InstabilityError: 4).
#pragma once
#include <stdexcept>
#include <string>

namespace mc {

// Bad scene, bad option, bad value: the message names the file, the key, the value and what is allowed.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A fixed timestep above the critical one estimated from the current stiffnesses: bad input, found by the engine.
struct TimestepError : InputError {
  using InputError::InputError;
};

// A file that cannot be read or written (path and reason in the message).
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The simulation became unstable: the message names the step, the particle or wall and the likely cause.
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace mc
