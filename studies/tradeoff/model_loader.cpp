// Loading one model of the study.
#include "model_loader.h"

#include "adb/support/mesh_generators.h"
#include "adb/io/mesh_file.h"

namespace adb::tradeoff {

Model loadModel(const ModelSource& source, std::size_t index, std::vector<std::string>& warnings) {
  if (source.kind == ModelSource::Kind::Generated) {
    return Model{source.name, index, adb::gen::makeModel(source.name, source.targetTriangles)};
  }
  if (source.kind == ModelSource::Kind::Fixed) {
    return Model{source.name, index, adb::gen::makeFixedModel(source.name)};
  }
  adb::io::LoadReport report;
  TriangleMesh mesh = adb::io::loadMesh(source.path, &report);
  for (const std::string& w : report.warnings) {
    // Name the file, unless the loader's message already starts with it.
    warnings.push_back(w.rfind(source.path, 0) == 0 ? w : source.path + ": " + w);
  }
  return Model{fileStem(source.path), index, std::move(mesh)};
}

}  // namespace adb::tradeoff
