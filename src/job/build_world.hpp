#pragma once
// The one place where a loaded scene becomes a physics world definition.
#include "discreel/physics.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

physics::WorldDef build_world(const scene::Scene& scene);

}  // namespace discreel::job
