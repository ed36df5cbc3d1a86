#include "common/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <utility>

namespace tcasim {

namespace {

double seconds_between(std::chrono::steady_clock::time_point a,
                       std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

ProgressReporter::ProgressReporter(std::FILE* stream, std::string label, std::size_t total,
                                   std::string unit, ProgressOptions options)
    : ProgressReporter(stream, std::move(label), total, std::move(unit), options,
                       isatty(fileno(stream)) == 1) {}

ProgressReporter::ProgressReporter(std::FILE* stream, std::string label, std::size_t total,
                                   std::string unit, ProgressOptions options, bool interactive)
    : stream_(stream),
      label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      options_(options),
      interactive_(interactive),
      start_(std::chrono::steady_clock::now()),
      last_line_(start_) {}

void ProgressReporter::update(std::size_t done) {
  const auto now = std::chrono::steady_clock::now();
  const bool last = done >= total_;
  if (!interactive_) {
    // A line when another line_fraction of the total is done, line_seconds have passed, or at the
    // end; nothing else (no formatting, no flush) otherwise, since callers such as the sweep's
    // threads update after every point under a shared lock.
    const double step = options_.line_fraction * static_cast<double>(total_);
    const bool fraction_due = static_cast<double>(done - last_line_done_) >= step;
    const bool time_due = seconds_between(last_line_, now) >= options_.line_seconds;
    if (!(last || fraction_due || time_due)) return;
    last_line_ = now;
    last_line_done_ = done;
  }
  const std::string text = fmt::format("{}: {}/{} {}, {:.2f} s", label_, done, total_, unit_,
                                       seconds_between(start_, now));
  if (interactive_) {
    fmt::print(stream_, "\r{}{}", text, last ? "\n" : "");
  } else {
    fmt::print(stream_, "{}\n", text);
  }
  std::fflush(stream_);
}

}  // namespace tcasim
