// The message of the error a call throws, for tests of what a user is told.
#pragma once
#include <doctest/doctest.h>

#include <string>

#include "engine/errors.hpp"

namespace mc::test {

// The message of the exception of type E (InputError unless named) that f throws; an empty string, and a failed
// check, when it throws none.
template <class E = InputError, class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  FAIL_CHECK("expected the call to throw");
  return "";
}

}  // namespace mc::test
