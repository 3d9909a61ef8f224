// Progress of a run on stderr: done/total, rate and ETA per phase ("base: shapes", ...).
// On a terminal one live line is rewritten in place (carriage return); otherwise (logs, CI) a
// plain line is printed at most every `interval_s` seconds and at the end. Thread-safe.
#pragma once

#include <chrono>
#include <mutex>
#include <ostream>
#include <string>

namespace symembed {

enum class ProgressMode { kQuiet, kLive, kPlain };

// kQuiet when quiet; else kLive when stderr is a terminal, kPlain otherwise.
ProgressMode DefaultProgressMode(bool quiet);

// "label  done/total  rate/s  ETA m:ss" (elapsed in seconds; no ETA before the first item).
std::string FormatProgress(const std::string& label, int done, int total, double elapsed_s);

class Progress {
 public:
  Progress(std::string label, int total, ProgressMode mode, std::ostream& out,
           double interval_s = 10.0);
  ~Progress();  // calls Finish()
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void Tick(int n = 1);
  // Prints the final line once ("... done in 12.3 s").
  void Finish();

 private:
  using Clock = std::chrono::steady_clock;
  double Elapsed() const;
  void PrintLocked(bool final_line);

  std::string label_;
  int total_;
  ProgressMode mode_;
  std::ostream& out_;
  double interval_s_;
  std::mutex mutex_;
  int done_ = 0;
  bool finished_ = false;
  Clock::time_point start_;
  Clock::time_point last_print_;
  size_t last_width_ = 0;
};

}  // namespace symembed
