// requireReaderForExtension: see reader_choice.h.
#include "reader_choice.h"

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>

#include <set>
#include <vector>

#include "adb/io/mesh_file.h"
#include "ascii_case.h"

namespace adb::io::detail {

void requireReaderForExtension(const Assimp::Importer& importer, const std::string& assimpPath,
                               Assimp::IOSystem& io, const std::string& name) {
  // The readers that claim the path's ending, as assimp's Importer::ReadFile gathers them
  // (the whole ending is compared: some extensions hold a dot).
  const std::string path = lowered(assimpPath);
  std::vector<Assimp::BaseImporter*> claimants;
  std::string extension;
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    std::set<std::string> extensions;
    reader->GetExtensionList(extensions);
    for (const std::string& e : extensions) {
      const std::string ending = "." + lowered(e);
      if (path.size() >= ending.size() &&
          path.compare(path.size() - ending.size(), ending.size(), ending) == 0) {
        claimants.push_back(reader);
        extension = e;
        break;
      }
    }
  }
  if (claimants.size() < 2) return;
  std::string names;
  for (Assimp::BaseImporter* reader : claimants) {
    // What assimp itself asks next; the data is read in the same (isolated) process.
    if (reader->CanRead(assimpPath, &io, true)) return;
    const aiImporterDesc* info = reader->GetInfo();
    names += (names.empty() ? "" : ", ") + std::string(info != nullptr ? info->mName : "?");
  }
  throw MeshFileError(name + ": not a ." + extension + " file: none of assimp's readers for it (" +
                      names + ") recognises the data");
}

}  // namespace adb::io::detail
