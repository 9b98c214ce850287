#pragma once
// The vgd::Error a call throws, for tests of error messages.
#include <gtest/gtest.h>

#include "vgd/core/diagnostics.hpp"

namespace vgd::test {

// Catches the vgd::Error `f` throws and returns its diagnostic; fails the test
// when it throws none.
template <class F>
Diagnostic error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.diagnostic();
  }
  ADD_FAILURE() << "no vgd::Error thrown";
  return {};
}

}  // namespace vgd::test
