// The check every hostile-input test makes: an action throws an InputError whose message holds given fragments.
#pragma once

#include <doctest/doctest.h>

#include <functional>
#include <initializer_list>
#include <string>

#include "spectral/error.h"

namespace rimu::test {

/// The InputError `action` throws (the test fails if it throws none), after checking its message holds each fragment.
inline InputError input_error(const std::function<void()>& action, std::initializer_list<std::string> fragments) {
  try {
    action();
  } catch (const InputError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    for (const std::string& f : fragments) CHECK_MESSAGE(what.find(f) != std::string::npos, "missing: " << f);
    return e;
  }
  FAIL("expected an InputError");
  return InputError({}, "");
}

}  // namespace rimu::test
