#pragma once
// The render-job layer: a loaded scene played frame by frame, and the jobs every front end
// runs on it (the CLI's commands, the bench, the tests, later the service and segments).
//     job::RenderDef def{.plan = *job::plan_render(scene, request, limits)};
//     Expected<job::RenderSummary> done = job::render(def);
// It owns scene -> world, the frame timeline, the frame descriptions the renderer draws, the
// simulate/render/encode stages and their threads, and the outputs that commit together. It
// never prints or exits: results and errors are values, progress and cancellation callbacks.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "discreel/encode.hpp"
#include "discreel/expected.hpp"
#include "discreel/physics.hpp"
#include "discreel/render.hpp"
#include "discreel/scene.hpp"

namespace discreel::job {

// The error of every job stopped by its caller (should_stop): a cancellation, a deadline.
inline constexpr const char* cancelled_message = "cancelled; nothing was written";

struct FrameRange {
    int first = 0;           // inclusive
    int last = -1;           // inclusive; negative: the clip's last frame
};

struct PlaybackDef {
    // Keep a checkpoint of the whole state (physics, trails, camera) every this many frames
    // as they are first shown, so that show() can go back to any frame by stepping on from the
    // nearest one before it; 0: none, frames go forward only. A checkpoint costs about the
    // world's memory (docs/serve.md, "Studio").
    int checkpoint_every = 0;
    // At most this many are kept: past it every other one is dropped and they are kept half as
    // often (going back then costs up to twice as many frames). 0: none at all, and going back
    // plays from t = 0.
    int max_checkpoints = 1 << 20;
    // And at most as many as fit in this many bytes, each estimated by checkpoint_bytes();
    // 0: no bound but max_checkpoints.
    double max_checkpoint_bytes = 0;
};

// A frame as Playback::play hands it over.
struct ShownFrame {
    int frame = 0;
    double t = 0;                                 // seconds: frame / fps
    const render::FrameScene* view = nullptr;     // the frame's look; null when not drawn
};

// What Playback::play plays.
struct PlayDef {
    int last = -1;                                // inclusive; negative: the clip's last
    // Which frames are drawn (their view built); frames not drawn are still observed, so
    // trails and the follow camera see them. Empty: every frame.
    std::function<bool(int frame)> drawn;
    // false: the physics only, nothing drawn or observed; such a playback draws no frame
    // after it (a caller that never draws: simulate, tests).
    bool look = true;
    // Asked before every physics step; true stops with "cancelled; nothing was written".
    std::function<bool()> should_stop;
    // Asked before every frame; true ends the play there, successfully (the caller has what
    // it needs). Empty: never.
    std::function<bool()> until;
};

// A scene played frame by frame: its physics world on the scene's timeline (frame n shows
// t = n / fps) and what each frame looks like. This is the one road from a scene to frames:
// every render, segment, golden check, soundtrack, bench and the studio show frames through it.
class Playback {
public:
    explicit Playback(const scene::Scene& scene, PlaybackDef def = {});   // keeps `scene`
    ~Playback();
    Playback(Playback&&) noexcept;
    Playback& operator=(Playback&&) noexcept;

    // Shows `frame`: steps the physics to it, showing the look every frame since the last one
    // shown, in order. `drawn`: returns the frame's description for the renderer (valid until
    // the next call); otherwise observes it and returns null. A frame at or before the last
    // one shown goes back to the nearest checkpoint before it (PlaybackDef::checkpoint_every),
    // or to t = 0, and steps on from there; a playback without checkpoint_every goes forward
    // only, and going back is an error. Fails, naming the body and the
    // time, once the state is no longer finite, and with "cancelled; nothing was written" as
    // soon as `should_stop` (asked before every physics step) says so.
    [[nodiscard]] Expected<const render::FrameScene*> show(
        int frame, bool drawn, const std::function<bool()>& should_stop = {});

    // Shows every frame from the next one to def.last and hands each to `each`, in order;
    // the first error (its own or `each`'s) ends it.
    [[nodiscard]] Status play(const PlayDef& def,
                              const std::function<Status(const ShownFrame&)>& each);

