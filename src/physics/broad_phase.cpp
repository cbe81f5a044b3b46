#include "broad_phase.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {
namespace {

// How far a body can travel in one step from its current velocity (see widen_threatened for
// the velocity an impact can give it).
double reach(const Body& b, double dt, double gravity) {
    if (!b.moves()) return 0.0;
    const double fall = b.falls() ? 0.5 * gravity * dt * dt : 0.0;
    return b.v.norm() * dt + fall;
}

// A quarter radius of slack: big enough that a settled pile rarely rebuilds, small enough that
// the pair list stays close to the actual contacts.
double base_margin(const Body& b) { return 0.25 * b.radius; }

std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(a) << 32) | b;
}

// The bucket of a cell. Where the occupied cells' bounding rectangle, with a ring of cells
// around it for the neighbours searched, fits in the table, cells are numbered row by row: no
// two cells share a bucket, and a disc's neighbours are its own bucket's successor and the
// buckets one row up, so the search reads the grid nearly in order. Otherwise (discs spread
// far apart) large odd multipliers spread neighbouring cells over the table.
struct CellBuckets {
    std::int64_t min_x = 0, min_y = 0;  // the ring's lower corner
    std::uint64_t row = 0;              // cells per row; 0: hashed
    std::uint64_t mask = 0;             // table size - 1

    CellBuckets(std::int64_t lo_x, std::int64_t lo_y, std::int64_t hi_x, std::int64_t hi_y,
                std::uint64_t table)
        : min_x(lo_x - 1), min_y(lo_y - 1), mask(table - 1) {
        // Spans in doubles: the cells of discs far apart could overflow an integer product.
        const double width = static_cast<double>(hi_x) - static_cast<double>(lo_x) + 3.0;
        const double height = static_cast<double>(hi_y) - static_cast<double>(lo_y) + 3.0;
        if (width * height <= static_cast<double>(table)) row = static_cast<std::uint64_t>(width);
    }
    std::uint64_t operator()(std::int64_t x, std::int64_t y) const {
        if (row != 0) {
            return static_cast<std::uint64_t>(x - min_x) +
                   static_cast<std::uint64_t>(y - min_y) * row;
        }
        const auto ux = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
        const auto uy = static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full;
        return ((ux ^ (uy >> 7) ^ uy) >> 16) & mask;
    }
};

}  // namespace

bool BroadPhase::update(const std::vector<Body>& bodies, std::size_t disc_count,
                        const std::vector<Feature>& features, double dt, double gravity,
                        std::vector<Contact>& contacts, std::optional<bool> known_valid) {
    if (built_ && (known_valid ? *known_valid : still_valid(bodies, disc_count, dt, gravity))) {
        return false;
    }
    rebuild(bodies, disc_count, features, dt, gravity, contacts);
    return true;
}

void BroadPhase::forget(std::size_t first, std::size_t last, std::vector<Contact>& contacts) {
    built_ = false;
    const bool listed = listed_.size() == contacts.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const Contact& c = contacts[i];
        if ((c.a >= first && c.a < last) || (c.b >= first && c.b < last)) continue;
        if (listed) listed_[kept] = listed_[i];
        contacts[kept++] = c;
    }
    contacts.resize(kept);
    // A list this broad phase did not build keeps no history (rebuild's merge).
    if (listed) {
        listed_.resize(kept);
    } else {
        listed_.clear();
    }
}

bool BroadPhase::still_valid(const std::vector<Body>& bodies, std::size_t disc_count, double dt,
                             double gravity) const {
    for (std::size_t i = 0; i < disc_count; ++i) {
        const Body& b = bodies[i];
        if (b.moves() && !keeps(b, i, dt, gravity)) return false;
    }
    return true;
}

void sort_pair_keys(std::vector<std::uint64_t>& keys, std::size_t body_count,
                    std::vector<std::uint64_t>& scratch, std::vector<std::uint32_t>& count) {
    // LSD radix sort on (a, b) packed into as few bits as the body count needs, 11 bits a pass:
    // two or three passes for up to 2^16 bodies instead of a comparison sort's log2(pairs).
    const int bits = std::min(32, static_cast<int>(std::bit_width(body_count)));
    const int key_bits = 2 * bits;
    constexpr int digit_bits = 11;
    constexpr std::size_t digits = std::size_t{1} << digit_bits;
    for (std::uint64_t& key : keys) key = ((key >> 32) << bits) | (key & 0xffffffffu);
    scratch.resize(keys.size());
    for (int shift = 0; shift < key_bits; shift += digit_bits) {
        count.assign(digits + 1, 0);
        for (const std::uint64_t key : keys) ++count[((key >> shift) & (digits - 1)) + 1];
        for (std::size_t d = 0; d < digits; ++d) count[d + 1] += count[d];
        for (const std::uint64_t key : keys) {
            scratch[count[(key >> shift) & (digits - 1)]++] = key;
        }
        keys.swap(scratch);
    }
    const std::uint64_t low = (std::uint64_t{1} << bits) - 1;
    for (std::uint64_t& key : keys) key = ((key >> bits) << 32) | (key & low);
}

