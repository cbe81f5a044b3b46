// The scalar sections: video, camera, physics and golden.
#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include "disc_ref.hpp"
#include "loader.hpp"

namespace discreel::scene {

int Video::frame_count() const { return static_cast<int>(std::lround(duration * fps)); }

int Video::segment_frames() const {
    return std::max(1, static_cast<int>(std::lround(segment * fps)));
}

std::optional<std::string> check_work(const Scene& scene, const Limits& limits) {
    const double frames = scene.video.duration * scene.video.fps;
    if (!(frames <= max_frames)) {
        return detail::format_number(scene.video.duration) + " seconds at " +
               std::to_string(scene.video.fps) + " fps is more than " +
               detail::format_number(max_frames) + " frames, the most a clip may have";
    }
    // substeps 0 asks the physics for the fewest that keep a substep at or under 1/480 s.
    const int per_step = scene.physics.substeps > 0
                             ? scene.physics.substeps
                             : std::max(1, static_cast<int>(std::ceil(480.0 / scene.physics.rate)));
    const double substeps = scene.video.duration * scene.physics.rate * per_step;
    if (substeps > static_cast<double>(limits.substeps)) {
        return detail::format_number(scene.video.duration) + " seconds at " +
               std::to_string(scene.physics.rate) + " steps per second and " +
               std::to_string(per_step) + (per_step == 1 ? " substep" : " substeps") +
               " per step is " + detail::format_number(std::ceil(substeps)) +
               " physics substeps, more than the limit of " +
               std::to_string(limits.substeps) + " (raise it with --max-substeps)";
    }
    return std::nullopt;
}

namespace detail {
namespace {

constexpr int min_side = 16, max_width = 7680, max_height = 4320;
constexpr int max_fps = 240;
constexpr int max_rate = 100'000;      // physics steps per second
constexpr int max_substeps = 1'000;    // per physics step
constexpr int max_iterations = 100;    // resting-contact iterations per substep
constexpr double max_follow_lag = 10;  // seconds

// One side of video.size; `name` is "width" or "height".
std::optional<int> read_side(const Value& value, std::string_view name, int max,
                             Diagnostics& diagnostics) {
    const auto side = read_integer(value, diagnostics);
    if (!side) return std::nullopt;
    const std::string n(name);
    if (*side < min_side || *side > max) {
        diagnostics.error(value.where, "video.size: " + n + " must be between " +
                                           std::to_string(min_side) + " and " +
                                           std::to_string(max) + ", got " + std::to_string(*side));
        return std::nullopt;
    }
    // Odd sides are for stills and GIFs: a video output refuses them (render_plan.cpp).
    return static_cast<int>(*side);
}

}  // namespace

void read_video(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 5> known{"size", "fps", "duration", "background",
                                                           "segment"};
    auto& d = loader.diagnostics;
    Video& video = loader.scene.video;
    const auto fields = Fields::open(value, known, d);
    if (!fields) {
        loader.frames_known = false;
        return;
    }
    if (const auto size = fields->get("size")) {
        if (const auto items = read_tuple(*size, 2, "[width, height]", d)) {
            if (const auto w = read_side((*items)[0], "width", max_width, d)) video.width = *w;
            if (const auto h = read_side((*items)[1], "height", max_height, d)) video.height = *h;
        }
    }
    if (const auto fps = fields->get("fps")) {
        const auto v = read_integer(*fps, d);
        if (v && check_between(*fps, static_cast<double>(*v), 1, max_fps, d))
            video.fps = static_cast<int>(*v);
        else
            loader.frames_known = false;
    }
    if (const auto duration = fields->get("duration")) {
        const auto v = read_number(*duration, d);
        if (v && (*v <= 0 || *v > loader.limits.duration)) {
            d.error(duration->where, duration->path + ": must be greater than 0 and at most " +
                                         format_number(loader.limits.duration) + " seconds, got " +
                                         format_number(*v) +
                                         (*v > 0 ? " (raise the limit with --max-duration)" : ""));
            loader.frames_known = false;
        } else if (v && *v * video.fps > max_frames) {
            d.error(duration->where, duration->path + ": " + format_number(*v) + " seconds at " +
                                         std::to_string(video.fps) + " fps is more than " +
                                         format_number(max_frames) + " frames, the most a clip may have");
            loader.frames_known = false;
        } else if (v) {
            video.duration = *v;
        } else {
            loader.frames_known = false;
        }
        if (loader.frames_known && video.frame_count() < 1)
            d.error(duration->where, duration->path + ": " + format_number(video.duration) +
                                         " seconds at " + std::to_string(video.fps) +
                                         " fps is less than one frame; a clip needs at least one");
    }
    if (loader.frames_known && video.frame_count() < 1) loader.frames_known = false;
    if (const auto background = fields->get("background"))
        if (const auto c = read_color(*background, d)) video.background = *c;
    if (const auto segment = fields->get("segment")) {
        const auto v = read_number(*segment, d);
        if (v && check_between(*segment, *v, 1e-3, 3600, d)) video.segment = *v;
    }
}

void read_audio(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 2> known{"enabled", "volume"};
    auto& d = loader.diagnostics;
    Audio& audio = loader.scene.audio;
    const auto fields = Fields::open(value, known, d);
    if (!fields) return;
    if (const auto enabled = fields->get("enabled"))
        if (const auto v = read_bool(*enabled, d)) audio.enabled = *v;
    if (const auto volume = fields->get("volume")) {
        const auto v = read_number(*volume, d);
        if (v && check_between(*volume, *v, 0, 1, d)) audio.volume = *v;
    }
}

namespace {

// `keys: [{t, center | follow, height}, ...]`: at least one, at most max_waypoints, times at
// least 0 and increasing strictly; follows are resolved once the bodies are known.
void read_camera_keys(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 4> known{"t", "center", "follow", "height"};
    auto& d = loader.diagnostics;
    const auto items = read_list(value, d);
    if (!items) return;
    if (items->empty() || items->size() > max_waypoints) {
        d.error(value.where, value.path + ": a camera move needs 1 to " +
                                 std::to_string(max_waypoints) + " keys, got " +
                                 std::to_string(items->size()));
        return;
    }
    std::vector<CameraKey>& keys = loader.scene.camera.keys;
    for (const Value& item : *items) {
        const auto fields = Fields::open(item, known, d);
        if (!fields) continue;
        CameraKey key;
        bool ok = true;
        if (const auto t = fields->get("t")) {
            const auto v = read_non_negative(*t, d);
            ok = ok && v;
            key.t = v.value_or(0);
            if (v && !keys.empty() && key.t <= keys.back().t) {
                d.error(t->where, t->path + ": key times must increase strictly, but " +
                                      format_number(key.t) + " comes after " +
                                      format_number(keys.back().t));
                ok = false;
            }
        } else {
            d.error(item.where, item.path + ": missing required key 't'");
            ok = false;
        }
        if (fields->has("center") && fields->has("follow")) {
            d.error(fields->key_location(fields->later_of("center", "follow")),
                    item.path + ": give a key 'center' or 'follow', not both");
            ok = false;
        }
        if (const auto center = fields->get("center")) {
            key.center = read_vec2(*center, "[x, y]", d);
            ok = ok && key.center;
        }
        if (const auto height = fields->get("height")) {
            key.height = read_positive(*height, d);
            ok = ok && key.height;
        }
        if (!ok) continue;
        if (const auto follow = fields->get("follow")) {
            loader.key_follows.emplace_back(keys.size(), *follow);
        }
        keys.push_back(key);
    }
}

}  // namespace

void read_camera(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 6> known{"center", "height",     "follow",
                                                           "follow_lag", "keys", "ease"};
    static constexpr std::array<std::string_view, 2> eases{"linear", "in-out"};
    auto& d = loader.diagnostics;
    const auto fields = Fields::open(value, known, d);
    if (!fields) return;
    if (fields->has("keys")) {
        for (const std::string_view other : {"center", "height", "follow", "follow_lag"}) {
            if (!fields->has(other)) continue;
            d.error(fields->key_location(fields->later_of("keys", other)),
                    value.path + ": give 'keys' (a camera move) or '" + std::string(other) +
                        "', not both; a key has its own center, follow and height");
            break;
        }
        read_camera_keys(loader, *fields->get("keys"));
    }
    if (const auto ease = fields->get("ease")) {
        if (!fields->has("keys")) {
            d.error(fields->key_location("ease"), value.path + ": 'ease' needs 'keys'");
        } else if (const auto i = read_choice(*ease, eases, d)) {
            loader.scene.camera.ease = static_cast<Ease>(*i);
        }
    }
    if (const auto center = fields->get("center"))
        loader.scene.camera.center = read_vec2(*center, "[x, y]", d);
    if (const auto height = fields->get("height"))
        loader.scene.camera.height = read_positive(*height, d);
    loader.camera_follow = fields->get("follow");
    if (const auto lag = fields->get("follow_lag"))
        if (const auto v = read_between(*lag, 0, max_follow_lag, d))
            loader.scene.camera.follow_lag = *v;
}

void resolve_camera_follow(Loader& loader) {
    if (!loader.camera_follow && loader.key_follows.empty()) return;
    const DiscIds ids(loader.scene.bodies);
    if (loader.camera_follow) {
        loader.scene.camera.follow = resolve_disc(loader, *loader.camera_follow, ids);
    }
    for (const auto& [k, value] : loader.key_follows) {
        const auto body = resolve_disc(loader, value, ids);
        if (k < loader.scene.camera.keys.size()) loader.scene.camera.keys[k].follow = body;
    }
}

namespace {

// `mix: {restitution: max, friction: mean}`: each one of the rules, in MixRule's order.
void read_mix(const Value& value, physics::Mixing& mix, Diagnostics& d) {
    static constexpr std::array<std::string_view, 2> known{"restitution", "friction"};
    static constexpr std::array<std::string_view, 4> rules{"max", "min", "mean", "product"};
    const auto fields = Fields::open(value, known, d);
    if (!fields) return;
    if (const auto v = fields->get("restitution"))
        if (const auto i = read_choice(*v, rules, d)) mix.restitution = static_cast<physics::MixRule>(*i);
    if (const auto v = fields->get("friction"))
        if (const auto i = read_choice(*v, rules, d)) mix.friction = static_cast<physics::MixRule>(*i);
}

}  // namespace

void read_physics(Loader& loader, const Value& value) {
    static constexpr std::array<std::string_view, 9> known{
        "gravity", "rate",     "substeps", "iterations", "sleep",
        "restitution", "friction", "seed", "mix"};
    auto& d = loader.diagnostics;
    Physics& physics = loader.scene.physics;
    const auto fields = Fields::open(value, known, d);
    if (!fields) return;
    if (const auto gravity = fields->get("gravity"))
        if (const auto g = read_vec2(*gravity, "[x, y]", d)) {
            const double length = std::hypot(g->x, g->y);
            if (length > ranges.max_gravity) {
                d.error(gravity->where, gravity->path + ": gravity of " + format_number(length) +
                                            " m/s^2 is beyond any scene's; it is at most " +
                                            format_number(ranges.max_gravity) + " m/s^2");
            } else {
                physics.gravity = *g;
            }
        }
    if (const auto rate = fields->get("rate")) {
        const auto v = read_integer(*rate, d);
        if (v && check_between(*rate, static_cast<double>(*v), 1, max_rate, d))
            physics.rate = static_cast<int>(*v);
    }
    if (const auto substeps = fields->get("substeps")) {
        const auto v = read_integer(*substeps, d);
        if (v && check_between(*substeps, static_cast<double>(*v), 1, max_substeps, d))
            physics.substeps = static_cast<int>(*v);
    }
    if (const auto iterations = fields->get("iterations")) {
        const auto v = read_integer(*iterations, d);
        if (v && check_between(*iterations, static_cast<double>(*v), 1, max_iterations, d))
            physics.iterations = static_cast<int>(*v);
    }
    if (const auto sleep = fields->get("sleep"))
        if (const auto v = read_bool(*sleep, d)) physics.sleep = *v;
    if (const auto restitution = fields->get("restitution"))
        if (const auto v = read_between(*restitution, 0, 1, d)) physics.restitution = *v;
    if (const auto friction = fields->get("friction"))
        if (const auto v = read_non_negative(*friction, d)) physics.friction = *v;
    if (const auto seed = fields->get("seed"))
        if (const auto v = read_unsigned(*seed, d)) physics.seed = *v;
    if (const auto mix = fields->get("mix")) read_mix(*mix, physics.mix, d);
}

void read_golden(Loader& loader, const std::optional<Value>& value) {
    static constexpr std::array<std::string_view, 4> known{"frames", "tolerance",
                                                           "max_diff_ratio", "max_diff_pixels"};
    auto& d = loader.diagnostics;
    const int frame_count = loader.scene.video.frame_count();
    auto& frames = loader.scene.golden_frames;
    std::optional<Value> listed;
    if (value) {
        const auto fields = Fields::open(*value, known, d);
        if (!fields) return;
        listed = fields->get("frames");
        auto& thresholds = loader.scene.golden_thresholds;
        if (const auto v = fields->get("tolerance")) thresholds.tolerance = read_between(*v, 0, 1, d);
        if (const auto v = fields->get("max_diff_ratio"))
            thresholds.max_diff_ratio = read_between(*v, 0, 1, d);
        if (const auto v = fields->get("max_diff_pixels")) {
            const auto pixels = read_integer(*v, d);
            if (pixels && check_non_negative(*v, static_cast<double>(*pixels), d))
                thresholds.max_diff_pixels = *pixels;
        }
    }
    if (!listed) {
        if (!loader.frames_known) return;
        for (const int frame : {0, frame_count / 2, frame_count - 1})
            if (frames.empty() || frames.back() != frame) frames.push_back(frame);
        return;
    }
    const auto items = read_list(*listed, d);
    if (!items) return;
    if (items->empty()) {
        d.error(listed->where, listed->path +
                                   ": list at least one frame, or leave out 'frames' for the "
                                   "default (first, middle and last)");
        return;
    }
    if (items->size() > max_golden_frames) {
        d.error(listed->where, listed->path + ": too many frames (" +
                                   std::to_string(items->size()) + "); the limit is " +
                                   std::to_string(max_golden_frames));
        return;
    }
    for (const Value& item : *items) {
        const auto frame = read_integer(item, d);
        if (!frame) continue;
        if (!loader.frames_known) {
            if (check_non_negative(item, static_cast<double>(*frame), d))
                frames.push_back(static_cast<int>(*frame));
            continue;
        }
        if (*frame < 0 || *frame >= frame_count) {
            d.error(item.where, item.path + ": frame " + std::to_string(*frame) +
                                    " is outside the clip; it has " + std::to_string(frame_count) +
                                    " frames, numbered 0 to " + std::to_string(frame_count - 1));
            continue;
        }
        frames.push_back(static_cast<int>(*frame));
    }
}

}  // namespace detail
}  // namespace discreel::scene
