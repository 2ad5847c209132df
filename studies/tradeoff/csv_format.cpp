// CSV field quoting and number formatting.
#include "csv_format.h"

#include <cmath>
#include <cstdio>

namespace adb::tradeoff {

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string format(const char* fmt, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, value);
  return buf;
}

std::string formatOrEmpty(const char* fmt, double value) {
  return std::isnan(value) ? "" : format(fmt, value);
}

std::string methodParamFields(const MethodParams& p) {
  const std::string quality =
      p.hasQuality ? format("%.15g", p.pMin) + ',' + std::to_string(p.kMin) : std::string(",");
  return quality + ',' + (std::isfinite(p.budgetUs) ? format("%.15g", p.budgetUs) : "");
}

}  // namespace adb::tradeoff
