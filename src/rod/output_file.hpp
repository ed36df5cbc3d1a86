#pragma once
/// Output files are written whole or not at all: the text goes to a temporary file in the
/// same directory, which is then renamed over the destination (rename(2) is atomic within
/// one file system). A failed or interrupted write leaves any existing file untouched and
/// removes the temporary. (Not a guard against power loss: the data is not fsync'ed.)
#include <sstream>
#include <string>
#include <utility>

namespace tcasim::rod {

/// Writes `text` to `path` atomically. Throws InputError(`what`, "<path>", reason) when the
/// temporary cannot be created or written, or the rename fails; the temporary is removed.
void write_file_atomically(const std::string& path, const std::string& text,
                           const std::string& what);

/// A stream for writers that print piece by piece (CSV tables): the text collects in memory
/// and commit() writes it with write_file_atomically. Without commit() nothing is written.
class AtomicOutput : public std::ostringstream {
 public:
  AtomicOutput(std::string path, std::string what)
      : path_(std::move(path)), what_(std::move(what)) {}
  void commit() { write_file_atomically(path_, str(), what_); }

 private:
  std::string path_, what_;
};

}  // namespace tcasim::rod
