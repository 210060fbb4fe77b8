#pragma once
// The message of the exception of type Error that an action throws; the test fails if the
// action throws nothing. For checking what users read in error messages.
#include <gtest/gtest.h>

#include <string>

namespace cocopp::testing {

template <class Error, class Action>
std::string error_message(Action&& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception, none was thrown";
  return "";
}

}  // namespace cocopp::testing