    std::span<const physics::BodyState> bodies() const;
    // New contacts (and sensor overlaps) since the last call, in the order they happened;
    // frames shown again after going back report theirs again.
    std::vector<physics::ContactEvent> take_events();
    // What went wrong without stopping the run, since the last call: a body that left the box
    // of walls it started in (once per body, at the first frame that shows it outside).
    std::vector<std::string> take_warnings();
    const physics::World& world() const;
    int frame_count() const;                  // round(duration * fps)
    double time_of_frame(int frame) const;    // seconds
    std::int64_t step_of_frame(int frame) const;   // the physics step whose state it shows
    int next_frame() const;                   // the first frame not shown yet
    std::size_t checkpoints() const;          // how many are kept
    // What one checkpoint holds, estimated: the world's copy (about 4.6 kB a body, walls
    // included) and the look's trails, bytes.
    double checkpoint_bytes() const;
    std::int64_t steps_taken() const;         // physics steps, counting those taken again

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

struct Progress {
    int frames_done = 0;     // encoded (render) or simulated (simulate)
    int frames_total = 0;
    double elapsed = 0;      // seconds since the job started
};

struct StageSeconds {        // time each stage spent working, not waiting
    double simulate = 0;
    double render = 0;
    double encode = 0;
};

// Ground truth for datasets, written beside a render (docs/cli.md, "Ground truth").
struct GroundTruthPaths {
    std::optional<std::string> shapes;   // JSON: every body's shape, colour and mass, per set
    std::optional<std::string> camera;   // CSV: each drawn frame's world-to-pixel transform
    std::optional<std::string> masks;    // directory: mask_NNNNN.png, 16-bit body ids, per frame
    std::optional<std::string> boxes;    // CSV: each visible body's pixel box, per drawn frame
};

// What a render draws, resolved: job::plan_render's answer to the `render` command's options or
// a service request (render_plan.hpp), or made by hand (the scene, sink.path, frames).
struct RenderPlan {
    scene::Scene scene;                      // loaded, validated, overrides applied
    encode::OutputDescription output;        // the format the output's name picks
    // Where and how: path, encoder settings. Size and fps are the scene's, the palette's key
    // colours and a PNG sequence's first number are filled in by the job.
    encode::SinkDef sink;
    FrameRange frames;                       // frames before `first` are simulated, not drawn
    std::optional<int> gif_fps_from;         // the frame rate a GIF could not show, if lowered
    bool drawn_opaque = false;               // a transparent background the format cannot keep
    // Render only this segment of the frames (from 0), into sink.path (segment_file_name).
    // No trace or events: those are the whole clip's. With `audio`, its sound goes beside it
    // (.wav).
    std::optional<int> segment;
    int segments = 1;                        // how many a whole render of `frames` has
    bool audio = false;                      // a video file gets the soundtrack (docs/sound.md)
};

struct RenderDef {
    RenderPlan plan;                         // what to render and where
    std::optional<std::string> trace;        // CSV path, one row per disc per frame
    std::optional<std::string> events;       // CSV path, one row per new contact
    std::optional<std::string> joints;       // CSV path, one row per joint per frame
    GroundTruthPaths truth;                  // of the drawn frames (shapes: of the clip)
    bool threaded = true;                    // false: one thread, same bytes, slower
    // Video files (.mp4, .mkv, .webm) are encoded in segments of scene.video.segment seconds,
    // each its own closed group of pictures on one encoder thread, and joined by stream copy:
    // `jobs` segments are rendered at once, each with its own playback, renderer and encoder.
    // The bytes never depend on it. 0: one per core the process may run on. GIFs (one palette
    // for the whole clip), streams on standard output and PNG are encoded in one pass.
    int jobs = 0;
    // A renderer of the scene's video size to draw with, kept warm between jobs by a caller
    // that renders many (its context and compiled shaders are reused); nullptr: the job
    // creates its own. Used by one job at a time. The bytes are the same either way.
    render::Renderer* renderer = nullptr;
    std::function<void(const Progress&)> on_progress;   // after each encoded frame
    // Polled before every physics step and every frame; true cancels, nothing written.
    std::function<bool()> should_stop;
    // Playback::take_warnings' messages, each once, from whichever thread simulates.
    std::function<void(const std::string&)> on_warning;
};

struct RenderSummary {
    int frames = 0;                          // frames written
    FrameRange range;                        // which, resolved
    double seconds = 0;                      // wall clock
    StageSeconds busy;
    std::string renderer;                    // GL_RENDERER and GL_VERSION
};

// How many segments of this frame size the machine's available memory (MemAvailable) holds at
// once, each with its own playback, renderer and encoder (about 48 MiB + 48 bytes a pixel);
// at least 1. RenderDef::jobs beyond it is cut to it.
int segments_memory_holds(int width, int height);

// Whether `output` is encoded in segments: a video file, not a stream, GIF or PNG.
bool segmented(const encode::OutputDescription& output);
// How many segments a render of `frames` (resolved) has.
int segment_count(const scene::Video& video, FrameRange frames);
// The frames of segment `index`.
FrameRange segment_frames(const scene::Video& video, FrameRange frames, int index);

// Renders def.plan's frames of its scene into its sink (and the trace and events), all committed
// together at the end, or nothing. Cancelled (should_stop), the error says so.
Expected<RenderSummary> render(const RenderDef& def);

struct SimulateDef {
    scene::Scene scene;
    std::optional<std::string> trace, events, joints;   // CSV paths, as for render
    std::optional<std::string> shapes;                  // JSON path, as for render
    std::function<bool()> should_stop;
    std::function<void(const std::string&)> on_warning;   // as RenderDef's
};

struct SimulateSummary {
    int frames = 0;
    std::int64_t steps = 0;                  // physics steps taken
    double t = 0;                            // seconds of simulated time at the end
    int substeps = 1;                        // per step
    int iterations = 1;                      // velocity iterations per substep
    bool manifold_solver = false;            // bodies of other shapes: the manifold solver
    std::size_t contacts = 0;                // new contacts over the run
    physics::WorldStats deepest;             // at the frame with the deepest overlap
    double energy_start = 0, energy_end = 0; // joules
    double seconds = 0;                      // wall clock
};

// The physics of the whole clip without drawing, writing the trace and events if asked.
Expected<SimulateSummary> simulate(const SimulateDef& def);

}  // namespace discreel::job
