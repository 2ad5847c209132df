// Internal: the file's format decides which of assimp's readers reads it, never the data alone.
// assimp picks its reader by the extension. Where several readers claim an extension (glTF 1
// and glTF 2 both claim .gltf and .glb; three claim .xml) it asks each whether the data is its
// own, and when none says yes it tries every reader it has on the data. A damaged glTF then
// went to the Open Game Engine Exchange reader (a few words like "IndexArray" are its
// signature), which spins on it: 20 s, the time limit, for a 72-byte file in the fuzzer's
// corpus (docs/reliability.md). Such data is refused at once instead.
#pragma once

#include <string>

namespace Assimp {
class Importer;
class IOSystem;
}  // namespace Assimp

namespace adb::io::detail {

/// Throws a MeshFileError naming `name` when several of `importer`'s readers claim the
/// extension of `assimpPath` (the path as assimp will open it through `io`) and none of them
/// recognises the data. With one reader or none claiming it, assimp decides as before.
void requireReaderForExtension(const Assimp::Importer& importer, const std::string& assimpPath,
                               Assimp::IOSystem& io, const std::string& name);

}  // namespace adb::io::detail
