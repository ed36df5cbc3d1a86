#pragma once
/// Choosing one TCA of a scenario's or TCA file's `tcas` with optional material and f12-form
/// overrides: the selection of `tcasim tca`, `tcasim fit` and tcasim.tca_curve, which differ
/// only in how they name their arguments in error messages.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "tca/tca.hpp"

namespace tcasim::rod {

/// The TCAs of a scenario or TCA file by id (RodModel::tcas, read_tcas).
using TcaMap = std::map<std::string, std::shared_ptr<const tca::Tca>>;

/// What to pick; an absent field takes the default.
struct TcaChoice {
  std::optional<std::string> id;        ///< the TCA id (required when the map has several)
  std::optional<std::string> material;  ///< a shipped material replacing the TCA's own
  std::optional<std::string> f12_form;  ///< "paper" or "castigliano" (Eq. (4) factor)
};

/// The name under which an argument is reported: key("tca"), key("material"),
/// key("f12_form") -> e.g. "--tca", "--material", "--f12-form" on the command line.
using KeyName = std::function<std::string(const std::string& key)>;

/// Picks `choice.id` of `tcas` (the only one when no id is given), then applies the overrides:
/// the material's own f12 form unless `choice.f12_form` is given (as in a file). InputError
/// naming key("tca") for a missing or unknown id (listing the ids of `source`, e.g. the file's
/// path), key("f12_form") for a form other than paper/castigliano, key("material") for an
/// unknown material (rod::load_material).
std::shared_ptr<const tca::Tca> select_tca(const TcaMap& tcas, const std::string& source,
                                           const TcaChoice& choice, const KeyName& key);

}  // namespace tcasim::rod
