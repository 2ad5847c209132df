// A progress bar on stderr for long runs (the study's queries, a scene's steps): percentage,
// units done / total, elapsed time and ETA. Redrawn
// in place (\r) at most 10 times a second on a terminal; when stderr is not a terminal (a
// log file, a test), only notes and one final line are printed.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace adb::tools {

class Progress {
 public:
  /// `unit` names what is counted ("queries", "steps").
  Progress(std::uint64_t total, std::string unit);

  /// Counts `n` more units done; redraws when the last draw is old enough.
  void advance(std::uint64_t n = 1);
  /// Takes the bar off the terminal's line so that something else can print there; the next
  /// advance() draws it again.
  void hide();
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
  std::string m_unit;
  Clock::time_point m_start, m_lastDraw;
  bool m_tty;
  bool m_drawn = false;
};

}  // namespace adb::tools
