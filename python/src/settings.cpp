#include "settings.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <limits>

#include "adb/core/errors.h"

namespace adb::python {

void requireRange(double value, double lo, double hi, const char* name) {
  if (!(value >= lo && value <= hi)) {
    auto text = [](double x) {
      // Whole numbers without a fraction: "steps: 0, expected 1 to 100000000".
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, x == std::floor(x) && std::abs(x) < 1e15 ? "%.0f" : "%g", x);
      return std::string(buffer);
    };
    throw SettingsError(std::string(name) + ": " + text(value) + ", expected " + text(lo) +
                        " to " + text(hi));
  }
}

QuerySettings querySettings(const QueryOptions& o) {
  QuerySettings s;
  if (o.mode == "adb") {
    s.mode = QueryMode::Adb;
  } else if (o.mode == "exact") {
    s.mode = QueryMode::Exact;
  } else {
    throw SettingsError("mode: '" + o.mode + "', expected 'adb' or 'exact'");
  }
  if (!(o.pMin >= 0.0 && o.pMin <= 1.0)) {
    throw SettingsError("p_min: " + std::to_string(o.pMin) + ", expected a probability in [0, 1]");
  }
  s.pMin = o.pMin;
  if (o.kMin < 1 || o.kMin > std::numeric_limits<int>::max()) {
    throw SettingsError("k_min: " + std::to_string(o.kMin) + ", expected an integer >= 1");
  }
  s.kMin = static_cast<int>(o.kMin);
  if (o.budgetUs) {
    if (!(*o.budgetUs >= 0.0)) {
      throw SettingsError("budget_us: " + std::to_string(*o.budgetUs) +
                          ", expected microseconds >= 0 (None for no budget)");
    }
    s.budgetMicros = *o.budgetUs;
  }
  if (o.budgetPairs) {
    if (*o.budgetPairs < 0) {
      throw SettingsError("budget_pairs: " + std::to_string(*o.budgetPairs) +
                          ", expected node pairs >= 0 (None for no budget)");
    }
    s.budgetNodePairs = static_cast<std::uint64_t>(*o.budgetPairs);
  }
  s.stopAtFirstHit = o.stopAtFirstHit.value_or(true);
  if (o.maxWitnesses < 0 || o.maxWitnesses > (1 << 20)) {
    throw SettingsError("max_witnesses: " + std::to_string(o.maxWitnesses) +
                        ", expected an integer in [0, 1048576]");
  }
  s.maxWitnesses = static_cast<std::uint32_t>(o.maxWitnesses);
  if (!(o.contactMargin >= 0.0 && std::isfinite(o.contactMargin))) {
    throw SettingsError("contact_margin: " + std::to_string(o.contactMargin) +
                        ", expected a finite distance >= 0");
  }
  s.contactMargin = o.contactMargin;
  validate(s);
  return s;
}

}  // namespace adb::python
