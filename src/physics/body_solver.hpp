#pragma once
// One step of rigid bodies of any shape (shape.hpp) against each other: the contact manifolds
// of every pair (manifold.hpp, speculative), warm-started from the last step by feature id,
// solved with the two-point block solve (block_solver.hpp), then positions integrated and
// pushed out of any remaining overlap one point at a time. It is the shapes' solver on its
// own, tested here before the world steps shapes with it; pairs are found by testing every
// pair, so it is meant for the small islands the tests build.
#include <cstdint>
#include <vector>

#include "block_solver.hpp"
#include "manifold.hpp"
#include "shape.hpp"

namespace discreel::physics::detail {

struct RigidBody {
    Polygon shape;
    V2 x = V2::Zero();             // centroid, metres
    double angle = 0;              // radians
    V2 v = V2::Zero();             // m/s
    double omega = 0;              // rad/s
    double inv_mass = 0;           // 1/kg; 0: static
    double inv_inertia = 0;        // 1/(kg m^2)
    double restitution = 0;
    double friction = 0;
};

struct BodySolverDef {
    int iterations = 8;            // velocity iterations per step
    int position_iterations = 3;   // overlap-removal sweeps per step
    double speculative = 0.02;     // metres: points this far apart are already contacts
    double slop = 5e-4;            // metres of overlap left alone (resting contact jitters less)
    double max_correction = 0.02;  // metres pushed out per point and sweep at most
};

class BodySolver {
public:
    explicit BodySolver(BodySolverDef def = {}) : def_(def) {}
    void step(std::vector<RigidBody>& bodies, const V2& gravity, double dt);

private:
    struct PairContact {
        std::uint32_t a = 0, b = 0;    // body indices, a < b
        Manifold manifold;
        BlockContact contact;
    };
    BodySolverDef def_;
    std::vector<PairContact> contacts_;   // the last step's, in (a, b) order
};

}  // namespace discreel::physics::detail
