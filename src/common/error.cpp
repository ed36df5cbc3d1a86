#include "common/error.hpp"

#include <fmt/format.h>

#include <utility>

namespace tcasim {

InputError::InputError(std::string key, std::string value, std::string rule)
    : std::runtime_error(fmt::format("{} = {} {}", key, value, rule)),
      key_(std::move(key)),
      value_(std::move(value)),
      rule_(std::move(rule)) {}

std::string format_value(double v) { return fmt::format("{}", v); }

void throw_input_error(std::string_view key, double value, std::string_view rule) {
  throw InputError(std::string(key), format_value(value), std::string(rule));
}

void throw_input_error(std::string_view key, std::string_view value_text, std::string_view rule) {
  throw InputError(std::string(key), std::string(value_text), std::string(rule));
}

}  // namespace tcasim
