// job::render: the simulate, render and encode stages of a clip or still, and its outputs.
#include <sys/prctl.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <thread>

#include "discreel/commit.hpp"
#include "discreel/job.hpp"
#include "warnings_once.hpp"
#include "pipeline.hpp"
#include "sample_queue.hpp"
#include "segment_render.hpp"
#include "side_outputs.hpp"
#include "soundtrack.hpp"

namespace discreel::job {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The colours frames are drawn in; a GIF palette starts with them so they come out exact.
std::vector<encode::Rgb> scene_colours(const scene::Scene& scene) {
    std::vector<encode::Rgb> colours;
    const auto add = [&](const scene::Color& c) { colours.push_back({c.r, c.g, c.b}); };
    add(scene.video.background);
    for (const auto& wall : scene.walls) add(wall.color);
    for (const auto& disc : scene.bodies) add(disc.color);
    return colours;
}

const Error cancelled{cancelled_message};

}  // namespace

// Up to 720p, six slots (3.5 MiB each at 720p) let the simulate and render stages, which
// yield to the encoder (PipelineDef::encoder_first), work several frames ahead in the cycles
// x264 leaves idle. Above 720p a slot is 8 MiB or more and two keep a 1080p render under
// 300 MB (docs/performance.md); the encoder still has the next frame ready, because drawing
// and simulating a frame take a fraction of the time it needs.
int slots_for(int width, int height) {
    return static_cast<long>(width) * height > 1280L * 720L ? 2 : 6;
}

bool segmented(const encode::OutputDescription& output) {
    return !output.to_stdout &&
           (output.format == "mp4" || output.format == "mkv" || output.format == "webm");
}

int segment_count(const scene::Video& video, FrameRange frames) {
    const int length = video.segment_frames();
    return (frames.last - frames.first + length) / length;
}

FrameRange segment_frames(const scene::Video& video, FrameRange frames, int index) {
    const int length = video.segment_frames();
    const int first = frames.first + index * length;
    return {first, std::min(frames.last, first + length - 1)};
}

