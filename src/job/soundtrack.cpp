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
    bodies.reserve(world.bodies.size());
    for (const physics::BodyDef& disc : world.bodies) {
        bodies.push_back({disc.shape ? physics::bounding_radius(*disc.shape) : disc.radius,
                          disc.is_static ? std::numeric_limits<double>::infinity() : disc.mass});
    }
    return bodies;
}

}  // namespace

std::size_t sample_of_frame(int frame, int fps) {
    const auto scaled = static_cast<std::int64_t>(frame) * sound_rate;
    return static_cast<std::size_t>((2 * scaled + fps) / (2 * static_cast<std::int64_t>(fps)));
}

Status write_soundtrack(const scene::Scene& scene, FrameRange range, const SampleWriter& out,
                        const std::function<bool()>& should_stop) {
    const std::vector<Body> bodies = bodies_of(build_world(scene));
    const double aspect = static_cast<double>(scene.video.width) / scene.video.height;
    const int frame_count = scene.video.frame_count();
    // As long as the pictures: frame_count / fps, which the duration rounds to.
    audio::Synthesizer synth({.sample_rate = sound_rate,
                              .duration = static_cast<double>(frame_count) / scene.video.fps,
                              .volume = scene.audio.volume});
    const std::size_t begin = sample_of_frame(range.first, scene.video.fps);
    const std::size_t end = sample_of_frame(range.last + 1, scene.video.fps);
    std::size_t position = 0;   // sample frames the synthesizer has given
    Status written;
    const auto write = [&](std::span<const std::int16_t> samples) {
        const std::size_t frames = samples.size() / 2;
        const std::size_t from = std::clamp(begin, position, position + frames) - position;
        const std::size_t to = std::clamp(end, position, position + frames) - position;
        position += frames;
        if (to > from) written = out(samples.subspan(2 * from, 2 * (to - from)));
        return static_cast<bool>(written);
    };
    // Bodies resting on others touch again and again, each time with the speed gravity gave
    // them in a step or two: settling, not impacts. Below four steps' worth they are silent.
    const double g = std::hypot(scene.physics.gravity.x, scene.physics.gravity.y);
    const double settling = 4.0 * g / scene.physics.rate;
    Playback playback(scene);
    // Frames until the sound reaches the end of the range (the synthesizer gives each frame's
    // samples a little after it, for its limiter's look-ahead), or the clip ends.
    const Status played = playback.play(
        {.last = -1, .drawn = {}, .look = true, .should_stop = should_stop,
         .until = [&] { return position >= end; }},
        [&](const ShownFrame& shown) -> Status {
            const render::Camera camera = shown.view->camera;
            const double half_width = camera.height * aspect / 2;
            for (const physics::ContactEvent& event : playback.take_events()) {
                // A sensor's overlaps are silent: nothing struck.
                if (event.kind != physics::ContactEvent::Kind::contact) continue;
                const Body& body = bodies[event.a];
                const bool disc = event.other_kind == physics::ContactEvent::Other::body;
                const Body other = disc ? bodies[event.other]
                                        : Body{body.size, std::numeric_limits<double>::infinity()};
                // The lighter body's change of speed: what makes the contact loud, at any
                // scale.
                const double lighter = std::min(body.mass, other.mass);
                const double x = playback.bodies()[event.a].position.x;
                const double speed = std::isfinite(lighter) ? event.impulse / lighter : 0.0;
                if (speed < settling) continue;
                synth.add({.t = event.t,
                           .speed = speed,
                           .size = std::min(body.size, other.size),
                           .pan = std::clamp((x - camera.center_x) / half_width, -1.0, 1.0)});
            }
            if (!synth.render_until(synth.frame_of(shown.t), write)) return written.error();
            return {};
        });
    if (!played) return played.error();
    if (position < end && !synth.finish(write)) return written.error();
    return {};
}

Expected<RenderSummary> render_soundtrack(const RenderDef& def, FrameRange range) {
    const auto started = Clock::now();
    auto writer = encode::WavWriter::open(def.plan.sink.path, sound_rate, 2);
    if (!writer) return writer.error();
    const auto write = [&](std::span<const std::int16_t> samples) {
        return writer->write(samples);
    };
    if (Status done = write_soundtrack(def.plan.scene, range, write, def.should_stop); !done) {
        return done.error();
    }
    if (Status sealed = writer->seal(); !sealed) return sealed.error();
    if (def.should_stop && def.should_stop()) return Error{cancelled_message};
    if (Status committed = writer->file().commit(); !committed) return committed.error();
    return RenderSummary{.frames = range.last - range.first + 1,
                         .range = range,
                         .seconds = std::chrono::duration<double>(Clock::now() - started).count(),
                         .busy = {},
                         .renderer = {}};
}

}  // namespace discreel::job
