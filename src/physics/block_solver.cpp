#include "block_solver.hpp"

#include <algorithm>
#include <cmath>

namespace discreel::physics::detail {
namespace {

// The effective mass's inverse along direction d at point p: 1 / (what an impulse of 1 N s
// along d changes the relative velocity along d by).
double inverse_mass_along(const BlockBody& a, const BlockBody& b, const BlockPoint& p,
                          const V2& d) {
    const double ra = cross(p.ra, d), rb = cross(p.rb, d);
    return a.inv_mass + b.inv_mass + a.inv_inertia * ra * ra + b.inv_inertia * rb * rb;
}

}  // namespace

void apply_impulse(BlockBody& a, BlockBody& b, const BlockPoint& p, const V2& impulse) {
    a.v -= a.inv_mass * impulse;
    a.omega -= a.inv_inertia * cross(p.ra, impulse);
    b.v += b.inv_mass * impulse;
    b.omega += b.inv_inertia * cross(p.rb, impulse);
}

V2 velocity_at(const BlockBody& body, const V2& r) { return body.v + body.omega * perp(r); }

V2 relative_velocity(const BlockPoint& p, const BlockBody& a, const BlockBody& b) {
    return velocity_at(b, p.rb) - velocity_at(a, p.ra);
}

double normal_velocity(const BlockContact& c, const BlockPoint& p, const BlockBody& a,
                       const BlockBody& b) {
    return relative_velocity(p, a, b).dot(c.normal);
}

void set_restitution_targets(BlockContact& c, const BlockBody& a, const BlockBody& b,
                             double restitution) {
    for (int k = 0; k < c.count; ++k) {
        BlockPoint& p = c.points[k];
        const double vn = normal_velocity(c, p, a, b);
        p.target = vn < 0 ? -restitution * vn : 0;
    }
}

void prepare_block(BlockContact& c, const BlockBody& a, const BlockBody& b) {
    const V2 tangent = -perp(c.normal);
    for (int k = 0; k < c.count; ++k) {
        BlockPoint& p = c.points[k];
        const double k_t = inverse_mass_along(a, b, p, tangent);
        p.tangent_mass = k_t > 0 ? 1 / k_t : 0;
    }
    const V2& n = c.normal;
    const BlockPoint& p1 = c.points[0];
    const BlockPoint& p2 = c.points[c.count > 1 ? 1 : 0];
    const double ra1 = cross(p1.ra, n), rb1 = cross(p1.rb, n);
    const double ra2 = cross(p2.ra, n), rb2 = cross(p2.rb, n);
    const double m = a.inv_mass + b.inv_mass;
    c.k11 = m + a.inv_inertia * ra1 * ra1 + b.inv_inertia * rb1 * rb1;
    c.k22 = m + a.inv_inertia * ra2 * ra2 + b.inv_inertia * rb2 * rb2;
    c.k12 = m + a.inv_inertia * ra1 * ra2 + b.inv_inertia * rb1 * rb2;
}

void solve_block(BlockContact& c, BlockBody& a, BlockBody& b) {
    const V2 tangent = -perp(c.normal);
    for (int k = 0; k < c.count; ++k) {
        BlockPoint& p = c.points[k];
        if (p.tangent_mass <= 0) continue;
        const double vt = (velocity_at(b, p.rb) - velocity_at(a, p.ra)).dot(tangent);
        const double limit = c.friction * p.normal_impulse;
        const double total =
            std::clamp(p.tangent_impulse - vt * p.tangent_mass, -limit, limit);
        const double change = total - p.tangent_impulse;
        p.tangent_impulse = total;
        apply_impulse(a, b, p, change * tangent);
    }

    if (c.count == 1) {
        BlockPoint& p = c.points[0];
        const double k_n = c.k11;
        if (k_n <= 0) return;
        const double vn = normal_velocity(c, p, a, b);
        const double total = std::max(0.0, p.normal_impulse - (vn - p.target) / k_n);
        apply_impulse(a, b, p, (total - p.normal_impulse) * c.normal);
        p.normal_impulse = total;
        return;
    }

    // Two points: K x + b_vec = w with x >= 0, w >= 0 and x_i w_i = 0, where x are the total
    // normal impulses, w the normal velocities beyond their targets, and K the 2x2 matrix of
    // how each point's impulse moves each point's normal velocity.
    BlockPoint& p1 = c.points[0];
    BlockPoint& p2 = c.points[1];
    const V2& n = c.normal;
    const double k11 = c.k11, k22 = c.k22, k12 = c.k12;
    const std::array<double, 2> old{p1.normal_impulse, p2.normal_impulse};
    // The velocities beyond target with the accumulated impulses taken out again.
    const double b1 = normal_velocity(c, p1, a, b) - p1.target - (k11 * old[0] + k12 * old[1]);
    const double b2 = normal_velocity(c, p2, a, b) - p2.target - (k12 * old[0] + k22 * old[1]);
    std::array<double, 2> x{0, 0};
    const double det = k11 * k22 - k12 * k12;
    // Points so close together that K is nearly singular are one point: the last cases.
    const bool regular = det > 1e-12 * k11 * k22;
    bool found = false;
    if (regular) {   // both points pushing
        x = {(-k22 * b1 + k12 * b2) / det, (k12 * b1 - k11 * b2) / det};
        found = x[0] >= 0 && x[1] >= 0;
    }
    if (!found && k11 > 0) {   // only the first: the second separates by itself
        x = {-b1 / k11, 0};
        found = x[0] >= 0 && k12 * x[0] + b2 >= 0;
    }
    if (!found && k22 > 0) {   // only the second
        x = {0, -b2 / k22};
        found = x[1] >= 0 && k12 * x[1] + b1 >= 0;
    }
    if (!found) x = {0, 0};    // neither: both separate (or no solution: apply nothing)
    apply_impulse(a, b, p1, (x[0] - old[0]) * n);
    apply_impulse(a, b, p2, (x[1] - old[1]) * n);
    p1.normal_impulse = x[0];
    p2.normal_impulse = x[1];
}

void collide_poisson(BlockContact& c, BlockBody& a, BlockBody& b, double restitution) {
    prepare_block(c, a, b);
    for (int it = 0; it < 4; ++it) solve_block(c, a, b);
    for (int k = 0; k < c.count; ++k) {
        BlockPoint& p = c.points[k];
        apply_impulse(a, b, p, restitution * p.normal_impulse * c.normal);
        p.normal_impulse *= 1 + restitution;
    }
}

}  // namespace discreel::physics::detail
