#pragma once
/// Expectations on the InputError (common/error.hpp) that bad input must raise: the key it
/// names and its rule.
#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"

namespace tcasim::test_support {

/// Expects `f()` to throw an InputError naming `key` with a non-empty rule that contains
/// `rule_part` (any rule when empty); a test failure (not an exception) otherwise.
template <class F>
void expect_input_error(F&& f, const std::string& key, const std::string& rule_part = "") {
  try {
    f();
    ADD_FAILURE() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_FALSE(e.rule().empty()) << e.what();
    EXPECT_NE(e.rule().find(rule_part), std::string::npos)
        << "rule without '" << rule_part << "': " << e.what();
  }
}

/// The rule of the InputError that `f()` throws; "(accepted)" when it throws none.
template <class F>
std::string input_error_rule(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.rule();
  }
  return "(accepted)";
}

}  // namespace tcasim::test_support
