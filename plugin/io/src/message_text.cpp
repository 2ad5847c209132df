#include "adb/io/message_text.h"

namespace adb::io {

std::string excerpt(std::string_view text, std::size_t maxBytes) {
  std::size_t keep = text.size();
  if (keep > maxBytes) {
    keep = maxBytes;
    // Not inside a UTF-8 sequence: back up over continuation bytes (10xxxxxx).
    while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80) --keep;
  }
  std::string out(text.substr(0, keep));
  for (char& c : out) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) c = '?';
  }
  if (keep < text.size()) out += "... (" + std::to_string(text.size() - keep) + " more bytes)";
  return out;
}

std::string quoted(std::string_view word) { return "'" + excerpt(word, 60) + "'"; }

}  // namespace adb::io
