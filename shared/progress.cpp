// Progress bar drawing.
#include "progress.h"

#include <unistd.h>

#include <cstdio>
#include <utility>

namespace adb::tools {
namespace {

constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr int kBarWidth = 30;

std::string hms(double seconds) {
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%02lld:%02lld", s / 60, s % 60);
  }
  return buf;
}

}  // namespace

Progress::Progress(std::uint64_t total, std::string unit)
    : m_total(total), m_unit(std::move(unit)), m_start(Clock::now()), m_lastDraw(m_start), m_tty(isatty(STDERR_FILENO) != 0) {}

void Progress::advance(std::uint64_t n) {
  m_done += n;
  if (!m_tty) return;
  const auto now = Clock::now();
  if (m_drawn && now - m_lastDraw < kRedrawInterval) return;
  m_lastDraw = now;
  draw();
}

std::string Progress::line() const {
  const double fraction = m_total ? static_cast<double>(m_done) / static_cast<double>(m_total) : 1.0;
  const double elapsed = std::chrono::duration<double>(Clock::now() - m_start).count();
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kBarWidth, '.');
  const std::string eta = m_done > 0 && m_done < m_total
                              ? hms(elapsed * (1.0 - fraction) / fraction)
                              : "--:--";
  char buf[160];
  std::snprintf(buf, sizeof buf, "[%s] %5.1f%%  %llu/%llu %s  elapsed %s  ETA %s",
                bar.c_str(), 100.0 * fraction, static_cast<unsigned long long>(m_done),
                static_cast<unsigned long long>(m_total), m_unit.c_str(), hms(elapsed).c_str(), eta.c_str());
  return buf;
}

void Progress::clearLine() {
  if (m_tty && m_drawn) std::fputs("\r\033[K", stderr);
}

void Progress::draw() {
  clearLine();
  std::fputs(line().c_str(), stderr);
  std::fflush(stderr);
  m_drawn = true;
}

void Progress::hide() {
  clearLine();
  m_drawn = false;
}

void Progress::note(const std::string& text) {
  clearLine();
  std::fprintf(stderr, "%s\n", text.c_str());
  m_drawn = false;
  if (m_tty) draw();
}

void Progress::finish() {
  clearLine();
  std::fprintf(stderr, "%s\n", line().c_str());
  m_drawn = false;
}

}  // namespace adb::tools
