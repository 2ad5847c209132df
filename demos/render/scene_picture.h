// A picture of a scene world: bodies shaded (static grey, kinematic blue, dynamic in the
// palette; overlapping bodies in an overlap scene tinted by their pair's confidence), contact
// points and the pairs a budget cut coloured by confidence, and a caption.
#pragma once

#include <string>

#include "adb/scene/scene_world.h"
#include "render/camera.h"
#include "render/image.h"

namespace adb::demo {

/// The scene's view, or a camera that frames its bodies as they are now (planes left out),
/// seen from the front, right and above.
render::Camera sceneCamera(const scene::SceneWorld& world);

/// The caption of a picture after the world's last step: the backend, its budget, the step,
/// the simulated time and the run's mean step so far (`meanStepMillis`, the recorder's).
std::string sceneCaption(const scene::SceneWorld& world, double meanStepMillis);

render::Image drawScene(const scene::SceneWorld& world, const render::Camera& camera, int width,
                        int height, const std::string& caption);

}  // namespace adb::demo
