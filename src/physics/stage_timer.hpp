#pragma once
// Times one stage of a step into a field of World's StepProfile, when profiling is on
// (WorldDef::profile); with it off, a stage pays one test of a null pointer. The clock is read
// only to be reported: nothing a step computes depends on it.
#include <chrono>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {

class StageTimer {
public:
    StageTimer(StepProfile* profile, double StepProfile::*stage)
        : slot_(profile != nullptr ? &(profile->*stage) : nullptr) {
        if (slot_ != nullptr) start_ = Clock::now();
    }
    ~StageTimer() {
        if (slot_ != nullptr) {
            *slot_ += std::chrono::duration<double>(Clock::now() - start_).count();
        }
    }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    using Clock = std::chrono::steady_clock;
    double* slot_;
    Clock::time_point start_{};
};

}  // namespace discreel::physics::detail
