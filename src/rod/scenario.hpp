#pragma once
/// Reading scenario files (docs/scenario-format.md) into a RodModel, and TCA material
/// data files (data/materials/*.json). Every malformed input throws InputError naming
/// the key path, the value and the rule; unknown keys are rejected.
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "common/data_dir.hpp"
#include "rod/model.hpp"
#include "tca/tca.hpp"

namespace tcasim::rod {

/// Parses a scenario document. `base_dir` resolves relative paths (none yet).
RodModel parse_scenario(const nlohmann::json& doc, const std::string& base_dir = ".");

/// Reads and parses a scenario file (throws InputError naming the file on I/O or JSON errors).
RodModel read_scenario(const std::string& path);

/// Reads only the `tcas` of a file: either a full scenario or a TCA file
/// (schema "tcasim.tcas/1" with `name`, optional `comment`, and `tcas`).
std::map<std::string, std::shared_ptr<const tca::Tca>> read_tcas(const std::string& path);

/// Parses a TCA material object (inline, or a data file's content). `key` prefixes messages.
/// The name is the object's `name`, else "inline".
tca::Material parse_material(const nlohmann::json& j, const std::string& key);

/// Loads a shipped material by name: `<data dir>/materials/<name>.json`. The data dir is
/// data_directory() (common/data_dir.hpp: the environment variable TCASIM_DATA_DIR if set,
/// else the installed package's data, else the source tree's data/). A bad
/// or unknown name is reported under `key` (listing the shipped names); an error inside
/// the file under `<file path>:<key in the file>`. The material's name is `name`.
tca::Material load_material(const std::string& name, const std::string& key);

/// Directory holding shipped data (materials/, scenarios/): common/data_dir.hpp.
using tcasim::data_directory;

}  // namespace tcasim::rod
