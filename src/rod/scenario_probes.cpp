// The `probes` list of a scenario (docs/scenario-format.md "Probes and frames").
#include <cctype>

#include "rod/internal/scenario_reading.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

/// Probes of one scenario: each adds three CSV columns and one evaluation per solve; far
/// more markers than any motion-capture set or sensor array on one rod.
constexpr std::size_t kMaxProbes = 1000;

}  // namespace

bool csv_safe(const std::string& name) {
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

std::vector<Probe> parse_probes(const json& j, const std::string& path, double body_length_m) {
  if (!j.is_array()) {
    throw InputError(path, show(j),
                     fmt::format("must be an array of probe objects, not {}", type_name(j)));
  }
  if (j.size() > kMaxProbes) {
    throw InputError(path, fmt::format("(an array of {} probes)", j.size()),
                     fmt::format("must have at most {} probes", kMaxProbes));
  }
  std::vector<Probe> probes;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string p = fmt::format("{}[{}]", path, i);
    const Obj o(j[i], p, {"name", "s_m", "offset_m"});
    Probe probe;
    probe.name = o.nonempty_string("name");
    require(csv_safe(probe.name), o.key("name"), quote(probe.name),
            "must consist of letters, digits, '_', '-' and '.' only (it names CSV columns)");
    // "tip" would repeat the tip_x_m, tip_y_m, tip_z_m columns of sweeps and trajectories.
    require(probe.name != "tip", o.key("name"), quote(probe.name),
            "must not be \"tip\" (the tip_x_m, ... columns exist already)");
    for (std::size_t k = 0; k < probes.size(); ++k) {
      require(probes[k].name != probe.name, o.key("name"), quote(probe.name),
              fmt::format("is not unique (also {}[{}].name)", path, k));
    }
    probe.s_m = o.number("s_m");
    require(probe.s_m >= 0.0 && probe.s_m <= body_length_m, o.key("s_m"), probe.s_m,
            fmt::format("must lie in [0, body.length_m] = [0, {}]", body_length_m));
    probe.offset_B_m = o.vector3("offset_m");
    probes.push_back(std::move(probe));
  }
  return probes;
}

}  // namespace tcasim::rod::scenario_detail
