#include "off_reader.h"

#include <algorithm>
#include <cctype>

#include "adb/io/message_text.h"

namespace adb::io::detail {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw MeshFileError(name + ": " + what);
}

std::string firstWord(const char* data, std::size_t size) {
  std::string word;
  for (std::size_t i = 0; i < size && i < 16 && !std::isspace(static_cast<unsigned char>(data[i])); ++i) {
    word += static_cast<char>(std::toupper(static_cast<unsigned char>(data[i])));
  }
  return word;
}

std::uint64_t count(TextTokens& tokens, const std::string& name, const char* what) {
  std::string token;
  std::uint64_t n = 0;
  if (!tokens.next(token) || !parseIndex(token, n)) {
    if (token == "BINARY") fail(name, "binary OFF is not read (ASCII OFF is)");
    fail(name, std::string("OFF header: no ") + what + " count");
  }
  return n;
}

}  // namespace

bool looksLikeOff(const char* data, std::size_t size) {
  const std::string word = firstWord(data, size);
  // OFF with the optional prefixes: ST (texture), C (colour), N (normal), 4 (4D), n (nD).
  return word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0 &&
         word.find_first_not_of("STCN4OF") == std::string::npos;
}

PolygonMesh readOff(const char* data, std::size_t size, const std::string& name,
                    const LoadLimits& limits) {
  const std::string keyword = firstWord(data, size);
  if (keyword.find('4') != std::string::npos) fail(name, "4D OFF is not a 3D mesh");
  TextTokens tokens(data, size, keyword.size(), true);
  std::string token;
  // nOFF (a lower-case n; NOFF has normals): the dimension comes before the counts.
  if (keyword.size() >= 4 && std::string(data + keyword.size() - 4, 4) == "nOFF") {
    std::uint64_t dimension = 0;
    if (!tokens.next(token) || !parseIndex(token, dimension) || dimension != 3) {
      fail(name, "nOFF of dimension " + quoted(token) + " is not a 3D mesh");
    }
  }
  // "OFF BINARY" says so where the counts are (count() names it).
  const std::uint64_t vertices = count(tokens, name, "vertex");
  const std::uint64_t faces = count(tokens, name, "face");
  count(tokens, name, "edge");
  tokens.skipLine();
  if (vertices > limits.maxVertices) {
    fail(name, "OFF declares " + std::to_string(vertices) + " vertices, more than the limit of " +
                   std::to_string(limits.maxVertices) + " (LoadLimits::maxVertices)");
  }
  if (faces > limits.maxFaces) {
    fail(name, "OFF declares " + std::to_string(faces) + " faces, more than the limit of " +
                   std::to_string(limits.maxFaces) + " (LoadLimits::maxFaces)");
  }
  // A vertex takes at least "0 0 0" and a line end, a face "0" and a line end.
  if (vertices > size / 6 || faces > (size - 6 * vertices) / 2) {
    fail(name, "OFF declares " + std::to_string(vertices) + " vertices and " +
                   std::to_string(faces) + " faces, more than its " + std::to_string(size) +
                   " bytes can hold");
  }
  PolygonMesh out;
  out.vertices.reserve(static_cast<std::size_t>(vertices));
  out.faceSizes.reserve(static_cast<std::size_t>(faces));
  for (std::uint64_t v = 0; v < vertices; ++v) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      double x = 0;
      if (!tokens.next(token) || !parseNumber(token, x)) {
        fail(name, "OFF line " + std::to_string(tokens.line()) + ": vertex " + std::to_string(v) +
                       " has no " + std::string(1, "xyz"[k]) + " coordinate");
      }
      p[k] = x;
    }
    tokens.skipLine();  // colour, normal, texture coordinates
    out.vertices.push_back(p);
  }
  for (std::uint64_t f = 0; f < faces; ++f) {
    std::uint64_t n = 0;
    if (!tokens.next(token) || !parseIndex(token, n)) {
      fail(name, "OFF line " + std::to_string(tokens.line()) + ": face " + std::to_string(f) +
                     " has no corner count");
    }
    if (n > limits.maxFaceCorners) {
      fail(name, "OFF face " + std::to_string(f) + " has " + std::to_string(n) +
                     " corners, more than " + std::to_string(limits.maxFaceCorners) +
                     " (LoadLimits::maxFaceCorners)");
    }
    for (std::uint64_t k = 0; k < n; ++k) {
      std::uint64_t index = 0;
      if (!tokens.next(token) || !parseIndex(token, index) || index >= 4294967295u) {
        fail(name, "OFF line " + std::to_string(tokens.line()) + ": face " + std::to_string(f) +
                       " has " + std::to_string(k) + " of its " + std::to_string(n) + " corners");
      }
      out.corners.push_back(static_cast<std::uint32_t>(index));
    }
    out.faceSizes.push_back(static_cast<std::uint32_t>(n));
    tokens.skipLine();  // a colour
  }
  return out;
}

}  // namespace adb::io::detail
