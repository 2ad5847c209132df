#include "ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include "adb/io/message_text.h"

namespace adb::io::detail {
namespace {

constexpr std::size_t kMaxHeaderBytes = 64 * 1024;

enum class Format { Ascii, LittleEndian, BigEndian };

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool list = false;
  Type countType = Type::UInt8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t bytes = 0;  // where the body starts
};

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw MeshFileError(name + ": " + what);
}

bool typeOf(const std::string& word, Type& type) {
  static const std::pair<const char*, Type> kTypes[] = {
      {"char", Type::Int8},     {"int8", Type::Int8},      {"uchar", Type::UInt8},
      {"uint8", Type::UInt8},   {"short", Type::Int16},    {"int16", Type::Int16},
      {"ushort", Type::UInt16}, {"uint16", Type::UInt16},  {"int", Type::Int32},
      {"int32", Type::Int32},   {"uint", Type::UInt32},    {"uint32", Type::UInt32},
      {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64},
      {"float64", Type::Float64}};
  for (const auto& [n, t] : kTypes) {
    if (word == n) {
      type = t;
      return true;
    }
  }
  return false;
}

std::size_t bytesOf(Type t) {
  switch (t) {
    case Type::Int8: case Type::UInt8: return 1;
    case Type::Int16: case Type::UInt16: return 2;
    case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 1;
}

bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

// A whole number in [0, max] (a count or an index read as a double); the range is checked
// before any conversion to an integer type, which would be undefined beyond it.
bool isCount(double v, double max) { return v >= 0 && v <= max && v == std::floor(v); }

// The fewest bytes one element can take: a list at its count alone, an ascii value at a
// character and a separator.
std::uint64_t minBytes(const Element& e, Format f) {
  std::uint64_t n = 0;
  for (const Property& p : e.properties) {
    n += f == Format::Ascii ? 2 : bytesOf(p.list ? p.countType : p.type);
  }
  return std::max<std::uint64_t>(n, 1);
}

Header readHeader(const char* data, std::size_t size, const std::string& name) {
  Header h;
  std::size_t at = 0;
  bool format = false;
  for (int line = 1;; ++line) {
    const char* end = static_cast<const char*>(std::memchr(data + at, '\n', size - at));
    if (end == nullptr) {
      fail(name, size >= kMaxHeaderBytes ? "PLY header longer than 64 kB"
                                         : "PLY header has no end_header line (the file is cut short)");
    }
    std::string text(data + at, end);
    at = static_cast<std::size_t>(end - data) + 1;
    if (at > kMaxHeaderBytes) fail(name, "PLY header longer than 64 kB");
    if (!text.empty() && text.back() == '\r') text.pop_back();
    std::istringstream words(text);
    std::string key;
    words >> key;
    const std::string where = "PLY header line " + std::to_string(line) + ": ";
    if (line == 1) {
      if (key != "ply") fail(name, "not a PLY file (no 'ply' on the first line)");
      continue;
    }
    if (key == "end_header") break;
    if (key == "format") {
      std::string kind;
      words >> kind;
      if (kind == "ascii") h.format = Format::Ascii;
      else if (kind == "binary_little_endian") h.format = Format::LittleEndian;
      else if (kind == "binary_big_endian") h.format = Format::BigEndian;
      else fail(name, where + "unknown format " + quoted(kind));
      format = true;
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      std::uint64_t n = 0;
      if (!parseIndex(count, n)) {
        fail(name, where + "element " + quoted(e.name) + " has no valid count");
      }
      e.count = n;
      h.elements.push_back(e);
    } else if (key == "property") {
      if (h.elements.empty()) fail(name, where + "a property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        p.list = true;
        if (!typeOf(countType, p.countType) || !isInteger(p.countType) || !typeOf(itemType, p.type)) {
          fail(name, where + "bad list types " + quoted(countType) + ", " + quoted(itemType));
        }
      } else if (!typeOf(type, p.type)) {
        fail(name, where + "unknown property type " + quoted(type));
      }
      words >> p.name;
      h.elements.back().properties.push_back(p);
    } else if (key != "comment" && key != "obj_info" && !key.empty()) {
      fail(name, where + "unknown keyword " + quoted(key));
    }
  }
  if (!format) fail(name, "PLY header has no format line");
  h.bytes = at;
  return h;
}

// Reads values one after another, ascii or binary.
class Values {
 public:
  Values(const char* data, std::size_t size, std::size_t at, Format format)
      : m_data(data), m_size(size), m_at(at), m_format(format), m_tokens(data, size, at, false) {}

  bool read(Type type, double& out) {
    if (m_format == Format::Ascii) {
      std::string token;
      return m_tokens.next(token) && parseNumber(token, out);
    }
    const std::size_t n = bytesOf(type);
    if (m_size - m_at < n) return false;
    unsigned char b[8];
    std::memcpy(b, m_data + m_at, n);
    m_at += n;
    const bool little = m_format == Format::LittleEndian;
    std::uint64_t u = 0;
    for (std::size_t k = 0; k < n; ++k) u |= std::uint64_t(b[little ? k : n - 1 - k]) << (8 * k);
    out = decode(type, u);
    return true;
  }
  std::size_t left() const { return m_format == Format::Ascii ? m_size : m_size - m_at; }

 private:
  static double decode(Type type, std::uint64_t u) {
    switch (type) {
      case Type::Int8: return static_cast<std::int8_t>(u);
      case Type::UInt8: return static_cast<std::uint8_t>(u);
      case Type::Int16: return static_cast<std::int16_t>(u);
      case Type::UInt16: return static_cast<std::uint16_t>(u);
      case Type::Int32: return static_cast<std::int32_t>(u);
      case Type::UInt32: return static_cast<std::uint32_t>(u);
      case Type::Float32: {
        const auto bits = static_cast<std::uint32_t>(u);
        float f;
        std::memcpy(&f, &bits, 4);
        return f;
      }
      case Type::Float64: {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
      }
    }
    return 0;
  }

  const char* m_data;
  std::size_t m_size, m_at;
  Format m_format;
  TextTokens m_tokens;
};

// Which of the vertex element's properties are x, y and z; which of the face element's is
// the index list.
struct Roles {
  int x = -1, y = -1, z = -1, indices = -1;
};

Roles rolesOf(const Element& e) {
  Roles r;
  for (int i = 0; i < static_cast<int>(e.properties.size()); ++i) {
    const Property& p = e.properties[static_cast<std::size_t>(i)];
    if (p.list) {
      if (r.indices < 0 || p.name == "vertex_indices" || p.name == "vertex_index") r.indices = i;
    } else if (p.name == "x") {
      r.x = i;
    } else if (p.name == "y") {
      r.y = i;
    } else if (p.name == "z") {
      r.z = i;
    }
  }
  return r;
}

void checkCounts(const Header& h, std::size_t size, const std::string& name, const LoadLimits& limits) {
  std::uint64_t available = size - h.bytes;
  for (const Element& e : h.elements) {
    const std::string what =
        "PLY element " + quoted(e.name) + " declares " + std::to_string(e.count);
    if (e.name == "vertex" && e.count > limits.maxVertices) {
      fail(name, what + ", more than the limit of " + std::to_string(limits.maxVertices) +
                     " (LoadLimits::maxVertices)");
    }
    if (e.name == "face" && e.count > limits.maxFaces) {
      fail(name, what + ", more than the limit of " + std::to_string(limits.maxFaces) +
                     " (LoadLimits::maxFaces)");
    }
    const std::uint64_t each = minBytes(e, h.format);
    if (e.count > available / each) {
      fail(name, what + ", which needs at least " + std::to_string(each) + " bytes each; " +
                     std::to_string(available) + " bytes are left in the file");
    }
    available -= e.count * each;
  }
}

}  // namespace

