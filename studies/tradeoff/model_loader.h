// Turning a --mesh or --model argument (or --against-mesh, --against-model) into a Model: a
// file through adb::io (any format assimp reads), a name through adb::gen::makeModel or
// adb::gen::makeFixedModel. Throws adb::io::MeshFileError or adb::MeshError (the message names
// the file and the problem).
#pragma once

#include <string>
#include <vector>

#include "method.h"
#include "options.h"

namespace adb::tradeoff {

/// `index`: the model's key (Model::index). `warnings` receives the loader's warnings (to be
/// printed).
Model loadModel(const ModelSource& source, std::size_t index, std::vector<std::string>& warnings);

}  // namespace adb::tradeoff
