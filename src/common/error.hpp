#pragma once
/// Errors of tcasim. Three kinds of failure, three mechanisms:
///  - a broken internal invariant: assert (debug builds);
///  - bad user input: InputError, always checked, naming key, value and rule;
///  - a physical-domain violation found during a computation (a state outside the
///    model's validity): DomainError, with the quantity, its value and the limit;
///  - an external library's error code: ExternalError, converted where it is called.
#include <stdexcept>
#include <string>
#include <string_view>

namespace tcasim {

/// Bad user input: `key = value rule`, e.g.
/// "tca.coiled_length_m = 0.5 must be < fiber_length_m = 0.11".
class InputError : public std::runtime_error {
 public:
  InputError(std::string key, std::string value, std::string rule);
  const std::string& key() const noexcept { return key_; }
  const std::string& value() const noexcept { return value_; }
  const std::string& rule() const noexcept { return rule_; }

 private:
  std::string key_, value_, rule_;
};

/// A computed state outside the model's domain of validity.
class DomainError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An error code returned by an external library (SUNDIALS, SuiteSparse, ...).
class ExternalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Formats a number for messages: shortest round-trip representation.
std::string format_value(double v);

/// Throw InputError(key, format_value(value), rule) / InputError(key, value_text, rule).
[[noreturn]] void throw_input_error(std::string_view key, double value, std::string_view rule);
[[noreturn]] void throw_input_error(std::string_view key, std::string_view value_text,
                                    std::string_view rule);

/// Throws InputError(key, format_value(value), rule) unless `ok`. Views, so string literals
/// are not copied on the (usual) passing path; callers in hot loops should also avoid
/// building the rule by concatenation before the test.
inline void require(bool ok, std::string_view key, double value, std::string_view rule) {
  if (!ok) throw_input_error(key, value, rule);
}

/// Throws InputError(key, value_text, rule) unless `ok`.
inline void require(bool ok, std::string_view key, std::string_view value_text,
                    std::string_view rule) {
  if (!ok) throw_input_error(key, value_text, rule);
}

}  // namespace tcasim
