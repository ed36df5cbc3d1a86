#include "rod/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/error.hpp"

namespace tcasim::rod {
namespace {

/// Attempts at a fresh temporary name before giving up (names are unique per process and
/// call, so a clash means a stale file of a crashed process with the same pid).
constexpr int kTemporaryNameAttempts = 100;

std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

/// Writes all of `text` to `fd`; false (errno set) on failure.
bool write_all(int fd, const std::string& text) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& text,
                           const std::string& what) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; attempt < kTemporaryNameAttempts && fd < 0; ++attempt) {
    tmp = (dir / fmt::format(".{}.tmp-{}-{}", target.filename().string(), ::getpid(), counter++))
              .string();
    // 0666 and the umask: the permissions a plain std::ofstream would give the file.
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) {
    throw InputError(what, quoted(path),
                     fmt::format("cannot be opened for writing: {}", std::strerror(errno)));
  }
  const bool written = write_all(fd, text);
  int saved = errno;
  const bool closed = ::close(fd) == 0;
  if (written && !closed) saved = errno;
  if (!written || !closed) {
    ::unlink(tmp.c_str());
    throw InputError(what, quoted(path),
                     fmt::format("could not be written: {}", std::strerror(saved)));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    saved = errno;
    ::unlink(tmp.c_str());
    throw InputError(what, quoted(path),
                     fmt::format("could not be written: {}", std::strerror(saved)));
  }
}

}  // namespace tcasim::rod
