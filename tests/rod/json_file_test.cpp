// Strict JSON reading (rod/json_file.hpp): deep nesting, numbers outside the double range
// and duplicate keys are input errors naming the file and the key path, before anything
// recursive runs; scenario and material files are read this way.
#include "rod/json_file.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.hpp"
#include "rod/scenario.hpp"

namespace tcasim::rod {
namespace {

/// Expects parse_json_text(text) to throw InputError with exactly `key` and a rule and
/// value containing the fragments.
void expect_refused(const std::string& text, const std::string& key, const std::string& value,
                    const std::string& rule) {
  try {
    (void)parse_json_text(text, "f.json", "scenario file");
    ADD_FAILURE() << "accepted; expected " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.value().find(value), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find(rule), std::string::npos) << e.what();
  }
}

std::string nested_arrays(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

/// The key of the InputError that parse_json_text(text) throws ("" if none).
std::string refused_key(const std::string& text, std::string* rule = nullptr) {
  try {
    (void)parse_json_text(text, "f.json", "scenario file");
  } catch (const InputError& e) {
    if (rule != nullptr) *rule = e.value() + " " + e.rule();
    return e.key();
  }
  return "";
}

TEST(JsonFile, NestingDeeperThanTheLimitIsRefusedWithoutRecursion) {
  // 100000 levels used to crash `tcasim solve` (stack overflow printing the value).
  std::string rule;
  const std::string key = refused_key(nested_arrays(100000), &rule);
  EXPECT_EQ(key.rfind("f.json:[0][0][0]", 0), 0u) << key;
  EXPECT_NE(key.find("..."), std::string::npos) << "a 256-level path is abbreviated: " << key;
  EXPECT_NE(rule.find("(nesting depth 257) nests arrays and objects deeper than 256 levels"),
            std::string::npos)
      << rule;
  EXPECT_EQ(refused_key("{\"name\": " + nested_arrays(300) + "}").rfind("f.json:name[0][0]", 0),
            0u);
  EXPECT_NO_THROW((void)parse_json_text(nested_arrays(kMaxJsonDepth), "f.json", "scenario file"));
}

TEST(JsonFile, NumberOutsideTheDoubleRangeNamesItsKeyPath) {
  expect_refused(R"({"body": {"length_m": 1e400}})", "f.json:body.length_m", "1e400",
                 "outside the range of a double");
  expect_refused(R"({"actuators": [{"name": "a"}, {"count": -2e308}]})",
                 "f.json:actuators[1].count", "-2e308", "outside the range of a double");
  expect_refused(R"({"v": [1, 2, [3, 1e999]]})", "f.json:v[2][1]", "1e999", "outside the range");
}

TEST(JsonFile, DuplicateKeyNamesItsKeyPath) {
  expect_refused(R"({"body": {"length_m": 0.04, "length_m": 0.05}})", "f.json:body.length_m",
                 "\"length_m\"", "appears twice");
  expect_refused(R"({"actuators": [{}, {"drive": 1, "name": "x", "drive": 2}]})",
                 "f.json:actuators[1].drive", "\"drive\"", "appears twice");
  // The same key in different objects is fine.
  EXPECT_NO_THROW((void)parse_json_text(
      R"({"a": {"k": 1}, "b": {"k": 2}, "c": [{"k": 1}, {"k": 2}]})", "f.json", "scenario file"));
}

TEST(JsonFile, SyntaxErrorNamesTheFile) {
  try {
    (void)parse_json_text("{\"schema\": ", "f.json", "scenario file");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "scenario file");
    EXPECT_EQ(e.value(), "\"f.json\"");
    EXPECT_NE(e.rule().find("is not valid JSON"), std::string::npos) << e.what();
  }
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("tcasim_json_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(JsonFile, ScenarioAndMaterialFilesAreReadStrictly) {
  const std::string deep = write_temp("deep.json", nested_arrays(100000));
  EXPECT_THROW((void)read_scenario(deep), InputError);
  const std::string dup =
      write_temp("dup.json", R"({"schema": "tcasim.scenario/1", "schema": "x"})");
  try {
    (void)read_scenario(dup);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), dup + ":schema") << e.what();
  }
  // A material file in a data directory: the same rules, under the file's path.
  const auto dir = std::filesystem::temp_directory_path() / "tcasim_json_test_data";
  std::filesystem::create_directories(dir / "materials");
  const std::string material = (dir / "materials" / "dup-material.json").string();
  std::ofstream(material) << R"({"source": "x", "source": "y"})";
  ASSERT_EQ(setenv("TCASIM_DATA_DIR", dir.string().c_str(), 1), 0);
  try {
    (void)load_material("dup-material", "tcas.t.material");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), material + ":source") << e.what();
  }
  ASSERT_EQ(unsetenv("TCASIM_DATA_DIR"), 0);
  std::filesystem::remove_all(dir);
  std::filesystem::remove(deep);
  std::filesystem::remove(dup);
}

}  // namespace
}  // namespace tcasim::rod
