// The timing policy of the study, the same for every method:
//   one untimed warm-up run unless `warmup` is off (caches warm, as for a pair queried frame
//   after frame; scratch memory grown), then `repeats` runs, each timed with std::chrono::steady_clock around
//   the method's query call; the fastest is the query's time (the machine is shared and
//   noisy: interference only ever adds time), and the answer of that run is the one recorded
//   (it matters for wall-clock budgets, where runs may stop at different points).
#pragma once

#include "method.h"

namespace adb::tradeoff {

struct TimedAnswer {
  Answer answer;
  double nanoseconds = 0.0;
};

TimedAnswer timeQuery(Method& method, const Pose& a, const Pose& b, int repeats,
                      bool warmup = true);

}  // namespace adb::tradeoff
