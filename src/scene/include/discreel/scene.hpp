#pragma once
// A scene file, loaded and validated into plain data. Everything here is resolved: defaults
// are filled in, generators are expanded, boxes stay boxes (physics decides how to collide
// with them), throws name discs by index. Nothing here knows about YAML once loading is done.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/physics.hpp"
#include "discreel/shapes.hpp"
#include "discreel/vec2.hpp"

namespace discreel::scene {

// Limits that protect the machine from a scene that asks too much (memory, time, disk). A scene
// beyond one is rejected with a message that states the limit and the command-line option that
// raises it; the CLI fills this from --max-bodies (alias --max-discs), --max-duration,
// --max-scene-bytes, --max-scene-values and --max-substeps. At the defaults any input is judged
// in well under 1 GiB of memory (docs/reliability.md).
struct Limits {
    // Bodies of every kind: discs, shapes, and every set a respawning generator will bring.
    std::size_t bodies = 100'000;
    double duration = 3600;                   // seconds of video
    std::uintmax_t file_bytes = 64u << 20;    // size of the scene file; more is never read
    // YAML values (scalars, lists, mappings, keys included) in the file: each costs about half
    // a kilobyte once parsed, so this bounds the parser's memory. 100 000 discs written out
    // one by one with an id and a colour take 1.1 million.
    std::size_t values = 1'200'000;
    // Physics substeps a run may take: duration x physics.rate x physics.substeps. One hour at
    // the default 480 Hz x 3 takes 5.2 million.
    std::uint64_t substeps = 50'000'000;
};

// Frames a clip may have: its index must fit an int, with room to spare.
inline constexpr double max_frames = 1e9;

// Fixed limits on the shape of a file: beyond them it is malformed rather than ambitious.
inline constexpr std::size_t max_walls = 10'000;
inline constexpr std::size_t max_throws = 10'000;
inline constexpr std::size_t max_joints = 100'000;
inline constexpr std::size_t max_waypoints = 10'000;      // per grab path
inline constexpr std::size_t max_golden_frames = 1'000;
inline constexpr std::size_t max_alias_values = 1'000'000;  // values repeated by YAML aliases

// What no scene needs, refused at its line (docs/scene-format.md, "Ranges"): beyond these the
// numbers say more about a typo than about a demo. Within them, scenes beyond the measured
// envelope of the physics load with a warning instead (physics::envelope).
struct Ranges {
    double min_mass = 1e-9;        // kg, of every moving body, given or from density * area
    double max_mass = 1e12;        // kg
    double max_gravity = 1000;     // m/s^2, the gravity vector's length (about 100 g)
    double max_speed = 1e5;        // m/s, of a body, a throw, a release or a grab's path
    double max_spin = 1000;        // rad/s, a body's angular velocity (about 160 turns a second)
};
inline constexpr Ranges ranges{};

struct Color {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;   // sRGB-encoded, straight alpha
    friend bool operator==(const Color&, const Color&) = default;
};

struct Video {
    int width = 1280;              // pixels, even, 16..7680
    int height = 720;              // pixels, even, 16..4320
    int fps = 60;                  // frames per second, 1..240
    double duration = 8.0;         // seconds of simulated time, (0, 3600]
    Color background{0x0f, 0x14, 0x19, 0xff};
    // Seconds per encoded segment of a video, (0, 3600]: each is its own closed group of
    // pictures, so every way of rendering the clip (any number of workers or machines) gives
    // the same bytes. A property of the output, never of the machine.
    double segment = 2.0;

