#include "rod/tca_choice.hpp"

#include <fmt/format.h>

#include <utility>

#include "common/error.hpp"
#include "rod/scenario.hpp"

namespace tcasim::rod {

std::shared_ptr<const tca::Tca> select_tca(const TcaMap& tcas, const std::string& source,
                                           const TcaChoice& choice, const KeyName& key) {
  std::string ids;
  for (const auto& [name, t] : tcas) ids += (ids.empty() ? "" : ", ") + name;
  std::shared_ptr<const tca::Tca> chosen;
  if (!choice.id) {
    require(tcas.size() == 1, key("tca"), "(missing)",
            fmt::format("is required: {} defines {} TCAs: {}", source, tcas.size(), ids));
    chosen = tcas.begin()->second;
  } else {
    const auto it = tcas.find(*choice.id);
    require(it != tcas.end(), key("tca"), *choice.id,
            fmt::format("is not a TCA of {} (it has: {})", source, ids));
    chosen = it->second;
  }
  const std::optional<std::string>& form = choice.f12_form;
  if (form) {
    require(*form == "paper" || *form == "castigliano", key("f12_form"), *form,
            "must be paper or castigliano");
  }
  if (!choice.material && !form) return chosen;
  tca::Parameters p = chosen->parameters();
  tca::Material m = chosen->material();
  if (choice.material) {
    m = load_material(*choice.material, key("material"));
    // Without an explicit form, the overriding material's own form applies (as in a file).
    if (!form && m.f12_form) p.f12_form = *m.f12_form;
  }
  if (form) p.f12_form = *form == "paper" ? tca::F12Form::kPaper : tca::F12Form::kCastigliano;
  return std::make_shared<const tca::Tca>(p, std::move(m));
}

}  // namespace tcasim::rod
