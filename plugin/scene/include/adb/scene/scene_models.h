// The generated models a scene may name (shapes of type "generated"): the core's named models
// (adb::gen::modelNames(): pipes, gears, lock, knot, torus, sphere) and two that scenes need
// with their own parameters, a single "gear" (teeth) and a "box" (half extents).
#pragma once

#include <string>
#include <vector>

#include "adb/core/mesh.h"
#include "adb/scene/scene.h"

namespace adb::scene {

std::vector<std::string> generatedModelNames();

/// The mesh of a generated shape, about shape.triangles triangles, scaled by shape.scale.
/// Throws adb::MeshError for an unknown model (the loader has checked it).
TriangleMesh generatedMesh(const ShapeSpec& shape);

}  // namespace adb::scene
