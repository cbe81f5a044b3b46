#include "timeline.hpp"

namespace discreel::job {

std::int64_t Timeline::step_for_frame(int frame) const {
    const std::int64_t numerator = 2 * static_cast<std::int64_t>(frame) * rate + fps;
    return numerator / (2 * static_cast<std::int64_t>(fps));
}

}  // namespace discreel::job