    // round(duration * fps): frame n shows the state at t = n / fps.
    int frame_count() const;
    // Frames per segment: round(segment * fps), at least 1.
    int segment_frames() const;
};

// The soundtrack made from the contacts (docs/sound.md).
struct Audio {
    bool enabled = false;          // in video files; `--audio` / `--no-audio` override it
    double volume = 0.8;           // 0..1 of full scale: the loudest a sample may be
};

// A keyframe of a camera move: where the view is at time t. A key without `center` or
// `follow` keeps the previous key's aim, without `height` its height (the first key's come from
// the fitted view).
struct CameraKey {
    double t = 0.0;                    // seconds, increasing strictly from key to key
    std::optional<Vec2> center;        // metres
    std::optional<std::size_t> follow; // a body whose centre is the aim (index into bodies)
    std::optional<double> height;      // metres visible vertically
};

enum class Ease { linear, in_out };

struct Camera {
    // Absent: the app frames the walls and bodies at t = 0 with a 5 % margin (fit_camera).
    std::optional<Vec2> center;    // metres
    std::optional<double> height;  // metres visible vertically
    // A body the view tracks (index into Scene::bodies); its centre replaces `center`.
    std::optional<std::size_t> follow;
    double follow_lag = 0.25;      // seconds, time constant of the smoothing, 0..10; 0: rigid
    // A camera move instead of center/height/follow: between two keys the aim and the height
    // go from one to the other, eased; before the first and after the last they hold.
    std::vector<CameraKey> keys;
    Ease ease = Ease::in_out;
};

// A live value in text, written {t}, {energy}, {speed:cue}, {x:cue:.1}: substituted per frame.
struct Readout {
    enum class Kind { time, frame, energy, kinetic, momentum, speed, x, y, angle };
    Kind kind = Kind::time;        // s, frame number, J (kinetic + potential), J, N s, m/s, m, m, rad
    std::size_t body = 0;          // speed, x, y, angle: which body (index into bodies)
    int precision = 2;             // digits after the point (frame: none)
};
// A piece of text: literal characters, or a readout.
struct TextPart {
    std::string literal;
    std::optional<Readout> readout;
};

enum class TextAnchor { top_left, top, top_right, left, center, right, bottom_left, bottom,
                        bottom_right };

// `overlays:` — a title, a caption, a line of readouts: drawn over everything.
struct Overlay {
    std::vector<TextPart> text;
    std::optional<Vec2> at;        // a world position (metres); else placed by `anchor`
    TextAnchor anchor = TextAnchor::top;   // the frame's point it sits at, or its own at `at`
    double size = 0.06;            // the em height: a fraction of the frame's height, or metres
    Color color{0xff, 0xff, 0xff, 0xff};
    double from = 0.0;             // seconds
    std::optional<double> to;      // seconds; default the end
    double fade = 0.0;             // seconds in and out
};

// How frames look beyond the scene's colours. Every overlay is off unless the file asks.
struct VelocityArrows {
    bool enabled = false;
    double scale = 0.25;           // seconds: an arrow is speed * scale metres long, (0, 100]
    Color color{0xff, 0xff, 0xff, 0xff};
    double width = 2.0;            // pixels, line width, 0.5..20
    // Seconds: when set, a body's arrow shows only at its contacts and fades out over this
    // long after each, (0, 10]; unset, every arrow shows always.
    std::optional<double> after_contact;
};

struct Trails {
    bool enabled = false;
    double length = 0.5;           // seconds of history behind each moving disc, (0, 10]
    bool fade = true;              // older parts fade into the background and thin out
    double width = 0.4;            // fraction of the disc's diameter, (0, 1]
};

enum class Corner { top_left, top_right, bottom_left, bottom_right };
enum class ClockFormat { time, frame, both };

struct Clock {
    bool enabled = false;
    Corner corner = Corner::top_left;
    ClockFormat format = ClockFormat::time;
    Color color{0xff, 0xff, 0xff, 0xff};
};

// Joints drawn over the bodies: lines between anchors (springs as zigzags), rings at pins.
struct JointLines {
    bool enabled = true;           // whenever the scene has joints
    Color color{0xe5, 0xe9, 0xf0, 0xff};
    double width = 2.0;            // pixels, line width, 0.5..20
};

// The physics testbed's drawing over the frame (style.debug), for looking into a simulation.
struct DebugDraw {
    bool contacts = false;         // a dot where two bodies, or a body and a wall, touch
    bool normals = false;          // each contact's normal, a fixed 12 pixels long
    bool impulses = false;         // each contact's resting push on its first body: as long as
                                   // the lighter body's radius for its weight, to two radii
    bool boxes = false;            // every body's bounding box
    bool joints = false;           // each joint's two anchors and the force it holds
    bool sleep = false;            // bodies of a sleeping island drawn greyed
    bool any() const { return contacts || normals || impulses || boxes || joints || sleep; }
};

struct Style {
    bool outline = true;           // a darker rim on discs
    bool spin_marker = true;       // a contrasting spoke on every non-static disc, so spin shows
    VelocityArrows velocity_arrows;
    Trails trails;
    Clock clock;
    JointLines joints;
    // Seconds: a body brightens at each of its contacts and fades back over this long, (0, 10];
    // unset, never.
    std::optional<double> flash;
    DebugDraw debug;
};

struct Physics {
    Vec2 gravity{0.0, -9.81};      // m/s^2
    int rate = 480;                // physics steps per second, independent of video fps
    int substeps = 0;              // solver substeps per step; 0: the fewest that keep a
                                   // substep at or under 1/480 s
    int iterations = 0;            // velocity iterations per substep; 0: the solver's own
    bool sleep = true;             // islands of bodies at rest stop until something reaches them
    double restitution = 0.8;      // default coefficient of restitution, 0..1
    double friction = 0.2;         // default Coulomb friction coefficient, >= 0
    std::uint64_t seed = 1;        // for generated discs
    physics::Mixing mix;           // how a contact's restitution and friction come from its two
                                   // sides' (`physics.mix`)
};

struct Wall {
    enum class Shape { box, segment };
    Shape shape = Shape::segment;
    Vec2 a;                        // metres: box corner (min) or segment start
    Vec2 b;                        // metres: box corner (max) or segment end
    double thickness = 0.02;       // metres, full thickness (a capsule of radius thickness/2)
    double restitution = 0.8;      // resolved from physics.restitution when not given
    double friction = 0.2;         // resolved from physics.friction when not given
    Color color{0x88, 0x99, 0xaa, 0xff};
    std::uint32_t category = physics::walls_category;
    std::uint32_t collides = physics::all_categories;
};

// A body: a disc of `radius` from `discs:` (or a `circle:` body), or a body of another shape
// from `bodies:`. Discs and bodies share one list and one numbering (Scene::discs).
struct Body {
    std::string id;                // from the file, or the index / "<generator>.<k>"
    Vec2 position;                 // metres; the centroid for a shape
    Vec2 velocity;                 // m/s
    double angle = 0.0;            // radians
    double angular_velocity = 0.0; // rad/s, counter-clockwise positive
    double radius = 0.0;           // metres, > 0; for a shape its bounding radius
    double mass = 0.0;             // kg; from mass, or density (kg/m^2, default 1) * area
    double inertia = 0.0;          // kg m^2 about the centroid (physics::inertia_of); 0 if static
    std::optional<physics::Shape> shape;   // unset: a disc of `radius`
    double restitution = 0.8;      // resolved from physics.restitution when not given
    double friction = 0.2;         // resolved from physics.friction when not given
    Color color;                   // resolved from a palette by index when not given
    bool is_static = false;        // a fixed peg: collides, never moves
    std::optional<physics::KinematicDef> kinematic;   // moved as told (a platform, a windmill)
    std::vector<TextPart> label;   // drawn at its centre; empty: none
    bool label_turns = false;      // the label turns with the body (else it stays upright)
    // Collision filter bits (a category's bit; the bits of those it meets) and sensing.
    std::uint32_t category = physics::default_category;
    std::uint32_t collides = physics::all_categories;
    bool sensor = false;           // overlaps reported, nothing pushed
    // Where the file gives it (its list item, or its generator's): 1-based; 0 for none.
    int line = 0, column = 0;
};

struct Waypoint {
    double t = 0.0;                // seconds
    Vec2 position;                 // metres
};

struct Throw {
    std::size_t body = 0;          // index into Scene::bodies
    // A flick: at time `at` the disc's velocity becomes `velocity`.
    double at = 0.0;               // seconds; for a grab, the time of its first waypoint
    std::optional<Vec2> velocity;  // m/s; set for a flick
    // A grab: held along `path` from its first to its last waypoint, then released with the
    // path's velocity there, or with `release` when given.
    std::vector<Waypoint> path;    // non-empty for a grab; times strictly increasing
    std::optional<Vec2> release;   // m/s
};

// A generator's bodies [first, first + bodies.size()) replaced by a new set at time `at`.
struct Respawn {
    double at = 0.0;               // seconds
    std::size_t first = 0;         // index into Scene::discs
    std::vector<Body> bodies;
};

struct Scene {
    std::string name;              // file stem ("demo" for configs/demo.yaml)
    int version = 1;
    Video video;
    Audio audio;
    Camera camera;
    Style style;
    Physics physics;
    std::vector<Wall> walls;
    std::vector<Body> bodies;
    std::vector<Throw> throws;
    std::vector<Respawn> respawns;   // in order of `at`
    // Joints between bodies (indices into `bodies`; an end without one is the world's).
    std::vector<physics::JointDef> joints;
    std::vector<std::string> joint_ids;   // per joint: its `id`, or its index
    std::vector<int> golden_frames;  // default: first, middle, last
    // `golden:`'s thresholds for this scene's frames; unset: the command line's.
    struct GoldenThresholds {
        std::optional<double> tolerance;              // perceptual colour distance, 0..1
        std::optional<double> max_diff_ratio;         // of a frame's pixels, 0..1
        std::optional<std::int64_t> max_diff_pixels;  // per frame, >= 0
    } golden_thresholds;
    bool warnings = true;          // `warnings: false`: the scene's warnings are not reported
    std::vector<Overlay> overlays;
};

struct Diagnostic {
    std::string file;
    int line = 0;                  // 1-based
    int column = 0;                // 1-based
    std::string message;
    bool warning = false;          // the scene loads all the same

