#pragma once
/// Reading JSON input files (scenarios, TCA files, material files) strictly. Before the
/// document is built, one SAX pass over the text refuses, as InputError naming the file
/// and the key path (`<file>:body.length_m`, `<file>:actuators[1].drive`):
///  - nesting deeper than kMaxJsonDepth arrays/objects (printing or walking such a
///    document recursively would overflow the stack);
///  - a number outside the range of a double (1e400);
///  - a key that appears twice in one object (the JSON library would keep the last one).
/// Syntax errors are reported as `<what> = "<file>" is not valid JSON: ...`.
#include <nlohmann/json.hpp>
#include <string>

namespace tcasim::rod {

/// Deepest nesting of arrays and objects accepted (the top-level value is depth 1). The
/// scenario format nests at most 6 levels; 256 leaves room for any future format and keeps
/// recursive walks of the document far from the stack limit.
inline constexpr int kMaxJsonDepth = 256;

/// Checks `text` (the content of `file`) against the rules above and parses it. `what`
/// names the file's role in messages ("scenario file", "TCA file", a material's key).
nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const std::string& what);

/// Reads `path` and returns parse_json_text(content, path, what); an unreadable file is
/// `<what> = "<path>" cannot be opened: <reason>`.
nlohmann::json read_json_file(const std::string& path, const std::string& what);

}  // namespace tcasim::rod
