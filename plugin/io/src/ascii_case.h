// Internal: ASCII lower case for extensions, format words and paths. std::tolower on a plain
// char is undefined for bytes above 127 (a damaged file's), hence the cast, in one place.
#pragma once

#include <cctype>
#include <string>

namespace adb::io::detail {

inline std::string lowered(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace adb::io::detail
