#pragma once
// The velocity solve of one two-body contact manifold with its points solved together: the
// normal impulses of two points as one 2x2 linear complementarity problem (each impulse >= 0,
// each point's normal velocity >= its target, one of the two zero), solved exactly by trying
// its four cases in a fixed order, as Box2D v2.4's block solver did. Solving both points at
// once is what lets a box land flat without starting to spin and a stack rest without creeping:
// one point at a time, each point's impulse disturbs the other's, and the iteration settles
// only approximately. Friction rows are solved per point after the normal block, bounded by
// the friction coefficient times that point's normal impulse.
#include <array>

#include "body.hpp"

namespace discreel::physics::detail {

struct BlockBody {
    V2 v = V2::Zero();             // m/s
    double omega = 0;              // rad/s
    double inv_mass = 0;           // 1/kg; 0 for static and held bodies
    double inv_inertia = 0;        // 1/(kg m^2)
};

struct BlockPoint {
    V2 ra = V2::Zero(), rb = V2::Zero();   // from each body's centre of mass to the point, m
    double target = 0;             // wanted normal velocity after the solve, m/s (restitution)
    double normal_impulse = 0;     // accumulated, N s (warm start in, result out)
    double tangent_impulse = 0;    // accumulated, N s
    double tangent_mass = 0;       // 1 / (inverse mass along the tangent), kg; 0: immovable
};

struct BlockContact {
    V2 normal = V2::UnitY();       // unit, from A to B
    int count = 0;                 // 1 or 2 points
    std::array<BlockPoint, 2> points{};
    double friction = 0;           // coefficient
    // How each point's normal impulse moves each point's normal velocity (prepare_block):
    // constant over a step, as the offsets and masses are.
    double k11 = 0, k12 = 0, k22 = 0;
};

// A body's kinetic energy at these velocities, J, in a frame moving at `frame` (m/s); an
// immovable body (inverse mass 0) has none.
inline double kinetic_energy(const BlockBody& b, const V2& frame = V2::Zero()) {
    double energy = 0;
    if (b.inv_mass > 0) energy += 0.5 * (b.v - frame).squaredNorm() / b.inv_mass;
    if (b.inv_inertia > 0) energy += 0.5 * b.omega * b.omega / b.inv_inertia;
    return energy;
}

// Applies `impulse` (N s, on B; its opposite on A) at point p to both bodies.
void apply_impulse(BlockBody& a, BlockBody& b, const BlockPoint& p, const V2& impulse);

// The velocity of a body's material point at offset r from its centre of mass, m/s.
V2 velocity_at(const BlockBody& body, const V2& r);
// B's point's velocity relative to A's at point p, m/s.
V2 relative_velocity(const BlockPoint& p, const BlockBody& a, const BlockBody& b);

// The normal velocity of B relative to A at a point, m/s (positive: separating).
double normal_velocity(const BlockContact& c, const BlockPoint& p, const BlockBody& a,
                       const BlockBody& b);

// Sets each point's target from the velocities before the solve: a point closing at vn < 0
// is to leave at -restitution * vn; a separating one only to not close.
void set_restitution_targets(BlockContact& c, const BlockBody& a, const BlockBody& b,
                             double restitution);

// Computes the contact's effective masses from the points' offsets and the bodies' inverse
// masses; once per step, before solve_block.
void prepare_block(BlockContact& c, const BlockBody& a, const BlockBody& b);

// One iteration: friction per point, then the normal block, updating both bodies.
void solve_block(BlockContact& c, BlockBody& a, BlockBody& b);

// A collision by Poisson's rule: the points are stopped together (one pair: the normal block
// is exact, a few passes settle friction against it), then each gets `restitution` times the
// normal impulse that stopped it, which never adds energy (Newton's rule at two points can).
// Each point's normal impulse ends as the whole of its collision's, N s.
void collide_poisson(BlockContact& c, BlockBody& a, BlockBody& b, double restitution);

}  // namespace discreel::physics::detail
