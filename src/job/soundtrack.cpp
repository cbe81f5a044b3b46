// A scene's soundtrack alone (a .wav output): the physics played from t = 0 without drawing,
// each new contact heard as a hit (docs/sound.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "build_world.hpp"
#include "discreel/audio.hpp"
#include "discreel/job.hpp"
#include "discreel/shapes.hpp"
#include "soundtrack.hpp"

namespace discreel::job {
namespace {

using Clock = std::chrono::steady_clock;

// What a contact sounds like depends on each body's size (metres) and mass (kg; infinite for
// static bodies and walls).
struct Body {
    double size = 0;
    double mass = 0;
};

std::vector<Body> bodies_of(const physics::WorldDef& world) {
    std::vector<Body> bodies;
    bodies.reserve(world.discs.size());
    for (const physics::DiscDef& disc : world.discs) {
        bodies.push_back({disc.shape ? physics::bounding_radius(*disc.shape) : disc.radius,
                          disc.is_static ? std::numeric_limits<double>::infinity() : disc.mass});
    }
    return bodies;
}

}  // namespace

Expected<RenderSummary> render_soundtrack(const RenderDef& def, FrameRange range) {
    const auto started = Clock::now();
    const scene::Scene& scene = def.scene;
    if (range.first != 0 || range.last != scene.video.frame_count() - 1) {
        return Error{"a .wav is the whole clip's soundtrack; --frames does not apply"};
    }
    auto writer = encode::WavWriter::open(def.output.path, 48000, 2);
    if (!writer) return writer.error();
    const std::vector<Body> bodies = bodies_of(build_world(scene));
    const double aspect = static_cast<double>(scene.video.width) / scene.video.height;
    audio::Synthesizer synth({.sample_rate = 48000,
                              .duration = scene.video.duration,
                              .volume = scene.audio.volume});
    Status written;
    const auto write = [&](std::span<const std::int16_t> samples) {
        written = writer->write(samples);
        return static_cast<bool>(written);
    };
    Playback playback(scene);
    for (int frame = 0; frame <= range.last; ++frame) {
        if (def.should_stop && def.should_stop()) return Error{"cancelled; nothing was written"};
        if (Status advanced = playback.advance_to(frame); !advanced) return advanced.error();
        const render::Camera camera = playback.frame_scene(frame).camera;
        for (const physics::ContactEvent& event : playback.take_events()) {
            const physics::DiscState& a = playback.discs()[event.a];
            const Body& body = bodies[event.a];
            const bool disc = event.other_kind == physics::ContactEvent::Other::disc;
            const Body other = disc ? bodies[event.other] : Body{body.size, std::numeric_limits<double>::infinity()};
            // The lighter body's change of speed: what makes the contact loud, at any scale.
            const double lighter = std::min(body.mass, other.mass);
            const double half_width = camera.height * aspect / 2;
            synth.add({.t = event.t,
                       .speed = std::isfinite(lighter) ? event.impulse / lighter : 0.0,
                       .size = std::min(body.size, other.size),
                       .pan = std::clamp((a.position.x - camera.center_x) / half_width, -1.0, 1.0)});
        }
        if (!synth.render_until(synth.frame_of(playback.time_of_frame(frame)), write)) {
            return written.error();
        }
        if (def.on_progress) {
            def.on_progress({.frames_done = frame + 1,
                             .frames_total = range.last + 1,
                             .elapsed = std::chrono::duration<double>(Clock::now() - started).count()});
        }
    }
    if (!synth.finish(write)) return written.error();
    if (Status sealed = writer->seal(); !sealed) return sealed.error();
    if (def.should_stop && def.should_stop()) return Error{"cancelled; nothing was written"};
    if (Status committed = writer->file().commit(); !committed) return committed.error();
    return RenderSummary{.frames = range.last + 1,
                         .range = range,
                         .seconds = std::chrono::duration<double>(Clock::now() - started).count(),
                         .busy = {},
                         .renderer = {}};
}

}  // namespace discreel::job
