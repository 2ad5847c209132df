// FrameSettings' validation, beside the settings (as adb::validate(QuerySettings) is beside
// QuerySettings).
#include "adb/bullet/frame_budget.h"

#include <cmath>
#include <cstddef>
#include <string>

#include "adb/core/errors.h"

namespace adb {
namespace {

void require(bool ok, const char* field, double value, const char* rule) {
  if (ok) return;
  throw SettingsError(std::string("FrameSettings::") + field + " is " + std::to_string(value) +
                      "; it must be " + rule);
}

}  // namespace

std::optional<FrameSettings::Fronts> frontsNamed(const std::string& name) {
  for (std::size_t i = 0; i < kFrontsNames.size(); ++i) {
    if (name == kFrontsNames[i]) return static_cast<FrameSettings::Fronts>(i);
  }
  return std::nullopt;
}

void validate(const FrameSettings& s) {
  require(!std::isnan(s.budgetMicros) && s.budgetMicros >= 0.0, "budgetMicros", s.budgetMicros,
          ">= 0 (infinity for none)");
  require(s.pMin >= 0.0 && s.pMin <= 1.0, "pMin", s.pMin, "in [0, 1]");
  require(s.kMin >= 0, "kMin", s.kMin, ">= 0 (0: never stop on quality)");
  require(s.pAccept >= 0.0 && s.pAccept <= 1.0, "pAccept", s.pAccept, "in [0, 1]");
  require(s.maxPlausibleContacts >= 0, "maxPlausibleContacts", s.maxPlausibleContacts,
          ">= 0");
  require(s.softCfm >= 0.0 && std::isfinite(s.softCfm), "softCfm", s.softCfm,
          "finite and >= 0");
  require(s.threads >= 0 && s.threads <= kMaxThreads, "threads", s.threads,
          "in [0, 256] (0: all hardware threads)");
}

}  // namespace adb
