// The core's error types, in one place. Each is a std::invalid_argument whose what() names
// what is wrong and where; the layers above add their own (adb::io::MeshFileError,
// adb::scene::SceneError) for files.
#pragma once

#include <stdexcept>

namespace adb {

/// Invalid mesh input. what() names what is wrong and where (for example "triangle 17
/// references vertex 90, but the mesh has 64 vertices").
class MeshError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Invalid build or query settings; the message names the setting and the range.
class SettingsError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A pose with a non-finite entry or a rotation that is not orthonormal.
class PoseError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace adb
