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

void require(bool ok, const std::string& key, double value, const std::string& rule) {
  if (!ok) throw InputError(key, format_value(value), rule);
}

void require(bool ok, const std::string& key, const std::string& value_text,
             const std::string& rule) {
  if (!ok) throw InputError(key, value_text, rule);
}

}  // namespace tcasim
