// rod::select_tca: the TCA picked by id (or the only one), the f12-form override, and the
// errors naming each argument under the caller's name for it (rod/tca_choice.hpp).
#include "rod/tca_choice.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"
#include "rod/scenario.hpp"

namespace {

using namespace tcasim;

const std::string kTwoTcas =
    std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/fig5-tcas.json";

std::string flag(const std::string& key) { return "--" + key; }

InputError error_of(const rod::TcaMap& tcas, const rod::TcaChoice& choice) {
  try {
    rod::select_tca(tcas, "fig5", choice, flag);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

TEST(SelectTca, PicksTheNamedTcaAndKeepsItWithoutOverrides) {
  const rod::TcaMap tcas = rod::read_tcas(kTwoTcas);
  EXPECT_EQ(rod::select_tca(tcas, "fig5", {"four-thread", {}, {}}, flag), tcas.at("four-thread"));
  const rod::TcaMap one = {{"only", tcas.at("three-thread")}};
  EXPECT_EQ(rod::select_tca(one, "one", {}, flag), tcas.at("three-thread"));
}

TEST(SelectTca, AppliesTheF12FormOverride) {
  const rod::TcaMap tcas = rod::read_tcas(kTwoTcas);
  for (const auto& [form, expected] :
       {std::pair{"paper", tca::F12Form::kPaper}, {"castigliano", tca::F12Form::kCastigliano}}) {
    const auto t = rod::select_tca(tcas, "fig5", {"three-thread", {}, form}, flag);
    EXPECT_EQ(t->parameters().f12_form, expected) << form;
    EXPECT_EQ(t->material().name, tcas.at("three-thread")->material().name);
  }
}

TEST(SelectTca, ErrorsNameTheArgumentAsTheCallerDoes) {
  const rod::TcaMap tcas = rod::read_tcas(kTwoTcas);
  const InputError missing = error_of(tcas, {});
  EXPECT_EQ(missing.key(), "--tca");
  EXPECT_EQ(missing.value(), "(missing)");
  EXPECT_EQ(missing.rule(), "is required: fig5 defines 2 TCAs: four-thread, three-thread");
  const InputError unknown = error_of(tcas, {"two-thread", {}, {}});
  EXPECT_EQ(unknown.key(), "--tca");
  EXPECT_EQ(unknown.rule(), "is not a TCA of fig5 (it has: four-thread, three-thread)");
  const InputError form = error_of(tcas, {"three-thread", {}, "exact"});
  EXPECT_EQ(form.key(), "--f12_form");
  EXPECT_EQ(form.rule(), "must be paper or castigliano");
  EXPECT_EQ(error_of(tcas, {"three-thread", "no-such-material", {}}).key(), "--material");
}

}  // namespace
