#include "declared_counts.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <vector>

namespace adb::io::detail {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw MeshFileError(name + ": " + what);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Lines of the head, without their line ends; `complete` false for a last line the head cuts.
struct Lines {
  std::vector<std::string> lines;
  bool lastComplete = true;
};

Lines splitLines(const char* head, std::size_t size) {
  Lines out;
  std::string line;
  for (std::size_t i = 0; i < size; ++i) {
    if (head[i] == '\n') {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      out.lines.push_back(line);
      line.clear();
    } else {
      line += head[i];
    }
  }
  if (!line.empty()) {
    out.lines.push_back(line);
    out.lastComplete = false;
  }
  return out;
}

// The size in bytes of a PLY scalar type, 0 when unknown.
std::uint64_t plyTypeBytes(const std::string& type) {
  static const std::pair<const char*, std::uint64_t> kTypes[] = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},
      {"ushort", 2}, {"int16", 2}, {"uint16", 2}, {"int", 4},     {"uint", 4},
      {"int32", 4}, {"uint32", 4}, {"float", 4},  {"float32", 4}, {"double", 8},
      {"float64", 8}};
  for (const auto& [name, bytes] : kTypes) {
    if (type == name) return bytes;
  }
  return 0;
}

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t minBytes = 0;  // the fewest bytes one element can take in the file
};

void checkCount(const std::string& name, const std::string& what, std::uint64_t count,
                std::uint64_t limit, const char* limitName) {
  if (count > limit) {
    fail(name, what + " declares " + std::to_string(count) + ", more than the limit of " +
                   std::to_string(limit) + " (LoadLimits::" + limitName + ")");
  }
}

void checkFits(const std::string& name, const std::string& what, std::uint64_t count,
               std::uint64_t minBytes, std::uint64_t available) {
  // count * minBytes > available, without overflow.
  if (minBytes > 0 && count > available / minBytes) {
    fail(name, what + " declares " + std::to_string(count) + ", which needs at least " +
                   std::to_string(minBytes) + " bytes each; the file has " +
                   std::to_string(available) + " bytes after its header");
  }
}

void checkPly(const char* head, std::size_t headSize, std::uint64_t size, const std::string& name,
              const LoadLimits& limits) {
  const Lines lines = splitLines(head, headSize);
  bool ascii = true, format = false, ended = false;
  std::uint64_t headerBytes = 0;
  std::vector<PlyElement> elements;
  for (std::size_t i = 0; i < lines.lines.size(); ++i) {
    const std::string& line = lines.lines[i];
    if (i + 1 == lines.lines.size() && !lines.lastComplete) break;
    headerBytes += line.size() + 1;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (i == 0) continue;  // "ply"
    if (key == "end_header") {
      ended = true;
      break;
    }
    if (key == "format") {
      std::string kind;
      words >> kind;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian") {
        fail(name, "PLY header line " + std::to_string(i + 1) + ": unknown format '" + kind + "'");
      }
      ascii = kind == "ascii";
      format = true;
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos ||
          count.size() > 19) {
        fail(name, "PLY header line " + std::to_string(i + 1) + ": element '" + e.name +
                       "' has no valid count ('" + count + "')");
      }
      e.count = std::stoull(count);
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) {
        fail(name, "PLY header line " + std::to_string(i + 1) + ": a property before any element");
      }
      std::string type;
      words >> type;
      std::uint64_t bytes = 0;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        bytes = plyTypeBytes(countType);
        if (bytes == 0 || plyTypeBytes(itemType) == 0) {
          fail(name, "PLY header line " + std::to_string(i + 1) + ": unknown list types '" +
                         countType + "', '" + itemType + "'");
        }
      } else {
        bytes = plyTypeBytes(type);
        if (bytes == 0) {
          fail(name, "PLY header line " + std::to_string(i + 1) + ": unknown property type '" +
                         type + "'");
        }
      }
      // An ascii value is at least a digit and a separator.
      elements.back().minBytes += ascii ? 2 : bytes;
    }
  }
  if (!ended) {
    fail(name, headSize >= kHeaderBytes && size > headSize
                   ? "PLY header longer than " + std::to_string(kHeaderBytes) + " bytes"
                   : "PLY header has no end_header line (the file is cut short)");
  }
  if (!format) fail(name, "PLY header has no format line");
  const std::uint64_t body = size - std::min<std::uint64_t>(size, headerBytes);
  std::uint64_t needed = 0;
  for (const PlyElement& e : elements) {
    const std::string what = "PLY element '" + e.name + "'";
    if (e.name == "vertex") checkCount(name, what, e.count, limits.maxVertices, "maxVertices");
    if (e.name == "face") checkCount(name, what, e.count, limits.maxFaces, "maxFaces");
    checkFits(name, what, e.count, std::max<std::uint64_t>(e.minBytes, 1), body - std::min(body, needed));
    needed += e.count * std::max<std::uint64_t>(e.minBytes, 1);
  }
}