    std::string to_string() const; // "file:line:column: message", "...: warning: message"
};

struct LoadResult {
    Scene scene;                   // meaningful only when ok()
    std::vector<Diagnostic> diagnostics;  // every problem found, in file order
    // When ok(): what the scene asks beyond the range the physics is measured to hold
    // (docs/physics.md, "Limits"), in file order. It renders; bodies may overlap.
    std::vector<Diagnostic> warnings;

    bool ok() const { return diagnostics.empty(); }
};

// `--set KEY=VALUE`: a value put into the scene before it is read (docs/scene-format.md,
// "Overrides"), checked as the file's own values are; its problems are reported as
// `<label>: message`.
struct Override {
    std::string path;              // dotted: "physics.seed", "video.size", "discs.0.radius"
    std::string value;             // YAML: "3", "[128, 128]", "{x: 1}"
    std::string label;             // how problems name it: "--set physics.seed=3"
};

// Splits "KEY=VALUE"; `option` starts the label ("--set").
Expected<Override> parse_override(std::string_view text, std::string_view option = "--set");

// `display_name` is what diagnostics print as the file (usually the path as the user typed it).
// `clip_duration`: the length the clip will have when the caller sets it instead of
// video.duration (a command-line override, checked by the caller); respawns are drawn up to it,
// as they must exist for the whole clip. video.duration itself stays the file's.
// `overrides` are applied in order, a later one winning.
LoadResult load_scene_text(std::string_view text, std::string_view display_name,
                           const Limits& limits = {},
                           std::optional<double> clip_duration = std::nullopt,
                           std::span<const Override> overrides = {});
LoadResult load_scene_file(const std::filesystem::path& path, const Limits& limits = {},
                           std::optional<double> clip_duration = std::nullopt,
                           std::span<const Override> overrides = {});

// The work a scene asks for against `limits`: more frames than max_frames, or more physics
// substeps than limits.substeps. The problem in words, naming the option that raises the limit;
// nullopt when within. The loader checks this; so must whoever changes the video or physics
// settings after loading (command-line overrides).
std::optional<std::string> check_work(const Scene& scene, const Limits& limits);

}  // namespace discreel::scene
