#pragma once
// A pair of bodies that touched during a step: what both solvers report, and World turns into
// contact events.
#include <cstdint>

namespace discreel::physics::detail {

struct PairTouch {
    std::uint32_t a = 0, b = 0;    // body indices, a < b
    double impulse = 0;            // N s, the total normal impulse of its points
    bool began = false;            // it did not touch the step before
    // A contact; or a sensor's overlap that began or ended in the step (impulse 0).
    enum class Kind : std::uint8_t { contact, begin, end };
    Kind kind = Kind::contact;
};

}  // namespace discreel::physics::detail
