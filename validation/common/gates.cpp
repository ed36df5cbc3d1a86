#include "validation/common/gates.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "rod/output_file.hpp"

namespace tcasim::validation {

namespace {

/// CSV field: quoted when it holds a comma or a quote.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// True when `text` holds the word nan, inf or infinity (any case; fmt and printf spell
/// non-finite numbers so): a measured text naming a non-finite number.
bool names_non_finite(const std::string& text) {
  std::string word;
  auto is_non_finite = [](const std::string& w) {
    return w == "nan" || w == "inf" || w == "infinity";
  };
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      if (is_non_finite(word)) return true;
      word.clear();
    }
  }
  return is_non_finite(word);
}

}  // namespace

bool Gates::check(const std::string& name, bool passed, const std::string& measured,
                  const std::string& bound) {
  const bool ok = passed && !names_non_finite(measured);
  records_.push_back({name, measured, bound, ok});
  fmt::print("  [{}] {}: {} ({})\n", ok ? "PASS" : "FAIL", name, measured, bound);
  return ok;
}

bool Gates::at_most(const std::string& name, double measured, double bound,
                    const std::string& unit) {
  const std::string u = unit.empty() ? "" : " " + unit;
  const bool finite = std::isfinite(measured) && std::isfinite(bound);
  return check(name, finite && measured <= bound, fmt::format("{:.3e}{}", measured, u),
               fmt::format("<= {:.3e}{}", bound, u));
}

bool Gates::within(const std::string& name, double measured, double lo, double hi) {
  const bool finite = std::isfinite(measured) && std::isfinite(lo) && std::isfinite(hi);
  return check(name, finite && measured >= lo && measured <= hi, fmt::format("{:.4g}", measured),
               fmt::format("in [{:.4g}, {:.4g}]", lo, hi));
}

bool Gates::expect_count(const std::string& what, std::size_t ran, std::size_t expected) {
  return check(
      "cases run: " + what, expected > 0 && ran >= expected, fmt::format("{} of {}", ran, expected),
      expected > 0 ? fmt::format(">= {} (declared)", expected) : std::string(">= 1 declared"));
}

void Gates::not_run(const std::string& name, const std::string& reason) {
  check(name + ": not run", false, reason, "runs");
}

int Gates::failures() const {
  int n = 0;
  for (const auto& r : records_) n += r.passed ? 0 : 1;
  return n;
}

void Gates::write_csv(const std::string& out_dir) const {
  std::filesystem::create_directories(out_dir);
  const std::string path = out_dir + "/gates.csv";
  rod::AtomicOutput f(path, "gates csv");
  f << "program,gate,measured,bound,passed\n";
  for (const auto& r : records_) {
    fmt::print(f, "{},{},{},{},{}\n", csv_field(program_), csv_field(r.name), csv_field(r.measured),
               csv_field(r.bound), r.passed ? 1 : 0);
  }
  f.commit();
}

int Gates::finish() const {
  const int n = failures();
  if (records_.empty()) {
    fmt::print("FAIL: no gates recorded (a program that checks nothing cannot pass)\n");
    return 1;
  }
  fmt::print("{}: {} gates, {} failed\n", n == 0 ? "PASS" : "FAIL", records_.size(), n);
  return n == 0 ? 0 : 1;
}

}  // namespace tcasim::validation
