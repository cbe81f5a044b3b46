#pragma once
// style.debug: the physics testbed's drawing over a frame (docs/scene-format.md, "Debug
// drawing"): contact points, their normals and pushes, bounding boxes and joint anchors, as
// plain lines and dots of render::FrameScene::debug.
#include <vector>

#include "discreel/physics.hpp"
#include "discreel/render.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

// The physics a debug drawing shows, as the world has it at the frame.
struct DebugState {
    std::vector<physics::ContactPoint> contacts;
    std::vector<bool> sleeping;              // per body
    std::vector<physics::JointState> joints;
};

// Replaces frame.debug with what scene.style.debug asks for, drawn over `frame`'s bodies as
// they stand (its discs and polygons: call it once they are placed).
void add_debug_geometry(const scene::Scene& scene, const DebugState& state,
                        render::FrameScene& frame);

// A sleeping body's fill: halfway to grey, so an island asleep reads at a glance.
render::Rgba asleep_fill(const render::Rgba& fill);

}  // namespace discreel::job