// OFF: a first line "OFF" (or COFF, NOFF, ...), maybe with the counts after it, else the
// counts "vertices faces edges" on the next line that is not a comment.
void checkOff(const char* head, std::size_t headSize, std::uint64_t size, const std::string& name,
              const LoadLimits& limits) {
  const Lines lines = splitLines(head, headSize);
  std::uint64_t headerBytes = 0;
  std::vector<std::string> numbers;
  for (std::size_t i = 0; i < lines.lines.size() && numbers.size() < 2; ++i) {
    std::istringstream words(lines.lines[i]);
    headerBytes += lines.lines[i].size() + 1;
    std::string word;
    bool first = true;
    while (words >> word && numbers.size() < 2) {
      if (word[0] == '#') break;
      if (i == 0 && first) {
        first = false;
        continue;  // the OFF keyword
      }
      numbers.push_back(word);
    }
  }
  if (numbers.size() < 2) return;  // assimp will say what is missing
  std::uint64_t counts[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string& n = numbers[static_cast<std::size_t>(k)];
    if (n.find_first_not_of("0123456789") != std::string::npos || n.size() > 19) {
      fail(name, std::string("OFF header: the ") + (k == 0 ? "vertex" : "face") +
                     " count is not a count ('" + n + "')");
    }
    counts[k] = std::stoull(n);
  }
  checkCount(name, "OFF vertex count", counts[0], limits.maxVertices, "maxVertices");
  checkCount(name, "OFF face count", counts[1], limits.maxFaces, "maxFaces");
  const std::uint64_t body = size - std::min<std::uint64_t>(size, headerBytes);
  // A vertex is at least "0 0 0" and a line end, a face at least "0" and a line end.
  checkFits(name, "OFF vertex count", counts[0], 6, body);
  checkFits(name, "OFF face count", counts[1], 2, body - std::min(body, 6 * counts[0]));
}

bool startsWithWord(const char* head, std::size_t size, const std::string& word) {
  if (size < word.size() || lower(std::string(head, word.size())) != word) return false;
  return size == word.size() || std::isspace(static_cast<unsigned char>(head[word.size()]));
}

bool isOff(const char* head, std::size_t size) {
  std::size_t end = 0;
  while (end < size && end < 16 && !std::isspace(static_cast<unsigned char>(head[end]))) ++end;
  const std::string first = lower(std::string(head, end));
  return first.size() >= 3 && first.compare(first.size() - 3, 3, "off") == 0 &&
         first.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789") == std::string::npos;
}

}  // namespace

void checkDeclaredCounts(const char* head, std::size_t headSize, std::uint64_t size,
                         const std::string& name, const LoadLimits& limits) {
  if (startsWithWord(head, headSize, "ply")) {
    checkPly(head, headSize, size, name, limits);
  } else if (isOff(head, headSize)) {
    checkOff(head, headSize, size, name, limits);
  }
}

}  // namespace adb::io::detail
