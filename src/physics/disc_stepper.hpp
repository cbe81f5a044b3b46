#pragma once
// The disc solver as World's stepper (stepper.hpp), for worlds of plain discs: each step runs
// the broad phase once (broad_phase.hpp), then `substeps` substeps of impacts (impacts.cpp),
// resting contact (contact_solver.cpp), direct islands (disc_islands.cpp) and position
// projection (projection.cpp). Its fixed bodies are one per wall feature (geometry.hpp).
#include <cstddef>
#include <memory>
#include <cstdint>
#include <vector>

#include "broad_phase.hpp"
#include "contact.hpp"
#include "contact_solver.hpp"
#include "discreel/physics.hpp"
#include "geometry.hpp"
#include "impacts.hpp"
#include "projection.hpp"
#include "stepper.hpp"

namespace discreel::physics::detail {

class DiscStepper final : public Stepper {
public:
    // Appends the wall features' fixed bodies to `bodies`, which hold the definition's.
    DiscStepper(const WorldDef& def, int substeps, std::vector<Body>& bodies);

    std::unique_ptr<Stepper> clone() const override {
        auto copy = std::make_unique<DiscStepper>(*this);
        copy->set_profile(nullptr);
        return copy;
    }
    int iterations() const override { return iterations_; }
    void step(std::vector<Body>& bodies, double t0, double t1, bool thrown,
              std::vector<PairTouch>& began) override;
    std::optional<std::size_t> end_step(std::vector<Body>& bodies, double dt) override;
    void forget(std::vector<Body>& bodies, std::size_t first, std::size_t last) override;
    void replaced(std::size_t /*i*/, const BodyDef& /*def*/) override {}
    std::size_t wall_of(std::size_t k) const override { return features_[k].wall; }
    void add_stats(const std::vector<Body>& bodies, std::size_t body_count,
                   WorldStats& stats) const override;
    void contact_points(const std::vector<Body>& bodies, std::size_t body_count,
                        std::vector<ContactPoint>& out) const override;

private:
    void substep(std::vector<Body>& bodies, double h, bool last);
    void collect_touches(std::vector<PairTouch>& began);

    V2 gravity_;
    int rate_;                   // steps per second
    int substeps_ = 1;
    int iterations_ = 1;
    std::size_t disc_count_;
    std::vector<Feature> features_;
    std::vector<Contact> contacts_;
    std::uint64_t contacts_version_ = 0;  // counts the broad phase's rebuilds
    // Counts the steps whose throws changed a body, and the respawns.
    std::uint64_t bodies_version_ = 0;
    std::vector<std::uint32_t> active_;
    std::vector<double> reach_;  // metres per body, scratch of substep()
    std::vector<V2> start_;      // disc centres at the start of the substep, scratch
    BroadPhase broad_phase_;
    ImpactResolver impact_resolver_;
    ContactSolver contact_solver_;
    PositionProjector projector_;
    // BroadPhase::keeps() held for every moving disc after the last step (a respawn makes the
    // broad phase build afresh whatever this says).
    bool list_kept_ = false;
    std::size_t contacts_last_step_ = 0;
};

}  // namespace discreel::physics::detail
