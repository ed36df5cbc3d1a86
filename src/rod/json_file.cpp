#include "rod/json_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_set>
#include <vector>

#include "common/error.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// Longest key path quoted in a message (a path 256 levels deep is abbreviated).
constexpr std::size_t kMaxPathChars = 120;
/// nlohmann's exception id for a number that does not fit a double.
constexpr int kNumberOverflowId = 406;

/// SAX pass that keeps the key path of the value being read and throws InputError on the
/// rules of json_file.hpp. It builds nothing, so it is as cheap as a syntax check.
class StrictSax : public nlohmann::json_sax<json> {
 public:
  StrictSax(const std::string& file, const std::string& what) : file_(file), what_(what) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    Frame& top = stack_.back();
    if (!top.seen.insert(k).second) {
      top.key = k;
      throw InputError(key_here(), json(k).dump(),
                       "appears twice in the same object (JSON keys must be unique; the reader "
                       "would silently keep the last value)");
    }
    top.key = k;
    return true;
  }

  bool parse_error(std::size_t, const std::string& last_token,
                   const nlohmann::detail::exception& e) override {
    if (e.id == kNumberOverflowId) {
      throw InputError(key_here(), last_token,
                       fmt::format("is outside the range of a double (magnitude up to {:.6g})",
                                   std::numeric_limits<double>::max()));
    }
    throw InputError(what_, json(file_).dump(), fmt::format("is not valid JSON: {}", e.what()));
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t next = 0;  ///< array: index of the next element
    std::string key;       ///< object: the current key
    std::unordered_set<std::string> seen;
  };

  /// A value starts in the current container: an array moves to its next element.
  void advance() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().next;
  }
  bool value() {
    advance();
    return true;
  }
  bool open(bool array) {
    // The key path of the new container, before it is pushed.
    if (static_cast<int>(stack_.size()) + 1 > kMaxJsonDepth) {
      throw InputError(
          key_here(), fmt::format("(nesting depth {})", stack_.size() + 1),
          fmt::format("nests arrays and objects deeper than {} levels", kMaxJsonDepth));
    }
    advance();
    stack_.push_back(Frame{array, 0, {}, {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  /// `<file>:<key path>` of the value being read (for an array: its next element).
  std::string key_here() const {
    std::string path;
    for (std::size_t k = 0; k < stack_.size(); ++k) {
      const Frame& f = stack_[k];
      if (path.size() > kMaxPathChars) {
        path += "...";
        break;
      }
      if (f.array) {
        // The innermost array is about to read element `next` (errors are raised before
        // advance()); an outer one has advanced past the element that holds it.
        path += fmt::format("[{}]", k + 1 == stack_.size() ? f.next : f.next - 1);
      } else {
        path += (path.empty() ? "" : ".") + f.key;
      }
    }
    return file_ + ":" + (path.empty() ? std::string("(document)") : path);
  }

  const std::string& file_;
  const std::string& what_;
  std::vector<Frame> stack_;
};

}  // namespace

json parse_json_text(const std::string& text, const std::string& file, const std::string& what) {
  StrictSax sax(file, what);
  json::sax_parse(text, &sax);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    // Unreachable after the SAX pass (same parser); kept so a library change cannot crash.
    throw InputError(what, json(file).dump(), fmt::format("is not valid JSON: {}", e.what()));
  }
}

json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(what, json(path).dump(),
                     fmt::format("cannot be opened: {}", std::strerror(errno)));
  }
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) {
    throw InputError(what, json(path).dump(),
                     fmt::format("cannot be read: {}", std::strerror(errno)));
  }
  return parse_json_text(content.str(), path, what);
}

}  // namespace tcasim::rod
