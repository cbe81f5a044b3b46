#include "generators.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace discreel::scene::detail {
namespace {

// A uniformly random unit vector without trigonometry: sin/cos differ between libm versions,
// sqrt is exact everywhere. Rejection from the square keeps the direction uniform.
Vec2 random_direction(Rng& rng) {
    for (;;) {
        const double x = rng.uniform(-1, 1), y = rng.uniform(-1, 1);
        const double length_squared = x * x + y * y;
        if (length_squared > 1e-12 && length_squared <= 1) {
            const double length = std::sqrt(length_squared);
            return {x / length, y / length};
        }
    }
}

}  // namespace

std::vector<Vec2> grid_positions(const GridSpec& spec, Rng& rng) {
    std::vector<Vec2> positions;
    positions.reserve(static_cast<std::size_t>(spec.columns) * static_cast<std::size_t>(spec.rows));
    for (int row = 0; row < spec.rows; ++row) {
        for (int column = 0; column < spec.columns; ++column) {
            Vec2 p{spec.origin.x + column * spec.spacing.x, spec.origin.y + row * spec.spacing.y};
            if (spec.jitter > 0) {
                p.x += rng.uniform(-spec.jitter, spec.jitter);
                p.y += rng.uniform(-spec.jitter, spec.jitter);
            }
            positions.push_back(p);
        }
    }
    return positions;
}

std::vector<PlacedDisc> place_random(const RandomSpec& spec, const std::vector<Circle>& existing,
                                     Rng& rng, std::span<const Wall> walls) {
    double largest = spec.radius_max;
    for (const Circle& c : existing) largest = std::max(largest, c.radius);
    CircleGrid grid(2 * largest);
    for (std::size_t i = 0; i < existing.size(); ++i) grid.insert(i, existing[i]);

    // Largest first: big discs find room while the region is empty, small ones then fill the
    // gaps. In draw order, the last big discs often find no room in a crowded region.
    std::vector<double> radii(spec.count);
    for (double& r : radii) r = rng.uniform(spec.radius_min, spec.radius_max);
    std::sort(radii.begin(), radii.end(), std::greater<>());

    std::vector<PlacedDisc> placed;
    placed.reserve(spec.count);
    for (std::size_t k = 0; k < spec.count; ++k) {
        const double radius = radii[k];
        const double x0 = spec.region_min.x + radius, x1 = spec.region_max.x - radius;
        const double y0 = spec.region_min.y + radius, y1 = spec.region_max.y - radius;
        if (x0 > x1 || y0 > y1) break;  // this disc does not fit in the region at all
        bool found = false;
        Circle circle{{}, radius, false};
        for (int attempt = 0; attempt < placement_attempts && !found; ++attempt) {
            circle.centre = {rng.uniform(x0, x1), rng.uniform(y0, y1)};
            found = !grid.first_overlap(circle) &&
                    std::none_of(walls.begin(), walls.end(),
                                 [&](const Wall& wall) { return overlaps_wall(circle, wall); });
        }
        if (!found) break;
        grid.insert(existing.size() + k, circle);
        const double speed = rng.uniform(spec.speed_min, spec.speed_max);
        const Vec2 direction = random_direction(rng);
        // At rest means {0, 0}, not a -0 that would show up in traces.
        const Vec2 velocity = speed == 0 ? Vec2{} : Vec2{speed * direction.x, speed * direction.y};
        placed.push_back({circle.centre, velocity, radius});
    }
    return placed;
}

}  // namespace discreel::scene::detail
