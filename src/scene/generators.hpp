#pragma once
// Body generators, as plain geometry: where the discs of a `grid` or a `random` entry go.
// Reading the YAML and giving the discs their other properties happens in discs.cpp.
#include <cstddef>
#include <span>
#include <vector>

#include "discreel/vec2.hpp"
#include "overlap.hpp"
#include "random.hpp"

namespace discreel::scene::detail {

struct GridSpec {
    Vec2 origin;            // metres, centre of the first disc
    int columns = 1;        // along +x
    int rows = 1;           // along +y
    Vec2 spacing;           // metres between neighbouring centres
    double jitter = 0;      // metres, uniform offset in [-jitter, jitter] per axis
};

// Centres in row-major order: k = row * columns + column.
std::vector<Vec2> grid_positions(const GridSpec& spec, Rng& rng);

struct RandomSpec {
    std::size_t count = 0;
    Vec2 region_min, region_max;          // metres; every disc lies wholly inside
    double radius_min = 0, radius_max = 0;  // metres, uniform
    double speed_min = 0, speed_max = 0;    // m/s, uniform, in a uniformly random direction
};

struct PlacedDisc {
    Vec2 position;
    Vec2 velocity;
    double radius = 0;
};

// How many random spots one disc may try before the region counts as full.
inline constexpr int placement_attempts = 1000;

// Places discs one after another, each where it overlaps neither `existing`, nor `walls`, nor
// the discs placed before it. Stops early (fewer than spec.count discs) when a disc finds no
// room.
std::vector<PlacedDisc> place_random(const RandomSpec& spec, const std::vector<Circle>& existing,
                                     Rng& rng, std::span<const Wall> walls = {});

}  // namespace discreel::scene::detail
