#pragma once
// The manifold solver as World's stepper (stepper.hpp): bodies of any shape (plain discs as
// circles), each step in substeps of body_solver.hpp's step. Its fixed bodies for the walls are
// a capsule per segment and the four slabs around a box's inside; it keeps every body's shape
// beside it, in the same order.
#include <cstddef>
#include <memory>
#include <vector>

#include "body_solver.hpp"
#include "discreel/physics.hpp"
#include "stepper.hpp"

namespace discreel::physics::detail {

class ShapeStepper final : public Stepper {
public:
    // Appends the walls' fixed bodies to `bodies`, which hold the definition's.
    ShapeStepper(const WorldDef& def, int substeps, std::vector<Body>& bodies);

    std::unique_ptr<Stepper> clone() const override {
        auto copy = std::make_unique<ShapeStepper>(*this);
        copy->set_profile(nullptr);
        return copy;
    }
    int iterations() const override { return solver_.def().iterations; }
    void step(std::vector<Body>& bodies, double t0, double t1, bool thrown,
              std::vector<PairTouch>& began) override;
    std::optional<std::size_t> end_step(std::vector<Body>& bodies, double dt) override;
    void forget(std::vector<Body>& bodies, std::size_t first, std::size_t last) override {
        solver_.forget(bodies, first, last);
    }
    void replaced(std::size_t i, const BodyDef& def) override;
    std::size_t wall_of(std::size_t k) const override { return wall_of_[k]; }
    void add_stats(const std::vector<Body>& bodies, std::size_t body_count,
                   WorldStats& stats) const override;
    void contact_points(const std::vector<Body>& bodies, std::size_t /*body_count*/,
                        std::vector<ContactPoint>& out) const override {
        solver_.contact_points(bodies, out);
    }
    void set_profile(StepProfile* profile) override { solver_.set_profile(profile); }
    void joint_states(const std::vector<Body>& bodies,
                      std::vector<JointState>& out) const override {
        solver_.joints().states(bodies, out);
    }

private:
    V2 gravity_;
    int substeps_ = 1;
    std::size_t body_count_ = 0;
    std::vector<Polygon> shapes_;           // each body's, walls' too
    std::vector<std::size_t> wall_of_;      // per fixed body after body_count_: its wall index
    BodySolver solver_;
    std::size_t touching_ = 0;              // pairs touching in the last substep
};

}  // namespace discreel::physics::detail