bool BroadPhase::widen_threatened(const std::vector<Body>& bodies, double dt, double gravity) {
    // A disc struck by a faster one leaves at up to its own speed plus 2 m_o / (m_o + m) times
    // the other's (the normal part of its velocity is mixed with the other's, e <= 1): its
    // margin covers a step at that speed, so that what it can reach after the impact is listed
    // for the rest of the step. (Impacts within one step that chain through several discs are
    // caught from the next step on.)
    bool widened = false;
    for (const std::uint64_t key : pairs_) {
        const auto i = static_cast<std::uint32_t>(key >> 32);
        const auto j = static_cast<std::uint32_t>(key & 0xffffffffu);
        for (const auto& [struck, other] : {std::pair{i, j}, std::pair{j, i}}) {
            const Body& s = bodies[struck];
            const Body& o = bodies[other];
            if (s.inv_mass == 0.0) continue;  // fixed or held: no impact moves it
            const double share = o.inv_mass == 0.0 ? 1.0 : s.inv_mass / (s.inv_mass + o.inv_mass);
            const double needed =
                base_margin(s) + reach(s, dt, gravity) + 2.0 * share * o.v.norm() * dt;
            if (needed > margin_[struck]) {
                margin_[struck] = needed;
                widened = true;
            }
        }
    }
    return widened;
}

