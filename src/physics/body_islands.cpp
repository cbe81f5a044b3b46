// The islands of the manifold solver's step (body_solver.hpp): which contacts are solved
// directly, as one problem per island of masses far apart, and which by blocks.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "body_solver.hpp"

namespace discreel::physics::detail {

std::uint32_t BodySolver::root_in(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

std::uint32_t BodySolver::root(std::uint32_t i) { return root_in(parent_, i); }

std::optional<std::pair<std::uint32_t, std::uint32_t>> BodySolver::unite(std::uint32_t i,
                                                                       std::uint32_t j) {
    const std::uint32_t ri = root(i), rj = root(j);
    if (ri == rj) return std::nullopt;
    const std::uint32_t low = std::min(ri, rj), high = std::max(ri, rj);
    parent_[high] = low;
    return std::pair{low, high};
}

std::uint32_t BodySolver::island_of(const PairContact& pc, const std::vector<Body>& bodies) {
    return root(bodies[pc.a].inv_mass > 0 ? pc.a : pc.b);
}

void BodySolver::find_islands(const std::vector<Body>& bodies) {
    const std::size_t n = bodies.size();
    direct_.assign(fresh_.size(), 0);
    blocked_.assign(fresh_.size(), 0);
    far_islands_ = false;
    // No island's masses can be further apart than the world's: where every moving body is
    // within direct_mass_ratio of every other (a pile of alike bodies), every island iterates
    // and none needs finding.
    double lightest = 0, heaviest = HUGE_VAL;   // by inverse mass
    for (const Body& b : bodies) {
        if (b.inv_mass <= 0) continue;
        lightest = std::max(lightest, b.inv_mass);
        heaviest = std::min(heaviest, b.inv_mass);
    }
    even_world_ = lightest < def_.direct_mass_ratio * heaviest;
    if (even_world_) {
        islands_.clear();
        island_start_.assign(1, 0);
        blocks_.clear();
        block_start_.assign(1, 0);
        return;
    }
    parent_.resize(n);
    lightest_.resize(n);
    heaviest_.resize(n);
    points_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        parent_[i] = static_cast<std::uint32_t>(i);
        // By inverse mass: what the solver uses (a body's `mass` may be left unset).
        lightest_[i] = heaviest_[i] = bodies[i].inv_mass;
    }
    const auto moves = [&](std::uint32_t i) { return bodies[i].inv_mass > 0; };
    // The lower index roots the merged island, so the grouping depends only on the contacts.
    for (const PairContact& pc : fresh_) {
        if (!moves(pc.a) || !moves(pc.b)) continue;
        if (const auto merged = unite(pc.a, pc.b)) {
            const auto [low, high] = *merged;
            lightest_[low] = std::max(lightest_[low], lightest_[high]);
            heaviest_[low] = std::min(heaviest_[low], heaviest_[high]);
        }
    }
    // Joined bodies are one island, which iterates: a direct solve knows contacts only.
    joints_.for_each_pair([&](std::uint32_t a, std::uint32_t b) {
        if (!moves(a) || !moves(b)) return;
        if (const auto merged = unite(a, b)) {
            const auto [low, high] = *merged;
            lightest_[low] = std::max(lightest_[low], lightest_[high]);
            heaviest_[low] = std::min(heaviest_[low], heaviest_[high]);
        }
    });
    for (const PairContact& pc : fresh_) points_[island_of(pc, bodies)] += pc.contact.count;
    jointed_.assign(n, 0);
    for (std::uint32_t k = 0; k < n; ++k) {
        if (joints_.holds(k)) jointed_[root(k)] = 1;
    }
    group_key_.resize(fresh_.size());
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        const PairContact& pc = fresh_[i];
        const std::uint32_t r = island_of(pc, bodies);
        if (lightest_[r] < def_.direct_mass_ratio * heaviest_[r]) continue;
        far_islands_ = true;
        if (jointed_[r]) continue;
        if (points_[r] <= def_.direct_points) {
            direct_[i] = 1;
            group_key_[i] = r;
            continue;
        }
        // Too large to solve whole: beyond block_mass_ratio the contact joins the block of its
        // lighter body; below it the island iterates like an even one.
        if (lightest_[r] < def_.block_mass_ratio * heaviest_[r]) continue;
        blocked_[i] = 1;
        const bool a_lighter =
            !moves(pc.b) || (moves(pc.a) && bodies[pc.a].inv_mass >= bodies[pc.b].inv_mass);
        group_key_[i] = a_lighter ? pc.a : pc.b;
    }
    group(direct_, islands_, island_start_);
    group(blocked_, blocks_, block_start_);
}

void BodySolver::group(const std::vector<unsigned char>& selected,
                       std::vector<IslandContact>& grouped, std::vector<std::size_t>& starts) {
    // Counting sort of the selected contacts by key (a body index), each group in fresh_'s
    // order; starts first counts per key, then keeps only the groups' bounds.
    const std::size_t n = parent_.size();
    starts.assign(n + 1, 0);
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (selected[i]) ++starts[group_key_[i] + 1];
    }
    for (std::size_t i = 0; i < n; ++i) starts[i + 1] += starts[i];
    grouped.resize(starts[n]);
    std::vector<std::size_t>& fill = island_fill_;
    fill.assign(starts.begin(), starts.end() - 1);
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
        if (!selected[i]) continue;
        PairContact& pc = fresh_[i];
        grouped[fill[group_key_[i]]++] =
            IslandContact{pc.a, pc.b, &pc.contact, static_cast<std::uint32_t>(i)};
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (starts[i + 1] > starts[i]) starts[kept++] = starts[i];
    }
    starts[kept] = grouped.size();
    starts.resize(kept + 1);
}

}  // namespace discreel::physics::detail
