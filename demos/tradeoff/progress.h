// A progress bar on stderr: percentage, queries done / total, elapsed time and ETA. Redrawn
// in place (\r) at most 10 times a second on a terminal; when stderr is not a terminal (a
// log file, a test), only notes and one final line are printed.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace adb::tradeoff {

class Progress {
 public:
  explicit Progress(std::uint64_t total);

  /// Counts `n` more queries done; redraws when the last draw is old enough.
  void advance(std::uint64_t n = 1);
  /// Prints a line of text above the bar (the bar is redrawn below it).
  void note(const std::string& line);
  /// The final line (100 % or where the run stopped).
  void finish();

 private:
  void draw();
  std::string line() const;
  void clearLine();

  using Clock = std::chrono::steady_clock;
  std::uint64_t m_total, m_done = 0;
  Clock::time_point m_start, m_lastDraw;
  bool m_tty;
  bool m_drawn = false;
};

}  // namespace adb::tradeoff
