#pragma once
// A pair of bodies close enough to touch during the current step. Contacts persist between
// steps while the pair stays in the broad phase, carrying warm-start impulses and whether the
// pair touched in the previous step (for ContactEvents).
#include <cstdint>
#include <vector>

#include "body.hpp"

namespace discreel::physics::detail {

struct Contact {
    std::uint32_t a = 0;           // disc index
    std::uint32_t b = 0;           // > a; a disc, or (>= disc count) a wall feature body
    double restitution = 0.0;      // mixed
    double friction = 0.0;         // mixed
    double normal_impulse = 0.0;   // N s, accumulated by the resting stage, warm-starts the next
    double tangent_impulse = 0.0;  // N s
    double step_impulse = 0.0;     // N s, normal impulse summed over the current step
    bool touched_before = false;   // exchanged an impulse during the previous step

    // The gap at the start of the current substep; set for active contacts only.
    double gap = 0.0;              // metres, negative when overlapping
};

}  // namespace discreel::physics::detail