void BroadPhase::find_disc_pairs(const std::vector<Body>& bodies, std::size_t disc_count) {
    hashed_ = false;
    pairs_.clear();
    double fat_sum = 0.0;
    for (std::size_t i = 0; i < disc_count; ++i) fat_sum += bodies[i].radius + margin_[i];

    // Discs much larger (or faster) than the typical one would force huge cells on everyone;
    // they are paired by a plain scan instead.
    const double fat_limit = disc_count > 0 ? 2.0 * fat_sum / static_cast<double>(disc_count) : 0.0;
    auto fat = [&](std::size_t i) { return bodies[i].radius + margin_[i]; };
    std::vector<std::uint32_t> oversized;
    double cell = 0.0;
    for (std::size_t i = 0; i < disc_count; ++i) {
        if (fat(i) > fat_limit) {
            oversized.push_back(static_cast<std::uint32_t>(i));
        } else {
            cell = std::max(cell, 2.0 * fat(i));
        }
    }
    auto consider = [&](std::size_t i, std::size_t j) {
        if (!bodies[i].moves() && !bodies[j].moves()) return;
        const double reach_sum = fat(i) + fat(j);
        if ((bodies[i].x - bodies[j].x).squaredNorm() > reach_sum * reach_sum) return;
        const auto lo = static_cast<std::uint32_t>(std::min(i, j));
        const auto hi = static_cast<std::uint32_t>(std::max(i, j));
        pairs_.push_back(pair_key(lo, hi));
    };

    if (cell > 0.0) {
        std::size_t table = 1;
        while (table < 2 * disc_count) table <<= 1;
        cell_x_.assign(disc_count, 0);
        cell_y_.assign(disc_count, 0);
        std::int64_t lo_x = INT64_MAX, lo_y = INT64_MAX, hi_x = INT64_MIN, hi_y = INT64_MIN;
        for (std::size_t i = 0; i < disc_count; ++i) {
            if (fat(i) > fat_limit) continue;
            cell_x_[i] = static_cast<std::int64_t>(std::floor(bodies[i].x.x() / cell));
            cell_y_[i] = static_cast<std::int64_t>(std::floor(bodies[i].x.y() / cell));
            lo_x = std::min(lo_x, cell_x_[i]);
            lo_y = std::min(lo_y, cell_y_[i]);
            hi_x = std::max(hi_x, cell_x_[i]);
            hi_y = std::max(hi_y, cell_y_[i]);
        }
        const CellBuckets bucket(lo_x, lo_y, hi_x, hi_y, table);
        hashed_ = bucket.row == 0;
        bucket_start_.assign(table + 1, 0);
        for (std::size_t i = 0; i < disc_count; ++i) {
            if (fat(i) > fat_limit) continue;
            ++bucket_start_[bucket(cell_x_[i], cell_y_[i]) + 1];
        }
        for (std::size_t k = 0; k < table; ++k) bucket_start_[k + 1] += bucket_start_[k];
        // Each bucket's discs are copied next to each other with what the search needs, so it
        // reads the grid in order instead of bodies scattered over memory.
        items_.resize(bucket_start_[table]);
        fill_.assign(bucket_start_.begin(), bucket_start_.end() - 1);
        for (std::size_t i = 0; i < disc_count; ++i) {
            if (fat(i) > fat_limit) continue;
            items_[fill_[bucket(cell_x_[i], cell_y_[i])]++] =
                GridItem{bodies[i].x, fat(i), cell_x_[i], cell_y_[i],
                         static_cast<std::uint32_t>(i), bodies[i].moves()};
        }
        // Each pair is met once: a disc meets the discs after it in its own cell and every disc
        // of the four neighbouring cells after it (right, and the three above), so half of
        // the neighbourhood is searched.
        const auto meet = [&](const GridItem& item, const GridItem& other) {
            if (!item.moves && !other.moves) return;
            const double reach_sum = item.fat + other.fat;
            if ((item.x - other.x).squaredNorm() > reach_sum * reach_sum) return;
            pairs_.push_back(pair_key(std::min(item.body, other.body),
                                      std::max(item.body, other.body)));
        };
        if (bucket.row != 0) {
            // One cell per bucket: the neighbours are whole buckets at fixed offsets.
            const std::uint64_t row = bucket.row;
            const std::uint64_t after[4] = {1, row - 1, row, row + 1};
            for (std::uint64_t h = 0; h < table; ++h) {
                const std::uint32_t begin = bucket_start_[h], end = bucket_start_[h + 1];
                for (std::uint32_t p = begin; p < end; ++p) {
                    const GridItem& item = items_[p];
                    for (std::uint32_t k = p + 1; k < end; ++k) meet(item, items_[k]);
                    for (const std::uint64_t offset : after) {
                        const std::uint64_t n = h + offset;
                        for (std::uint32_t k = bucket_start_[n]; k < bucket_start_[n + 1]; ++k) {
                            meet(item, items_[k]);
                        }
                    }
                }
            }
        } else {
            constexpr std::int64_t forward[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
            for (std::size_t p = 0; p < items_.size(); ++p) {
                const GridItem& item = items_[p];
                for (const auto& [dx, dy] : forward) {
                    const std::int64_t cx = item.cell_x + dx, cy = item.cell_y + dy;
                    const std::uint64_t h = bucket(cx, cy);
                    const std::size_t first = dx == 0 && dy == 0 ? p + 1 : bucket_start_[h];
                    for (std::size_t k = first; k < bucket_start_[h + 1]; ++k) {
                        const GridItem& other = items_[k];
                        // Other cells sharing the bucket are skipped so no pair comes twice.
                        if (other.cell_x != cx || other.cell_y != cy) continue;
                        meet(item, other);
                    }
                }
            }
        }
    }
    for (std::size_t k = 0; k < oversized.size(); ++k) {
        const std::uint32_t o = oversized[k];
        for (std::size_t j = 0; j < disc_count; ++j) {
            const bool other_oversized = fat(j) > fat_limit;
            // Oversized pairs are met twice in this loop; keep the one from the lower index.
            if (j == o || (other_oversized && j < o)) continue;
            consider(o, j);
        }
    }
}

void BroadPhase::rebuild(const std::vector<Body>& bodies, std::size_t disc_count,
                         const std::vector<Feature>& features, double dt, double gravity,
                         std::vector<Contact>& contacts) {
    built_ = true;
    anchor_.resize(disc_count);
    margin_.resize(disc_count);
    for (std::size_t i = 0; i < disc_count; ++i) {
        anchor_[i] = bodies[i].x;
        // Four steps' travel: a falling crowd would otherwise rebuild every few steps, and the
        // substep's own reach test keeps the extra pairs out of the solver stages.
        margin_[i] = base_margin(bodies[i]) + 4.0 * reach(bodies[i], dt, gravity);
    }
    find_disc_pairs(bodies, disc_count);
    if (widen_threatened(bodies, dt, gravity)) find_disc_pairs(bodies, disc_count);

    for (std::size_t i = 0; i < disc_count; ++i) {
        const Body& b = bodies[i];
        if (!b.moves()) continue;
        for (std::size_t f = 0; f < features.size(); ++f) {
            if (!feature_applies(features[f], b.x)) continue;
            if (disc_feature(b.x, b.radius, features[f]).gap > margin_[i]) continue;
            pairs_.push_back(pair_key(static_cast<std::uint32_t>(i),
                                      static_cast<std::uint32_t>(disc_count + f)));
        }
    }
    sort_pair_keys(pairs_, bodies.size(), sorted_, digit_count_);

    // Merge with the previous list (both sorted) so surviving pairs keep their history. Its
    // pairs are kept as keys too (listed_), which the merge compares without loading a contact.
    merged_.clear();
    merged_.reserve(pairs_.size());
    // (A list this broad phase did not build has no history to keep.)
    const std::size_t old_count = listed_.size() == contacts.size() ? listed_.size() : 0;
    std::size_t old = 0;
    for (const std::uint64_t key : pairs_) {
        while (old < old_count && listed_[old] < key) ++old;
        // Built in place: a contact built on the stack and then copied would be read back
        // before its stores complete, which stalls on store forwarding.
        if (old < old_count && listed_[old] == key) {
            merged_.push_back(contacts[old]);
            continue;
        }
        const auto a = static_cast<std::uint32_t>(key >> 32);
        const auto b = static_cast<std::uint32_t>(key & 0xffffffffu);
        Contact& c = merged_.emplace_back();
        c.a = a;
        c.b = b;
        c.restitution = mix_restitution(bodies[a].restitution, bodies[b].restitution);
        c.friction = mix_friction(bodies[a].friction, bodies[b].friction);
    }
    listed_.swap(pairs_);
    contacts.swap(merged_);
}

}  // namespace discreel::physics::detail
