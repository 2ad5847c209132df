// Small CSV formatting helpers shared by the writers: field quoting, number formats and a
// method's parameter columns.
#pragma once

#include <string>

#include "method.h"

namespace adb::tradeoff {

/// A CSV field: quoted (RFC 4180) when it holds a comma, quote or line break.
std::string csvField(const std::string& text);

/// printf-style formatting into a std::string ("%.17g", ...).
std::string format(const char* fmt, double value);
/// format(), or an empty field for NaN (a figure the row cannot have).
std::string formatOrEmpty(const char* fmt, double value);

/// The `p_min,k_min,budget_us` fields of a method setting (three fields, two commas):
/// p_min and k_min where the method has them (ADB), budget_us where it has a time budget.
std::string methodParamFields(const MethodParams& params);

}  // namespace adb::tradeoff
