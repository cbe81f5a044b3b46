#pragma once
// Turns the scene's look (colours, walls, camera) plus the current physics state into the plain
// frame description the renderer draws.
#include <span>

#include "discreel/physics.hpp"
#include "discreel/render.hpp"
#include "discreel/scene.hpp"

namespace discreel::app {

// The scene's camera, or, when it gives none, the bounding box of all walls (discs when there
// are no walls) with a 5 % margin on every side, widened to the frame's aspect ratio.
render::Camera fit_camera(const scene::Scene& scene);

class FrameSceneBuilder {
public:
    explicit FrameSceneBuilder(const scene::Scene& scene);

    // The returned reference stays valid until the next call.
    const render::FrameScene& build(std::span<const physics::DiscState> discs);

private:
    const scene::Scene& scene_;
    render::FrameScene frame_;
};

}  // namespace discreel::app
