// scenario_fuzzer: libFuzzer target of tcasim's input readers (src/rod/scenario.hpp).
//
// Each input is written as one file and read by the three readers that take user files:
//   rod::read_scenario(path)        a scenario file (docs/scenario-format.md),
//   rod::read_tcas(path)            a TCA file or the TCAs of a scenario,
//   rod::load_material("fuzz", k)   a material data file (data/materials/*.json), found
//                                   through TCASIM_DATA_DIR pointed at a private folder
//                                   (which also holds copies of the shipped materials, so
//                                   a scenario naming one reads past its material).
// The contract under test (docs/conventions.md, house rules): bad input is rejected with
// tcasim::InputError, never a crash, a sanitizer report or another exception. An
// InputError is therefore a valid outcome; any other exception prints its message and
// aborts, so libFuzzer records the input as a crash.
//
// Usage: scripts/fuzz.sh SECONDS (builds in build-fuzz, seeds the corpus, runs).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>

#include "common/error.hpp"
#include "rod/scenario.hpp"

namespace {

struct Config {
  std::filesystem::path dir;   ///< private data dir: dir/materials/fuzz.json is the input
  std::filesystem::path file;  ///< the input file
};

Config& config() {
  static Config c;
  return c;
}

void remove_dir() {
  std::error_code ec;
  std::filesystem::remove_all(config().dir, ec);
}

[[noreturn]] void abort_with(const char* reader, const char* kind, const char* what) {
  std::fprintf(stderr, "scenario_fuzzer: %s threw %s (not an InputError): %s\n", reader, kind,
               what);
  std::abort();
}

/// Runs one reader: InputError is a rejection; anything else aborts.
template <class Read>
void run_reader(const char* name, Read read) {
  try {
    read();
  } catch (const tcasim::InputError&) {
  } catch (const std::exception& e) {
    abort_with(name, "an exception", e.what());
  } catch (...) {
    abort_with(name, "a non-std exception", "");
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  Config& c = config();
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/tcasim-fuzz-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) {
    std::perror("scenario_fuzzer: mkdtemp");
    std::abort();
  }
  c.dir = pattern;
  const std::filesystem::path materials = c.dir / "materials";
  std::filesystem::create_directories(materials);
  const std::filesystem::path shipped =
      std::filesystem::path(TCASIM_SHIPPED_DATA_DIR) / "materials";
  for (const auto& e : std::filesystem::directory_iterator(shipped)) {
    if (e.path().extension() == ".json")
      std::filesystem::copy_file(e.path(), materials / e.path().filename());
  }
  c.file = materials / "fuzz.json";
  std::atexit(remove_dir);
  setenv("TCASIM_DATA_DIR", c.dir.c_str(), 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Config& c = config();
  std::FILE* f = std::fopen(c.file.c_str(), "wb");
  if (f == nullptr || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) {
    std::perror("scenario_fuzzer: writing the input file");
    std::abort();
  }
  const std::string path = c.file.string();
  run_reader("rod::read_scenario", [&] { (void)tcasim::rod::read_scenario(path); });
  run_reader("rod::read_tcas", [&] { (void)tcasim::rod::read_tcas(path); });
  run_reader("rod::load_material", [&] { (void)tcasim::rod::load_material("fuzz", "material"); });
  return 0;
}
