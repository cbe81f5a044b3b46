#pragma once
// State shared by the section readers while one scene file is loaded. Each section reads its
// part of the YAML into Scene and reports problems; load.cpp calls them in dependency order
// (physics before discs: discs take their defaults from it; discs before throws).
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "diagnostics.hpp"
#include "discreel/scene.hpp"
#include "yaml_values.hpp"

namespace discreel::scene::detail {

// Where a disc came from, so that later checks (ids, overlaps, throws) can point at it.
struct BodySource {
    Location entry;          // its item in `discs:` (the generator's item for generated discs)
    std::string where;       // "discs[4]"
    Location id_where;       // its `id:` value, or `entry` when the id was not written
    std::string id_path;     // "discs[4].id", or `where` when the id was not written
    Location velocity_where; // its `velocity:` value (a random entry's `speed:`), or `entry`
    std::string velocity_path;  // "discs[4].velocity", or `where` when none was written
    bool usable = true;      // position and radius read fine: takes part in overlap checks
};

// Where a throw's speeds were written, for the speed check once all throws are read.
struct ThrowSource {
    Location velocity_where;   // `velocity` of a flick, `release` of a grab, or the item
    std::string velocity_path; // "throws[0].velocity"
    Location path_where;       // `path` of a grab
    std::string path_path;     // "throws[0].path"
};

struct Loader {
    Diagnostics& diagnostics;
    Scene& scene;
    std::vector<BodySource> sources;  // parallel to scene.bodies
    bool discs_complete = true;       // every entry expanded, so indices and ids are final
    bool disc_limit_reached = false;  // limits.bodies reported: later entries are not read
    bool frames_known = true;         // fps and duration read fine, so frame_count() is right
    std::optional<Value> camera_follow;  // read with the camera, resolved once discs are known
    std::vector<ThrowSource> throw_sources;  // parallel to scene.throws, filled by read_throws
    Limits limits;
    std::optional<double> clip_duration;   // seconds, when the caller overrides video.duration
    // Category names (`category`, `collides`) and their bits, in the order first named after
    // "default" (1) and "walls" (2).
    std::map<std::string, std::uint32_t> category_bits;
    std::vector<std::pair<std::size_t, Value>> key_follows;   // camera.keys[k].follow, resolved
                                                              // with camera_follow
    // Bodies' `label` (and `label_turns`), read once all bodies are.
    struct Label {
        std::size_t body = 0;
        std::optional<Value> text, turns;
        Location entry;
        std::string where;
    };
    std::vector<Label> labels;
};

void read_video(Loader& loader, const Value& value);
void read_audio(Loader& loader, const Value& value);
void read_camera(Loader& loader, const Value& value);
void resolve_camera_follow(Loader& loader);
void read_style(Loader& loader, const Value& value);
void read_physics(Loader& loader, const Value& value);
void read_walls(Loader& loader, const Value& value);
void read_discs(Loader& loader, const Value& value);
void read_bodies(Loader& loader, const Value& value);   // after read_discs: one numbering
void check_discs(Loader& loader);   // ids, overlaps at t = 0
void read_throws(Loader& loader, const Value& value);
void read_joints(Loader& loader, const Value& value);   // after the bodies, before check_discs
void read_golden(Loader& loader, const std::optional<Value>& value);
void check_ranges(Loader& loader);     // masses, speeds and spins no scene needs (refused)
// Four significant digits, an exponent as people write it: 1e-9, 3.142e13, 5000 (bounds.cpp).
std::string format_bound(double value);

// A list of timed points (timed_points.cpp): a grab's waypoints, a kinematic path's poses.
struct TimedPointsForm {
    std::size_t width = 3;          // numbers in each, the time first
    std::string_view shape;         // "[t, x, y]"
    std::string_view noun;          // "waypoint"
    std::string_view owner;         // "a grab": what needs them, in messages
    std::size_t least = 1;          // the fewest there may be
};
struct TimedPoint {
    Value item;                     // where it was written
    std::array<double, 4> numbers{};   // the first `width` of them
};
// The points of `value`, at least form.least and at most max_waypoints, each a tuple of
// form.width numbers, the times at least 0 and increasing strictly; nothing if any is wrong
// (each mistake reported at its place).
std::optional<std::vector<TimedPoint>> read_timed_points(const Value& value,
                                                         const TimedPointsForm& form,
                                                         Diagnostics& d);
void check_envelope(Loader& loader);   // mass ratios and speeds the solver is known to handle
// overlays.cpp: after the bodies (readouts name them).
void read_overlays(Loader& loader, const Value& value);
void read_labels(Loader& loader);

}  // namespace discreel::scene::detail
