#include "apps/cli_util.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <utility>

#include "common/error.hpp"
#include "common/grid.hpp"
#include "rod/output_file.hpp"
#include "rod/scenario.hpp"
#include "rod/tca_choice.hpp"

namespace tcasim::app {

namespace {

double parse_number(const std::string& s, const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v)) {
    throw InputError(flag, text, "must be a number or a range START:STOP:STEP");
  }
  return v;
}

}  // namespace

std::vector<double> parse_range(const std::string& text, const std::string& flag) {
  const std::string rule = "must be a number or a range START:STOP:STEP";
  const std::vector<std::string> parts = split_list(text, ':', flag, rule);
  if (parts.size() == 1) return {parse_number(parts[0], flag, text)};
  if (parts.size() != 3) throw InputError(flag, text, rule);
  const double a = parse_number(parts[0], flag, text);
  const double b = parse_number(parts[1], flag, text);
  const double step = parse_number(parts[2], flag, text);
  return inclusive_grid(a, b, step, flag);
}

void require_one_time_step_mode(bool dt_given, const std::string& dt_text, bool rtol_given) {
  if (dt_given && rtol_given) {
    throw InputError("--dt-s", dt_text,
                     "cannot be given with --rtol (fixed or adaptive time steps: one of them)");
  }
  if (!dt_given && !rtol_given) {
    throw InputError("--dt-s", "missing",
                     "one of --dt-s (fixed time steps) or --rtol (adaptive) is required");
  }
}

Eigen::Vector3d parse_vector3(const std::string& text, const std::string& flag) {
  const std::string rule = "must be three comma-separated finite numbers X,Y,Z";
  const std::vector<std::string> items = split_list(text, ',', flag, rule);
  require(items.size() == 3, flag, text, rule);
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    const std::string& item = items[k];
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    require(used > 0 && item.find_first_not_of(" \t", used) == std::string::npos &&
                std::isfinite(value),
            flag, text, rule);
    v[k] = value;
  }
  return v;
}

std::shared_ptr<const tca::Tca> select_tca(const std::string& file, const std::string& id,
                                           const std::string& material_name,
                                           const std::string& f12_form) {
  const auto given = [](const std::string& v) {
    return v.empty() ? std::nullopt : std::optional<std::string>(v);
  };
  // The flag of an argument: "f12_form" -> "--f12-form".
  const auto flag = [](std::string key) {
    std::replace(key.begin(), key.end(), '_', '-');
    return "--" + key;
  };
  return rod::select_tca(rod::read_tcas(file), file,
                         {given(id), given(material_name), given(f12_form)}, flag);
}

Shard parse_shard(const std::string& text, const std::string& flag) {
  const std::size_t slash = text.find('/');
  const auto integer = [&](const std::string& part, long long& v) {
    if (part.empty() || part.size() > 18 ||
        !std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return false;
    v = std::stoll(part);
    return true;
  };
  Shard s;
  if (slash == std::string::npos || !integer(text.substr(0, slash), s.index) ||
      !integer(text.substr(slash + 1), s.count)) {
    throw InputError(flag, text, "must be I/N with whole numbers 0 <= I < N (e.g. 0/4)");
  }
  require(s.count >= 1 && s.count <= kMaxShards, flag, text,
          fmt::format("needs a shard count N in [1, {}]", kMaxShards));
  require(s.index < s.count, flag, text,
          fmt::format("needs I < N: the {} shards are numbered 0 to {}", s.count, s.count - 1));
  return s;
}

Output::Output(std::string path, std::string flag)
    : path_(std::move(path)), flag_(std::move(flag)) {
  if (path_.empty() || path_ == "-") return;
  // Checked before the work that fills the buffer, so a typo in the folder costs nothing.
  const std::filesystem::path dir = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  require(dir.empty() || std::filesystem::is_directory(dir, ec), flag_, path_,
          "cannot be opened for writing: its folder does not exist");
}

std::ostream& Output::stream() {
  if (path_.empty() || path_ == "-") return std::cout;
  return buffer_;
}

void Output::commit() {
  if (path_.empty() || path_ == "-") {
    std::cout.flush();
    if (!std::cout) throw InputError(flag_, "\"-\"", "could not be written to stdout");
    return;
  }
  rod::write_file_atomically(path_, buffer_.str(), flag_);
}

}  // namespace tcasim::app