Expected<RenderSummary> render(const RenderDef& def) {
    const auto started = Clock::now();
    const scene::Scene& scene = def.plan.scene;
    const int count = scene.video.frame_count();
    const FrameRange asked = def.plan.frames;
    const FrameRange range{asked.first, asked.last < 0 ? count - 1 : asked.last};
    if (range.first < 0 || range.first > range.last || range.last >= count) {
        return Error{"frames " + std::to_string(range.first) + ".." + std::to_string(range.last) +
                     " are not in the clip, which has " + std::to_string(count) + " frames"};
    }
    if (def.renderer != nullptr && (def.renderer->def().width != scene.video.width ||
                                    def.renderer->def().height != scene.video.height)) {
        return Error{"the warm renderer draws another size than the scene's video"};
    }
    // The encoder's threads keep most of the cores busy; llvmpipe's rasterizer threads would
    // compete with them and cost more CPU than they save, so the render stage draws on its own
    // thread (docs/performance.md). Set before any thread starts; LP_NUM_THREADS in the
    // environment still wins.
    render::set_rasterizer_threads(0);
    // libx264 asks for transparent huge pages on its frame buffers, which rounds each one up to
    // whole 2 MiB pages of resident memory: 11-13 MiB at 1080p, at no measurable cost in speed.
    // Best effort (a kernel without the setting just keeps the default).
    prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);

    encode::SinkDef sink_def = def.plan.sink;
    sink_def.width = scene.video.width;
    sink_def.height = scene.video.height;
    sink_def.fps = scene.video.fps;
    sink_def.key_colours = scene_colours(scene);
    sink_def.first_number = range.first;
    auto output = encode::describe_output(sink_def.path, sink_def.stream_container);
    if (!output) return output.error();
    if (output->format == "wav") return render_soundtrack(def, range);
    if (segmented(*output)) return render_segments(def, range, sink_def, output->format);
    if (def.plan.segment) return Error{"only video files (.mp4, .mkv, .webm) are made of segments"};

    auto outputs = SideOutputs::open(def.trace, def.events, def.joints, scene, def.truth);
    if (!outputs) return outputs.error();
    sink_def.sound = def.plan.audio;
    auto sink = encode::open_sink(sink_def);
    if (!sink) return sink.error();

    // A stream with sound: the samples come from a thread of their own (its own playback)
    // through a bounded queue of 2 s, and follow each frame into the sink.
    std::optional<SampleQueue> samples;
    std::thread sound_thread;
    Status sounded;
    if (def.plan.audio) {
        samples.emplace(std::size_t{2} * 2 * sound_rate);
        sound_thread = std::thread([&] {
            sounded = write_soundtrack(
                scene, range,
                [&](std::span<const std::int16_t> block) -> Status {
                    if (!samples->push(block)) return Error{"cancelled"};
                    return {};
                },
                def.should_stop);
            samples->close();
        });
    }
    // Ends the sound thread on every way out of this function.
    struct SoundThreadGuard {
        std::optional<SampleQueue>& queue;
        std::thread& thread;
        ~SoundThreadGuard() {
            if (queue) queue->cancel();
            if (thread.joinable()) thread.join();
        }
    } sound_guard{samples, sound_thread};
    const std::size_t first_sample = sample_of_frame(range.first, scene.video.fps);
    std::size_t samples_given = 0;   // sample frames given to the sink
    const auto give_sound = [&](int frames_done) -> Status {
        const std::size_t until =
            sample_of_frame(range.first + frames_done, scene.video.fps) - first_sample;
        while (samples_given < until) {
            const auto block = samples->take(2 * (until - samples_given));
            if (block.empty()) return sounded ? Error{"the sound ended early"} : sounded;
            if (Status written = (*sink)->write_sound(block); !written) return written;
            samples_given += block.size() / 2;
        }
        return {};
    };
    int frames_written = 0;

    Playback playback(scene);
    WarningsOnce warnings(def.on_warning);
    const auto stop_asked = [&] { return def.should_stop && def.should_stop(); };
    Status simulated;   // the physics' failure, which stops the run like a cancellation
    const PipelineStages stages{
        .simulate = [&](int frame) -> const render::FrameScene* {
            auto shown = playback.show(frame, frame >= range.first, def.should_stop);
            if (!shown) {
                simulated = shown.error();
                return nullptr;
            }
            warnings.say(playback.take_warnings());
            outputs->record(frame, playback.time_of_frame(frame), playback.world(),
                            playback.take_events());
            if (*shown == nullptr) return nullptr;   // before the range: observed only
            if (outputs->views_wanted()) {
                simulated = outputs->record_view(frame, playback.time_of_frame(frame), **shown);
                if (!simulated) return nullptr;
            }
            return *shown;
        },
        .encode =
            [&](const ImageView& image) {
                Status written = (*sink)->write(image);
                if (written && samples) written = give_sound(++frames_written);
                return written;
            },
        .encoded =
            [&](int done) {
                if (def.on_progress) {
                    def.on_progress({.frames_done = done,
                                     .frames_total = range.last - range.first + 1,
                                     .elapsed = seconds_since(started)});
                }
            },
        .should_stop = [&] { return !simulated || stop_asked(); },
    };
    const PipelineResult run = run_pipeline(
        {.frame_count = range.last + 1,
         .renderer = {.width = scene.video.width, .height = scene.video.height},
         .warm_renderer = def.renderer,
         .threaded = def.threaded,
         .slots = slots_for(scene.video.width, scene.video.height),
         .encoder_first = true},
        stages);
    // A cancellation is checked first: the write it broke (SIGPIPE's EPIPE) is not the story.
    if (stop_asked()) return cancelled;
    if (!simulated) return simulated.error();
    if (!run.status) return run.status.error();
    if (run.stopped) return cancelled;
    // The video, trace and events become visible together, or none of them.
    if (sound_thread.joinable()) sound_thread.join();
    if (!sounded) return sounded.error();
    Status sealed = (*sink)->seal();
    if (sealed) sealed = outputs->seal();
    if (stop_asked()) return cancelled;
    if (sealed) {
        std::vector<OutputFile*> files = (*sink)->files();
        for (OutputFile* file : outputs->files()) files.push_back(file);
        sealed = commit_together(files);
    }
    if (!sealed) return sealed.error();
    return RenderSummary{.frames = range.last - range.first + 1,
                         .range = range,
                         .seconds = seconds_since(started),
                         .busy = run.busy,
                         .renderer = run.renderer_info};
}

}  // namespace discreel::job
