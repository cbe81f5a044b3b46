#include "grid_pairs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace discreel::physics::detail {

// The bucket of a cell. Where the occupied cells' bounding rectangle, with a ring of cells
// around it for the neighbours searched, fits in the table, cells are numbered row by row: no
// two cells share a bucket, and a circle's neighbours are its own bucket's successor and the
// buckets one row up, so the search reads the grid nearly in order. Otherwise (circles spread
// far apart) large odd multipliers spread neighbouring cells over the table.
struct GridPairs::CellBuckets {
    std::int64_t min_x = 0, min_y = 0;  // the ring's lower corner
    std::uint64_t row = 0;              // cells per row; 0: hashed
    std::uint64_t mask = 0;             // table size - 1

    CellBuckets(std::int64_t lo_x, std::int64_t lo_y, std::int64_t hi_x, std::int64_t hi_y,
                std::uint64_t table)
        : min_x(lo_x - 1), min_y(lo_y - 1), mask(table - 1) {
        // Spans in doubles: the cells of circles far apart could overflow an integer product.
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

void GridPairs::find(std::span<const GridCircle> circles, std::vector<std::uint64_t>& pairs) {
    hashed_ = false;
    const std::size_t n = circles.size();
    double radius_sum = 0.0;
    for (const GridCircle& c : circles) radius_sum += c.radius;
    // Circles much larger than the typical one are paired by a plain scan.
    const double limit = n > 0 ? 2.0 * radius_sum / static_cast<double>(n) : 0.0;
    oversized_.clear();
    double cell = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        if (circles[i].radius > limit) {
            oversized_.push_back(static_cast<std::uint32_t>(i));
        } else {
            cell = std::max(cell, 2.0 * circles[i].radius);
        }
    }
    if (cell > 0.0) {
        const CellBuckets bucket = bin(circles, limit, cell);
        hashed_ = bucket.row == 0;
        if (bucket.row != 0) {
            meet_in_rows(bucket.row, pairs);
        } else {
            meet_hashed(bucket, pairs);
        }
    }
    meet_oversized(circles, limit, pairs);
}

GridPairs::CellBuckets GridPairs::bin(std::span<const GridCircle> circles, double limit,
                                      double cell) {
    const std::size_t n = circles.size();
    std::size_t table = 1;
    while (table < 2 * n) table <<= 1;
    cell_x_.assign(n, 0);
    cell_y_.assign(n, 0);
    std::int64_t lo_x = INT64_MAX, lo_y = INT64_MAX, hi_x = INT64_MIN, hi_y = INT64_MIN;
    for (std::size_t i = 0; i < n; ++i) {
        if (circles[i].radius > limit) continue;
        cell_x_[i] = static_cast<std::int64_t>(std::floor(circles[i].centre.x() / cell));
        cell_y_[i] = static_cast<std::int64_t>(std::floor(circles[i].centre.y() / cell));
        lo_x = std::min(lo_x, cell_x_[i]);
        lo_y = std::min(lo_y, cell_y_[i]);
        hi_x = std::max(hi_x, cell_x_[i]);
        hi_y = std::max(hi_y, cell_y_[i]);
    }
    const CellBuckets bucket(lo_x, lo_y, hi_x, hi_y, table);
    bucket_start_.assign(table + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (circles[i].radius > limit) continue;
        ++bucket_start_[bucket(cell_x_[i], cell_y_[i]) + 1];
    }
    for (std::size_t k = 0; k < table; ++k) bucket_start_[k + 1] += bucket_start_[k];
    // Each bucket's circles are copied next to each other with what the search needs, so it
    // reads the grid in order instead of circles scattered over memory.
    items_.resize(bucket_start_[table]);
    fill_.assign(bucket_start_.begin(), bucket_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        const GridCircle& c = circles[i];
        if (c.radius > limit) continue;
        items_[fill_[bucket(cell_x_[i], cell_y_[i])]++] =
            Item{c.centre, c.radius, cell_x_[i], cell_y_[i], static_cast<std::uint32_t>(i),
                 c.moves};
    }
    return bucket;
}

// Each pair is met once: a circle meets the circles after it in its own cell and every circle
// of the four neighbouring cells after it (right, and the three above), so half of the
// neighbourhood is searched.
void GridPairs::meet(const Item& item, const Item& other, std::vector<std::uint64_t>& pairs) {
    if (!item.moves && !other.moves) return;
    const double reach = item.radius + other.radius;
    if ((item.x - other.x).squaredNorm() > reach * reach) return;
    pairs.push_back(pair_key(std::min(item.index, other.index), std::max(item.index, other.index)));
}

void GridPairs::meet_in_rows(std::uint64_t row, std::vector<std::uint64_t>& pairs) const {
    // One cell per bucket: the neighbours are whole buckets at fixed offsets.
    const std::uint64_t after[4] = {1, row - 1, row, row + 1};
    const std::uint64_t table = bucket_start_.size() - 1;
    for (std::uint64_t h = 0; h < table; ++h) {
        const std::uint32_t begin = bucket_start_[h], end = bucket_start_[h + 1];
        for (std::uint32_t p = begin; p < end; ++p) {
            const Item& item = items_[p];
            for (std::uint32_t k = p + 1; k < end; ++k) meet(item, items_[k], pairs);
            for (const std::uint64_t offset : after) {
                const std::uint64_t next = h + offset;
                for (std::uint32_t k = bucket_start_[next]; k < bucket_start_[next + 1]; ++k) {
                    meet(item, items_[k], pairs);
                }
            }
        }
    }
}

void GridPairs::meet_hashed(const CellBuckets& bucket, std::vector<std::uint64_t>& pairs) const {
    constexpr std::int64_t forward[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    for (std::size_t p = 0; p < items_.size(); ++p) {
        const Item& item = items_[p];
        for (const auto& [dx, dy] : forward) {
            const std::int64_t cx = item.cell_x + dx, cy = item.cell_y + dy;
            const std::uint64_t h = bucket(cx, cy);
            const std::size_t first = dx == 0 && dy == 0 ? p + 1 : bucket_start_[h];
            for (std::size_t k = first; k < bucket_start_[h + 1]; ++k) {
                const Item& other = items_[k];
                // Other cells sharing the bucket are skipped so no pair comes twice.
                if (other.cell_x != cx || other.cell_y != cy) continue;
                meet(item, other, pairs);
            }
        }
    }
}

void GridPairs::meet_oversized(std::span<const GridCircle> circles, double limit,
                               std::vector<std::uint64_t>& pairs) const {
    for (const std::uint32_t o : oversized_) {
        const GridCircle& big = circles[o];
        for (std::size_t j = 0; j < circles.size(); ++j) {
            const GridCircle& other = circles[j];
            // Two oversized circles meet twice in this loop; the lower index keeps the pair.
            if (j == o || (other.radius > limit && j < o)) continue;
            if (!big.moves && !other.moves) continue;
            const double reach = big.radius + other.radius;
            if ((big.centre - other.centre).squaredNorm() > reach * reach) continue;
            const auto index = static_cast<std::uint32_t>(j);
            pairs.push_back(pair_key(std::min(o, index), std::max(o, index)));
        }
    }
}

}  // namespace discreel::physics::detail
