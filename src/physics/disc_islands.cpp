#include "disc_islands.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "substep.hpp"

namespace discreel::physics::detail {
namespace {

// The work a solve's rounding may show, relative to the work's scale (see solve_island): a
// light disc between two a million times heavier meeting elastically shows 6e-11 (its velocity
// is known to about 1e-16 of the heavy ones' momentum over its mass).
constexpr double work_rounding = 1e-8;

// Disc i moves and has a mass: walls, pegs and held discs end islands.
bool moving_disc(const Substep& s, std::uint32_t i) {
    return i < s.disc_count && s.bodies[i].inv_mass > 0.0;
}

std::uint32_t root_of(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

}  // namespace

void DiscIslands::plan(Substep& s, std::span<const std::uint32_t> row_contacts) {
    for (const std::uint32_t index : marked_list_) marked_[index] = 0;
    marked_list_.clear();
    planned_.clear();
    island_end_.clear();
    collided_.clear();
    if (!far_apart_) return;
    const std::size_t discs = s.disc_count;
    const auto moving = [&](std::uint32_t i) { return moving_disc(s, i); };
    parent_.resize(discs);
    std::iota(parent_.begin(), parent_.end(), 0U);
    for (const std::uint32_t index : row_contacts) {
        const Contact& c = s.contacts[index];
        if (moving(c.a) && moving(c.b)) {
            const std::uint32_t ra = root_of(parent_, c.a);
            const std::uint32_t rb = root_of(parent_, c.b);
            parent_[std::max(ra, rb)] = std::min(ra, rb);
        }
    }
    // Rows by island (its root, the least disc index in it), then in row order.
    keyed_.clear();
    for (std::uint32_t k = 0; k < row_contacts.size(); ++k) {
        const Contact& c = s.contacts[row_contacts[k]];
        const std::uint32_t end = moving(c.a) ? c.a : c.b;
        keyed_.push_back(std::uint64_t{root_of(parent_, end)} << 32 | k);
    }
    std::sort(keyed_.begin(), keyed_.end());
    for (std::size_t first = 0; first < keyed_.size();) {
        const std::uint64_t root = keyed_[first] >> 32;
        std::size_t last = first;
        double lightest = std::numeric_limits<double>::infinity(), heaviest = 0;
        bool touching = true;
        for (; last < keyed_.size() && (keyed_[last] >> 32) == root; ++last) {
            const Contact& c = s.contacts[row_contacts[static_cast<std::uint32_t>(keyed_[last])]];
            for (const std::uint32_t i : {c.a, c.b}) {
                if (!moving(i)) continue;
                lightest = std::min(lightest, s.bodies[i].mass);
                heaviest = std::max(heaviest, s.bodies[i].mass);
            }
            const double smaller = c.b < discs
                                       ? std::min(s.bodies[c.a].radius, s.bodies[c.b].radius)
                                       : s.bodies[c.a].radius;
            touching = touching && c.gap <= touching_gap * smaller;
        }
        if (last - first <= largest && touching && heaviest >= ratio * lightest) {
            for (std::size_t j = first; j < last; ++j) {
                planned_.push_back(static_cast<std::uint32_t>(keyed_[j]));
            }
            island_end_.push_back(static_cast<std::uint32_t>(planned_.size()));
        }
        first = last;
    }
    marked_.resize(s.contacts.size(), 0);
    row_contact_.clear();
    for (const std::uint32_t k : planned_) {
        marked_[row_contacts[k]] = 1;
        marked_list_.push_back(row_contacts[k]);
        row_contact_.push_back(row_contacts[k]);
    }
    collide(s);
}

void DiscIslands::collide(Substep& s) {
    const std::size_t discs = s.disc_count;
    // Islands whose collision cannot be solved go back to the impacts stage: they are dropped
    // from the plan (the rows kept are moved forward in place).
    std::size_t first = 0, kept = 0;
    std::size_t islands = 0;
    for (const std::uint32_t last : island_end_) {
        gather(s, first, last, [&](std::size_t j) {
            const Contact& c = s.contacts[row_contact_[j]];
            const Body& a = s.bodies[c.a];
            return c.b < discs
                       ? disc_disc(a.x, a.radius, s.bodies[c.b].x, s.bodies[c.b].radius).normal
                       : disc_feature(a.x, a.radius, *s.feature_of(c)).normal;
        });
        for (std::size_t j = first; j < last; ++j) {
            const BlockContact& bc = contacts_[j - first];
            const IslandContact& ic = island_[j - first];
            const double approach = -normal_velocity(bc, bc.points[0], state_[ic.a], state_[ic.b]);
            targets_[j - first] =
                s.contacts[row_contact_[j]].restitution * std::max(approach, 0.0);
        }
        if (solve_island()) {
            for (std::size_t l = 0; l < bodies_.size(); ++l) {
                if (!moving_disc(s, bodies_[l])) continue;
                Body& b = s.bodies[bodies_[l]];
                if (b.v != state_[l].v || b.omega != state_[l].omega) {
                    collided_.push_back(bodies_[l]);
                }
                b.v = state_[l].v;
                b.omega = state_[l].omega;
            }
            // As the impacts stage's impulses do, they count towards the step's contact events.
            for (std::size_t j = first; j < last; ++j) {
                s.contacts[row_contact_[j]].step_impulse +=
                    contacts_[j - first].points[0].normal_impulse;
            }
            for (std::size_t j = first; j < last; ++j, ++kept) {
                planned_[kept] = planned_[j];
                row_contact_[kept] = row_contact_[j];
            }
            island_end_[islands++] = static_cast<std::uint32_t>(kept);
        } else {
            for (std::size_t j = first; j < last; ++j) marked_[row_contact_[j]] = 0;
        }
        first = last;
    }
    planned_.resize(kept);
    row_contact_.resize(kept);
    island_end_.resize(islands);
}

template <class Normal>
void DiscIslands::gather(const Substep& s, std::size_t first, std::size_t last, Normal normal) {
    bodies_.clear();
    state_.clear();
    island_.clear();
    contacts_.resize(last - first);
    targets_.assign(last - first, 0.0);
    guesses_.assign(last - first, 0.0);
    const auto local = [&](std::uint32_t i) {
        const auto at = std::find(bodies_.begin(), bodies_.end(), i);
        if (at != bodies_.end()) return static_cast<std::uint32_t>(at - bodies_.begin());
        const Body& b = s.bodies[i];
        bodies_.push_back(i);
        state_.push_back(BlockBody{b.v, b.omega, b.inv_mass, b.inv_inertia});
        return static_cast<std::uint32_t>(bodies_.size() - 1);
    };
    for (std::size_t j = first; j < last; ++j) {
        const Contact& c = s.contacts[row_contact_[j]];
        // The block solver's normal runs from a to b, the rows' from b to a.
        const V2 n = normal(j);
        BlockContact& bc = contacts_[j - first];
        bc = BlockContact{};
        bc.normal = -n;
        bc.count = 1;
        bc.friction = c.friction;
        bc.points[0].ra = -s.bodies[c.a].radius * n;
        bc.points[0].rb = s.bodies[c.b].radius * n;
        const std::uint32_t a = local(c.a);
        island_.push_back(IslandContact{a, local(c.b), &bc, static_cast<std::uint32_t>(j)});
    }
}

bool DiscIslands::dissipates() const {
    // The work of the impulses on the island, J: each row's impulse times the mean of its
    // relative velocity before and after (exactly the change of kinetic energy where every
    // body is free, and the same in any frame, so a held disc's push counts as work done).
    double work = 0, scale = 0;
    for (const IslandContact& ic : island_) {
        const BlockContact& c = *ic.contact;
        const BlockPoint& p = c.points[0];
        const V2 before = relative_velocity(p, start_[ic.a], start_[ic.b]);
        const V2 after = relative_velocity(p, state_[ic.a], state_[ic.b]);
        const V2 tangent = -perp(c.normal);
        for (const auto& [impulse, direction] :
             {std::pair{p.normal_impulse, c.normal}, std::pair{p.tangent_impulse, tangent}}) {
            const double u0 = before.dot(direction), u1 = after.dot(direction);
            work += impulse * (u0 + u1) / 2;
            scale += std::abs(impulse) * (std::abs(u0) + std::abs(u1)) / 2;
        }
    }
    return work <= work_rounding * scale;
}

bool DiscIslands::solve_island() {
    start_ = state_;
    // Every row bouncing at e times its own approach (Newton's rule, which the rows ask for)
    // can add energy where several pairs of a crowd hit at once; then the island is solved
    // again without bounces, which only takes energy out.
    for (const bool bounce : {true, false}) {
        for (std::size_t j = 0; j < contacts_.size(); ++j) {
            BlockPoint& p = contacts_[j].points[0];
            p.target = bounce ? targets_[j] : std::min(targets_[j], 0.0);
            p.normal_impulse = guesses_[j];
        }
        state_ = start_;
        if (!direct_.velocities(island_, state_)) return false;
        if (dissipates()) return true;
    }
    return false;
}

void DiscIslands::solve(const Substep& s, std::span<const IslandRow> rows) {
    for (const std::uint32_t i : solved_bodies_) solved_[i].valid = false;
    solved_bodies_.clear();
    solved_islands_.clear();
    if (rows.empty()) return;
    solved_impulse_.assign(rows.size(), 0.0);
    solved_.resize(s.disc_count);
    std::size_t first = 0;
    for (const std::uint32_t last : island_end_) {
        gather(s, first, last, [&](std::size_t j) { return rows[j].normal; });
        // A disc of the island struck in this substep (by a pair that joined the listing
        // after an impact elsewhere sped one of its discs up) makes the rows' targets stale:
        // the iterations' answer stands.
        bool struck = false;
        for (const std::uint32_t i : bodies_) struck = struck || s.bodies[i].strikes != 0;
        for (std::size_t j = first; j < last; ++j) {
            targets_[j - first] = rows[j].target;
            guesses_[j - first] = rows[j].normal_impulse;
        }
        if (!struck && solve_island()) {
            solved_islands_.emplace_back(static_cast<std::uint32_t>(first), last);
            for (std::size_t l = 0; l < bodies_.size(); ++l) {
                const std::uint32_t i = bodies_[l];
                if (!moving_disc(s, i)) continue;
                solved_[i] = Solved{state_[l].v, state_[l].omega, true};
                solved_bodies_.push_back(i);
            }
            for (std::size_t j = first; j < last; ++j) {
                solved_impulse_[j] = contacts_[j - first].points[0].normal_impulse;
            }
        }
        first = last;
    }
}

void DiscIslands::count_impulses(std::vector<Contact>& contacts) const {
    for (const auto& [first, last] : solved_islands_) {
        for (std::size_t j = first; j < last; ++j) {
            Contact& c = contacts[row_contact_[j]];
            c.step_impulse += solved_impulse_[j] - c.normal_impulse;
        }
    }
}

}  // namespace discreel::physics::detail
