#pragma once
// Test support shared by the suites: the message of the exception a call is expected to throw
// (bad input must fail with a message that names the input, and the tests check that message).
#include <gtest/gtest.h>

#include <exception>
#include <stdexcept>
#include <string>

namespace aperture::test_support {

// Runs `action` expecting an exception of type E and returns its message. When `action` returns
// normally or throws another type, records a test failure and returns "".
template <typename E = std::invalid_argument, typename Action>
std::string MessageOf(Action&& action) {
  try {
    action();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected an exception, none was thrown";
  return "";
}

}  // namespace aperture::test_support
