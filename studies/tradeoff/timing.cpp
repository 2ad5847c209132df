// timeQuery: a warm-up (unless off), then the fastest of `repeats` timed runs (timing.h).
#include "timing.h"

#include <chrono>

namespace adb::tradeoff {

TimedAnswer timeQuery(Method& method, const Pose& a, const Pose& b, int repeats, bool warmup) {
  using Clock = std::chrono::steady_clock;
  if (warmup) method.query(a, b);  // untimed
  TimedAnswer best;
  for (int i = 0; i < repeats; ++i) {
    const auto start = Clock::now();
    const Answer answer = method.query(a, b);
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - start).count();
    if (i == 0 || ns < best.nanoseconds) best = TimedAnswer{answer, ns};
  }
  return best;
}

}  // namespace adb::tradeoff
