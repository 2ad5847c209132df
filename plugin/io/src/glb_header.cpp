// checkGlbBytes, checkGlbFile: see glb_header.h. GLB 2.0: a 12-byte header (magic, version,
// total length), then chunks of (length, type, data); GLB 1.0: the header, then (content
// length, content format) and the JSON content.
#include "glb_header.h"

#include <cstring>
#include <fstream>
#include <functional>
#include <string_view>

#include "adb/io/mesh_file.h"
#include "adb/io/message_text.h"

namespace adb::io::detail {
namespace {

constexpr std::uint64_t kHeaderBytes = 12;
constexpr std::uint64_t kChunkHeaderBytes = 8;

// Reads `bytes` bytes at `offset` of the data into `out`; false if the data is shorter. The
// check walks a file's chunk headers without reading the file, and a buffer's in place.
using ReadAt = std::function<bool(std::uint64_t offset, void* out, std::size_t bytes)>;

// The little-endian uint32 at `offset`.
std::uint32_t word(const ReadAt& readAt, std::uint64_t offset, const std::string& name) {
  unsigned char b[4];
  if (!readAt(offset, b, sizeof b)) throw MeshFileError(name + ": GLB header cut short");
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
         std::uint32_t(b[3]) << 24;
}

// The GLB's end is the length its header declares, at most the file's.
std::string pastTheEnd(const std::string& name, const std::string& what, std::uint64_t at,
                       std::uint64_t declared, std::uint64_t glbBytes) {
  return name + ": GLB " + what + " at byte " + std::to_string(at) + " declares " +
         std::to_string(declared) + " bytes, past the end of the GLB (" +
         std::to_string(glbBytes) + " bytes)";
}

void checkGlbLengths(const ReadAt& readAt, std::uint64_t fileBytes, const std::string& name) {
  char magic[4];
  if (fileBytes < sizeof magic || !readAt(0, magic, sizeof magic) ||
      std::memcmp(magic, "glTF", sizeof magic) != 0) {
    return;
  }
  if (fileBytes < kHeaderBytes + kChunkHeaderBytes) {
    throw MeshFileError(name + ": GLB header cut short: " + std::to_string(fileBytes) +
                        " bytes, the header takes 20");
  }
  const std::uint32_t version = word(readAt, 4, name);
  const std::uint64_t length = word(readAt, 8, name);
  if (length > fileBytes) {
    throw MeshFileError(name + ": GLB header declares " + std::to_string(length) +
                        " bytes, but the file has " + std::to_string(fileBytes));
  }
  if (version == 1) {
    const std::uint64_t content = word(readAt, kHeaderBytes, name);
    if (kHeaderBytes + kChunkHeaderBytes + content > length) {
      throw MeshFileError(pastTheEnd(name, "content", kHeaderBytes, content, length));
    }
    return;
  }
  if (version != 2) return;  // assimp's readers name the version they do not read
  // Each step passes at least a chunk's header: the walk ends within length / 8 steps.
  for (std::uint64_t at = kHeaderBytes; at + kChunkHeaderBytes <= length;) {
    const std::uint64_t chunk = word(readAt, at, name);
    char type[4];
    readAt(at + 4, type, sizeof type);
    if (at + kChunkHeaderBytes + chunk > length) {
      // A chunk's type is four ASCII letters ("JSON", "BIN\0"); a damaged one is not text.
      for (char& c : type) c = c >= 0x20 && c < 0x7F ? c : '?';
      const std::string what = "chunk " + quoted(std::string_view(type, sizeof type));
      throw MeshFileError(pastTheEnd(name, what, at, chunk, length));
    }
    at += kChunkHeaderBytes + chunk;
  }
}

}  // namespace

void checkGlbBytes(const char* data, std::size_t size, const std::string& name) {
  checkGlbLengths(
      [&](std::uint64_t offset, void* out, std::size_t count) {
        if (offset > size || count > size - offset) return false;
        std::memcpy(out, data + offset, count);
        return true;
      },
      size, name);
}

void checkGlbFile(const std::string& path, std::uint64_t fileBytes) {
  std::ifstream in(path, std::ios::binary);
  checkGlbLengths(
      [&](std::uint64_t offset, void* out, std::size_t count) {
        in.clear();
        in.seekg(static_cast<std::streamoff>(offset));
        in.read(static_cast<char*>(out), static_cast<std::streamsize>(count));
        return in.gcount() == static_cast<std::streamsize>(count);
      },
      fileBytes, path);
}

}  // namespace adb::io::detail
