#include "harness/progress.h"

#include <unistd.h>

#include <cstdio>

namespace symembed {

ProgressMode DefaultProgressMode(bool quiet) {
  if (quiet) return ProgressMode::kQuiet;
  return ::isatty(STDERR_FILENO) ? ProgressMode::kLive : ProgressMode::kPlain;
}

std::string FormatProgress(const std::string& label, int done, int total, double elapsed_s) {
  char text[256];
  const double rate = elapsed_s > 0 ? done / elapsed_s : 0.0;
  int n = std::snprintf(text, sizeof text, "%s  %d/%d  %.2f/s", label.c_str(), done, total, rate);
  if (done > 0 && done < total && rate > 0 && n > 0 && n < static_cast<int>(sizeof text)) {
    const long eta = static_cast<long>((total - done) / rate + 0.5);
    std::snprintf(text + n, sizeof text - n, "  ETA %ld:%02ld", eta / 60, eta % 60);
  }
  return text;
}

Progress::Progress(std::string label, int total, ProgressMode mode, std::ostream& out,
                   double interval_s)
    : label_(std::move(label)),
      total_(total),
      mode_(mode),
      out_(out),
      interval_s_(interval_s),
      start_(Clock::now()),
      last_print_(start_) {
  if (mode_ == ProgressMode::kLive) {
    std::lock_guard<std::mutex> lock(mutex_);
    PrintLocked(false);
  }
}

Progress::~Progress() { Finish(); }

double Progress::Elapsed() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void Progress::Tick(int n) {
  if (mode_ == ProgressMode::kQuiet) return;
  std::lock_guard<std::mutex> lock(mutex_);
  done_ += n;
  const double since = std::chrono::duration<double>(Clock::now() - last_print_).count();
  // A live line is cheap to redraw but is throttled to keep the terminal readable.
  const double interval = mode_ == ProgressMode::kLive ? 0.1 : interval_s_;
  if (since >= interval) PrintLocked(false);
}

void Progress::Finish() {
  if (mode_ == ProgressMode::kQuiet) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  PrintLocked(true);
}

void Progress::PrintLocked(bool final_line) {
  last_print_ = Clock::now();
  std::string line = FormatProgress(label_, done_, total_, Elapsed());
  if (final_line) {
    char tail[64];
    std::snprintf(tail, sizeof tail, "  done in %.1f s", Elapsed());
    line = label_ + "  " + std::to_string(done_) + "/" + std::to_string(total_) + tail;
  }
  if (mode_ == ProgressMode::kLive) {
    const size_t width = line.size();
    if (width < last_width_) line += std::string(last_width_ - width, ' ');
    last_width_ = width;
    out_ << '\r' << line;
    if (final_line) out_ << '\n';
  } else {
    out_ << line << '\n';
  }
  out_.flush();
}

}  // namespace symembed