bool looksLikePly(const char* data, std::size_t size) {
  return size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r');
}

PolygonMesh readPly(const char* data, std::size_t size, const std::string& name,
                    const LoadLimits& limits) {
  const Header h = readHeader(data, size, name);
  checkCounts(h, size, name, limits);
  PolygonMesh out;
  Values values(data, size, h.bytes, h.format);
  for (const Element& e : h.elements) {
    const Roles roles = rolesOf(e);
    const bool vertex = e.name == "vertex", face = e.name == "face";
    if (vertex && (roles.x < 0 || roles.y < 0 || roles.z < 0)) {
      fail(name, "PLY element 'vertex' has no x, y and z properties");
    }
    if (face && roles.indices < 0) fail(name, "PLY element 'face' has no list of vertex indices");
    if (vertex) out.vertices.reserve(static_cast<std::size_t>(e.count));  // checked against the size
    if (face) out.faceSizes.reserve(static_cast<std::size_t>(e.count));
    for (std::uint64_t i = 0; i < e.count; ++i) {
      // Built only for an error: a string per row would cost more than reading the row.
      const auto where = [&] { return "PLY element " + quoted(e.name) + " " + std::to_string(i); };
      Vec3 position = Vec3::Zero();
      for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
        const Property& p = e.properties[static_cast<std::size_t>(k)];
        double v = 0;
        if (!p.list) {
          if (!values.read(p.type, v)) {
            fail(name, where() + ": property " + quoted(p.name) + " is missing or not a number");
          }
          if (vertex && k == roles.x) position.x() = v;
          if (vertex && k == roles.y) position.y() = v;
          if (vertex && k == roles.z) position.z() = v;
          continue;
        }
        if (!values.read(p.countType, v) || !isCount(v, 4294967295.0)) {
          fail(name, where() + ": list " + quoted(p.name) + " has no valid count");
        }
        const auto n = static_cast<std::uint64_t>(v);
        const bool indices = face && k == roles.indices;
        if (indices && n > limits.maxFaceCorners) {
          fail(name, where() + " has " + std::to_string(n) + " corners, more than " +
                         std::to_string(limits.maxFaceCorners) + " (LoadLimits::maxFaceCorners)");
        }
        if (n > values.left()) {
          fail(name, where() + ": list " + quoted(p.name) + " runs past the end of the file");
        }
        for (std::uint64_t j = 0; j < n; ++j) {
          if (!values.read(p.type, v)) {
            fail(name, where() + ": list " + quoted(p.name) + " is cut short");
          }
          if (!indices) continue;
          if (!isCount(v, 4294967294.0)) {
            fail(name, where() + ": vertex index " + std::to_string(v) + " is not an index");
          }
          out.corners.push_back(static_cast<std::uint32_t>(v));
        }
        if (indices) out.faceSizes.push_back(static_cast<std::uint32_t>(n));
      }
      if (vertex) out.vertices.push_back(position);
    }
  }
  return out;
}

}  // namespace adb::io::detail
