#pragma once
// A world with bodies of any shape, stepped by the manifold solver (body_solver.hpp): every
// body (plain discs as circles) in one array in the definition's order, then the walls as
// fixed bodies (a segment as a capsule, a box as the four slabs around its inside). World
// hands a definition here when any of its bodies has a shape; disc-only worlds keep the disc
// solver, whose trajectories and speed they were measured with.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "body_solver.hpp"
#include "discreel/physics.hpp"
#include "throws.hpp"

namespace discreel::physics::detail {

class ShapeWorld {
public:
    ShapeWorld(const WorldDef& def, int substeps);

    // The step [t0, t0 + dt], at time t1 = t0 + dt; events are stamped t1.
    void step(double t0, double t1);
    std::span<const BodyState> states() const;
    std::vector<ContactEvent> take_events() { return std::exchange(events_, {}); }
    std::size_t respawns_applied() const { return respawns_applied_; }
    int iterations() const { return solver_.def().iterations; }
    // The first body whose state is not finite, if any.
    std::optional<std::size_t> non_finite() const;
    WorldStats stats(const V2& gravity) const;

    static bool wanted(const WorldDef& def);

private:
    void respawn(double t0);

    V2 gravity_;
    int substeps_ = 1;
    std::size_t body_count_ = 0;
    std::vector<Body> bodies_;              // bodies, then walls
    std::vector<Polygon> shapes_;           // each one's shape
    std::vector<std::size_t> wall_of_;      // per fixed body after body_count_: its wall index
    BodySolver solver_;
    Throws throws_;
    std::vector<RespawnDef> respawns_;
    std::size_t respawns_applied_ = 0;
    std::vector<ContactEvent> events_;
    std::size_t touching_ = 0;              // pairs touching in the last substep
    mutable std::vector<BodyState> states_;
};

}  // namespace discreel::physics::detail
