#include "island.hpp"

#include <cmath>
#include <limits>

namespace discreel::physics::detail {
namespace {

constexpr double unbounded = std::numeric_limits<double>::infinity();
// Friction bounds follow the normal impulses of the pass before; three passes settle them
// for the islands this solve is for (a light body pressed between heavy ones).
constexpr int friction_passes = 3;
// Changes of side per solve: far above the 2 to 3 per row that contact problems take.
int max_pivots(std::size_t rows) { return 4 * static_cast<int>(rows) + 16; }

}  // namespace

void DirectSolver::build(std::span<const IslandContact> island, std::span<const BlockBody> bodies,
                         bool friction) {
    rows_.clear();
    for (const IslandContact& ic : island) {
        const BlockContact& c = *ic.contact;
        const V2 tangent = -perp(c.normal);
        for (int k = 0; k < c.count; ++k) {
            rows_.push_back(row(ic, c.points[k], c.normal));
            if (friction) rows_.push_back(row(ic, c.points[k], tangent));
        }
    }
    fill_matrix(bodies);
}

void DirectSolver::fill_matrix(std::span<const BlockBody> bodies) {
    // A_ij: how an impulse of 1 N s along row j changes row i's relative velocity; only rows
    // that share a body couple. An end on body a moves it by minus the impulse.
    const std::size_t n = rows_.size();
    a_.assign(n * n, 0.0);
    const auto coupling = [&](const Row& r, std::uint32_t body, double sign_r, double arm_r,
                              const Row& s, double sign_s, double arm_s, std::uint32_t other) {
        if (body != other) return 0.0;
        const BlockBody& bb = bodies[body];
        return sign_r * sign_s *
               (bb.inv_mass * r.direction.dot(s.direction) + bb.inv_inertia * arm_r * arm_s);
    };
    for (std::size_t i = 0; i < n; ++i) {
        const Row& r = rows_[i];
        for (std::size_t j = 0; j <= i; ++j) {
            const Row& s = rows_[j];
            const double k = coupling(r, r.a, -1, r.arm_a, s, -1, s.arm_a, s.a) +
                             coupling(r, r.a, -1, r.arm_a, s, 1, s.arm_b, s.b) +
                             coupling(r, r.b, 1, r.arm_b, s, -1, s.arm_a, s.a) +
                             coupling(r, r.b, 1, r.arm_b, s, 1, s.arm_b, s.b);
            a_[i * n + j] = k;
            a_[j * n + i] = k;
        }
    }
}

DirectSolver::Row DirectSolver::row(const IslandContact& ic, const BlockPoint& p,
                                     const V2& direction) {
    return {ic.a, ic.b, direction, cross(p.ra, direction), cross(p.rb, direction)};
}

double DirectSolver::velocity(const Row& r, std::span<const BlockBody> bodies) const {
    const BlockBody& a = bodies[r.a];
    const BlockBody& b = bodies[r.b];
    return r.direction.dot(b.v - a.v) + b.omega * r.arm_b - a.omega * r.arm_a;
}

void DirectSolver::apply(const Row& r, double impulse, std::span<BlockBody> bodies) const {
    BlockBody& a = bodies[r.a];
    BlockBody& b = bodies[r.b];
    a.v -= a.inv_mass * impulse * r.direction;
    a.omega -= a.inv_inertia * impulse * r.arm_a;
    b.v += b.inv_mass * impulse * r.direction;
    b.omega += b.inv_inertia * impulse * r.arm_b;
}

bool DirectSolver::velocities(std::span<const IslandContact> island,
                              std::span<BlockBody> bodies) {
    build(island, bodies, true);
    const std::size_t n = rows_.size();
    b_.resize(n);
    lo_.resize(n);
    hi_.resize(n);
    x_.resize(n);
    std::vector<double>& normal = normal_;   // per point: what bounds its friction
    normal.clear();
    for (const IslandContact& ic : island) {
        for (int k = 0; k < ic.contact->count; ++k) {
            normal.push_back(ic.contact->points[k].normal_impulse);
        }
    }
    std::size_t row = 0;
    for (const IslandContact& ic : island) {
        for (int k = 0; k < ic.contact->count; ++k, row += 2) {
            b_[row] = velocity(rows_[row], bodies) - ic.contact->points[k].target;
            b_[row + 1] = velocity(rows_[row + 1], bodies);
            lo_[row] = 0;
            hi_[row] = unbounded;
        }
    }
    for (int pass = 0; pass < friction_passes; ++pass) {
        row = 0;
        std::size_t point = 0;
        for (const IslandContact& ic : island) {
            for (int k = 0; k < ic.contact->count; ++k, row += 2, ++point) {
                const double limit = ic.contact->friction * normal[point];
                lo_[row + 1] = -limit;
                hi_[row + 1] = limit;
            }
        }
        if (!lcp_.solve(a_, b_, lo_, hi_, x_, max_pivots(n))) return false;
        bool settled = true;
        for (std::size_t p = 0; p < normal.size(); ++p) {
            settled = settled && normal[p] == x_[2 * p];
            normal[p] = x_[2 * p];
        }
        if (settled) break;
    }
    row = 0;
    for (const IslandContact& ic : island) {
        for (int k = 0; k < ic.contact->count; ++k, row += 2) {
            BlockPoint& p = ic.contact->points[k];
            p.normal_impulse = x_[row];
            p.tangent_impulse = x_[row + 1];
            apply(rows_[row], x_[row], bodies);
            apply(rows_[row + 1], x_[row + 1], bodies);
        }
    }
    return true;
}

bool DirectSolver::stop(std::span<const IslandContact> island, std::span<const BlockBody> bodies,
                        std::vector<double>& impulses) {
    rows_.clear();
    point_of_row_.clear();
    std::size_t point = 0;
    for (const IslandContact& ic : island) {
        const BlockContact& c = *ic.contact;
        for (int k = 0; k < c.count; ++k, ++point) {
            const BlockPoint& p = c.points[k];
            if (p.normal_impulse <= 0) continue;
            rows_.push_back(row(ic, p, c.normal));
            point_of_row_.push_back(point);
        }
    }
    impulses.assign(point, 0.0);
    if (rows_.empty()) return true;
    fill_matrix(bodies);
    const std::size_t n = rows_.size();
    b_.resize(n);
    for (std::size_t i = 0; i < n; ++i) b_[i] = velocity(rows_[i], bodies);
    lo_.assign(n, 0.0);
    hi_.assign(n, unbounded);
    x_.resize(n);
    if (!lcp_.solve(a_, b_, lo_, hi_, x_, max_pivots(n))) return false;
    for (std::size_t i = 0; i < n; ++i) impulses[point_of_row_[i]] = x_[i];
    return true;
}

bool DirectSolver::positions(std::span<const IslandContact> island,
                             std::span<const BlockBody> bodies, std::span<const double> separation,
                             std::vector<double>& push) {
    build(island, bodies, false);
    const std::size_t n = rows_.size();
    lo_.assign(n, 0.0);
    hi_.assign(n, unbounded);
    push.resize(n);
    return lcp_.solve(a_, separation, lo_, hi_, push, max_pivots(n));
}

}  // namespace discreel::physics::detail
