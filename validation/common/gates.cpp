#include "validation/common/gates.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

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

}  // namespace

bool Gates::check(const std::string& name, bool passed, const std::string& measured,
                  const std::string& bound) {
  records_.push_back({name, measured, bound, passed});
  fmt::print("  [{}] {}: {} ({})\n", passed ? "PASS" : "FAIL", name, measured, bound);
  return passed;
}

bool Gates::at_most(const std::string& name, double measured, double bound, const std::string& unit) {
  const std::string u = unit.empty() ? "" : " " + unit;
  return check(name, measured <= bound, fmt::format("{:.3e}{}", measured, u), fmt::format("<= {:.3e}{}", bound, u));
}

bool Gates::within(const std::string& name, double measured, double lo, double hi) {
  return check(name, measured >= lo && measured <= hi, fmt::format("{:.4g}", measured),
               fmt::format("in [{:.4g}, {:.4g}]", lo, hi));
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
  fmt::print("{}: {} gates, {} failed\n", n == 0 ? "PASS" : "FAIL", records_.size(), n);
  return n == 0 ? 0 : 1;
}

}  // namespace tcasim::validation
