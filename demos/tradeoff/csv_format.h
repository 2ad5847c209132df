// Small CSV formatting helpers shared by the writers: field quoting and number formats.
#pragma once

#include <string>

namespace adb::tradeoff {

/// A CSV field: quoted (RFC 4180) when it holds a comma, quote or line break.
std::string csvField(const std::string& text);

/// printf-style formatting into a std::string ("%.17g", ...).
std::string format(const char* fmt, double value);

}  // namespace adb::tradeoff
