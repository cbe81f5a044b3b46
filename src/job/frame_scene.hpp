#pragma once
// Turns the scene's look (colours, walls, camera, style) plus the current physics state into
// the plain frame description the renderer draws. Trails and the follow camera need the past:
// the builder remembers what it was shown, frame by frame.
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "discreel/physics.hpp"
#include "discreel/render.hpp"
#include "debug_draw.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

// The scene's camera, or, when it gives none, the bounding box of its walls and its bodies at
// t = 0 (and of each respawned set where it appears) with a 5 % margin on every side, widened
// to the frame's aspect ratio.
render::Camera fit_camera(const scene::Scene& scene);

// Trails keep at most this many points over all bodies (12 bytes each): with very many
// bodies the trails get shorter rather than the memory larger.
inline constexpr std::size_t max_trail_points = 4'000'000;

class FrameSceneBuilder {
public:
    explicit FrameSceneBuilder(const scene::Scene& scene);
    // The bytes its trails hold (the ring is allocated whole at the start), which a copy of
    // it (a checkpoint) holds too.
    std::size_t trail_bytes() const { return trail_points_.capacity() * sizeof(Point); }

    // Frames must be shown in order, each once, starting at 0; a frame that is not drawn is
    // still observed, so that trails and the follow camera see it. Frame n is at t = n / fps.
    void observe(int frame, std::span<const physics::BodyState> discs);

    // observe() and the frame description of that state; `last_contacts`: per body, the time
    // of its latest contact (seconds, -infinity for none; may be short), for the arrows shown
    // after contacts. The returned reference stays valid until the next call.
    const render::FrameScene& build(int frame, std::span<const physics::BodyState> discs,
                                    std::span<const double> last_contacts = {});

    // Whether the scene draws style.debug, and what it shows of the physics at the next build.
    bool wants_debug() const { return scene_.style.debug.any(); }
    void debug_state(DebugState state) { debug_ = std::move(state); }

    // The world has carried out the first `applied` of the scene's respawns: later frames
    // draw the new bodies' shapes and colours.
    void respawned(std::size_t applied);

private:
    // Where body i is drawn: frame_.bodies or frame_.polygons, at `slot`.
    struct Slot {
        bool polygon = false;
        std::size_t slot = 0;
    };
    void set_look(std::size_t body, const scene::Body& d);
    // The camera of a camera move (scene::Camera::keys) at time `now`, seconds.
    render::Camera keyed_camera(double now, std::span<const physics::BodyState> bodies) const;
    // style.flash: each body's fill brightened after its contacts (its own colour otherwise).
    void flash(int frame, std::span<const double> last_contacts);
    void add_trails();
    void add_arrows(int frame, std::span<const physics::BodyState> discs,
                    std::span<const double> last_contacts);
    void add_clock(int frame);
    // overlays and bodies' labels, their readouts filled in for this frame.
    void add_text(int frame, std::span<const physics::BodyState> discs);
    std::string filled(const std::vector<scene::TextPart>& text, int frame,
                       std::span<const physics::BodyState> discs) const;
    void add_joints(std::span<const physics::BodyState> discs);
    void add_zigzag(Vec2 a, Vec2 b, float half, const render::Rgba& color);
    // style.debug: sleeping bodies greyed, and the debug lines (debug_draw.hpp).
    void add_debug();

    DebugState debug_;

    // Each joint's anchors (and a slider's axis) in its bodies' frames at t = 0, as physics
    // fixes them; an end without a body keeps its world point.
    struct JointEnds {
        Vec2 a, b, axis;
    };
    std::vector<JointEnds> joint_ends_;
    const scene::Scene& scene_;
    render::FrameScene frame_;
    std::vector<Slot> slots_;            // per body, in the scene's numbering
    // Half a trail's width across its motion, metres, at the body's `angle` (radians) for a
    // motion along `direction` (unit): a disc's radius, a shape's outline's half extent.
    float trail_half_width(std::size_t body, float angle, float dx, float dy) const;
    // Per body: its outline's vertices in its frame (none for a disc) and rounding, metres.
    std::vector<std::vector<Vec2>> outline_;
    std::vector<float> rounding_;
    std::vector<float> radius_;           // per body: a disc's radius, metres
    std::vector<render::Rgba> fill_;     // per body
    std::size_t respawns_applied_ = 0;
    std::vector<double> born_;            // per body: when a respawn put it in (s), or -inf
    std::size_t disc_count_ = 0, polygon_count_ = 0;
    render::Camera fitted_camera_;

    // Follow camera: the smoothed centre, metres, and the frame it was last moved for.
    Vec2 follow_center_;
    int last_frame_ = -1;

    // Trail history: a ring of the last `trail_capacity_` positions of every moving body.
    // Row k holds one frame's positions of all trailed discs.
    struct Point {
        float x, y;
        float half;   // the trail's half width on the segment ending here, metres
    };
    std::vector<std::size_t> trailed_;   // indices of the bodies that get trails, ascending
    std::vector<Point> trail_points_;    // trail_capacity_ rows of trailed_.size() points
    std::size_t trail_capacity_ = 0;     // rows
    std::size_t trail_newest_ = 0;       // row of the latest frame
    std::size_t trail_rows_filled_ = 0;
    std::size_t trail_rows_seen_ = 0;    // rows ever observed
    // Per trailed body: the first row (counted as trail_rows_seen_) of its trail. A respawned
    // body's trail starts with it, not at the body it replaced.
    std::vector<std::size_t> trail_since_;
};

}  // namespace discreel::job
