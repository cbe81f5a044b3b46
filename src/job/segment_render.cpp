// A video rendered in segments: workers take the next segment in turn, each playing the scene
// forward on its own (physics is sequential, and a small part of a frame's cost, so each
// worker simulates every frame up to its segment without drawing it) and encoding the segment
// into a file of its own; the files are then joined by stream copy. Segment k is the same
// bytes whichever worker renders it, so the output does not depend on the number of workers.
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "discreel/commit.hpp"
#include "pipeline.hpp"
#include "segment_render.hpp"
#include "side_outputs.hpp"
#include "soundtrack.hpp"
#include "warnings_once.hpp"

namespace discreel::job {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The cores this process may run on (its affinity mask, which containers and Slurm set).
int usable_cores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
    return std::max(1U, std::thread::hardware_concurrency());
}

const Error cancelled{cancelled_message};

// MemAvailable from /proc/meminfo, bytes; nullopt where there is none.
std::optional<double> available_memory() {
    std::FILE* file = std::fopen("/proc/meminfo", "r");
    if (file == nullptr) return std::nullopt;
    char line[256];
    std::optional<double> found;
    while (std::fgets(line, sizeof line, file) != nullptr) {
        unsigned long long kib = 0;
        if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) {
            found = static_cast<double>(kib) * 1024.0;
            break;
        }
    }
    std::fclose(file);
    return found;
}

// What the workers share: the queue of segments, progress, the first failure.
class SegmentRun {
public:
    SegmentRun(const RenderDef& def, FrameRange range, const encode::SinkDef& sink,
               std::vector<int> wanted, std::vector<std::string> paths)
        : def_(def), range_(range), sink_(sink), wanted_(std::move(wanted)),
          paths_(std::move(paths)), files_(wanted_.size()), started_(Clock::now()) {
        for (int k : wanted_) {
            const FrameRange piece = segment_frames(def_.plan.scene.video, range_, k);
            frames_total_ += piece.last - piece.first + 1;
        }
    }

    // Runs `workers` workers (the first on the caller's warm renderer, if any) and, when
    // asked for, the trace and events beside them.
    Status run(int workers, SideOutputs* outputs) {
        std::vector<std::thread> threads;
        for (int w = 1; w < workers; ++w) threads.emplace_back([this] { work(nullptr); });
        std::thread recorder;
        if (outputs != nullptr) recorder = std::thread([this, outputs] { record(*outputs); });
        work(def_.renderer);
        for (std::thread& thread : threads) thread.join();
        if (recorder.joinable()) recorder.join();
        if (stop_asked()) return cancelled;
        std::lock_guard lock(mutex_);
        return status_;
    }

    std::vector<std::optional<OutputFile>>& files() { return files_; }
    const StageSeconds& busy() const { return busy_; }
    const std::string& renderer_info() const { return renderer_info_; }

private:
    bool stop_asked() const { return def_.should_stop && def_.should_stop(); }
    bool stopping() const { return failed_.load() || stop_asked(); }

    void fail(Error error) {
        std::lock_guard lock(mutex_);
        if (status_) status_ = std::move(error);
        failed_ = true;
    }

    void work(render::Renderer* warm) {
        Playback playback(def_.plan.scene);
        std::optional<render::Renderer> own;
        for (;;) {
            const std::size_t j = next_.fetch_add(1);
            if (j >= wanted_.size() || stopping()) return;
            if (warm == nullptr) {
                auto made = render::Renderer::create(
                    {.width = def_.plan.scene.video.width, .height = def_.plan.scene.video.height});
                if (!made) return fail(made.error());
                own = std::move(*made);
                warm = &*own;
            }
            const FrameRange piece = segment_frames(def_.plan.scene.video, range_, wanted_[j]);
            if (Status done = encode_segment(playback, piece, *warm, j); !done) {
                return fail(as_output_error(done.error(), j));
            }
        }
    }

    // A segment of a whole render is a temporary file of the output's: its write errors are
    // the output's, and name it.
    Error as_output_error(Error error, std::size_t j) const {
        if (def_.plan.segment) return error;
        const std::string prefix = write_error(paths_[j], "").message;
        if (error.message.rfind(prefix, 0) != 0) return error;
        return write_error(def_.plan.sink.path, error.message.substr(prefix.size()));
    }

    Status encode_segment(Playback& playback, FrameRange piece,
                          render::Renderer& renderer, std::size_t j) {
        encode::SinkDef sink_def = sink_;
        sink_def.path = paths_[j];
        sink_def.first_number = piece.first;
        auto sink = encode::open_sink(sink_def);
        if (!sink) return sink.error();
        Status simulated;
        int reported = 0;
        const PipelineStages stages{
            .simulate = [&](int frame) -> const render::FrameScene* {
                auto shown = playback.show(frame, frame >= piece.first, def_.should_stop);
                if (!shown) {
                    simulated = shown.error();
                    return nullptr;
                }
                warnings_.say(playback.take_warnings());
                playback.take_events();   // the recorder writes them; here they are not kept
                return *shown;            // null before the segment: observed only
            },
            .encode = [&](const ImageView& image) { return (*sink)->write(image); },
            .encoded =
                [&](int done) {
                    progress(done - reported);
                    reported = done;
                },
            .should_stop = [&] { return !simulated || stopping(); },
        };
        const PipelineResult run = run_pipeline(
            {.first_frame = playback.next_frame(),
             .frame_count = piece.last + 1,
             .renderer = renderer.def(),
             .warm_renderer = &renderer,
             .threaded = def_.threaded,
             .slots = slots_for(def_.plan.scene.video.width, def_.plan.scene.video.height),
             .encoder_first = true},
            stages);
        {
            std::lock_guard lock(mutex_);
            busy_.simulate += run.busy.simulate;
            busy_.render += run.busy.render;
            busy_.encode += run.busy.encode;
            if (renderer_info_.empty()) renderer_info_ = run.renderer_info;
        }
        if (!simulated) return simulated.error();
        if (!run.status) return run.status.error();
        if (run.stopped) return cancelled;
        if (Status sealed = (*sink)->seal(); !sealed) return sealed.error();
        // The sealed file outlives its sink, whose encoder is freed now.
        files_[j].emplace(std::move(*(*sink)->files().front()));
        return {};
    }

    void progress(int frames) {
        std::lock_guard lock(mutex_);
        frames_done_ += frames;
        if (def_.on_progress) {
            def_.on_progress({.frames_done = frames_done_,
                              .frames_total = frames_total_,
                              .elapsed = seconds_since(started_)});
        }
    }

    // The trace and events of the whole clip, from a playback of their own.
    void record(SideOutputs& outputs) {
        Playback playback(def_.plan.scene);
        // The drawn frames' views as the segments draw them, every earlier frame observed
        // (trails, the follow camera); without views, the physics alone.
        const bool views = outputs.views_wanted();
        const Status played = playback.play(
            {.last = range_.last,
             .drawn = [&](int frame) { return frame >= range_.first; },
             .look = views,
             .should_stop = [&] { return stopping(); },
             .until = {}},
            [&](const ShownFrame& shown) -> Status {
                warnings_.say(playback.take_warnings());
                outputs.record(shown.frame, shown.t, playback.world(), playback.take_events());
                if (shown.view == nullptr) return {};
                return outputs.record_view(shown.frame, shown.t, *shown.view);
            });
        // Stopped because another worker failed: that failure is the story.
        if (!played && !failed_.load()) fail(played.error());
    }

    const RenderDef& def_;
    const FrameRange range_;
    const encode::SinkDef& sink_;
    const std::vector<int> wanted_;          // segment indices, rendered in this order
    const std::vector<std::string> paths_;   // each one's file
    std::vector<std::optional<OutputFile>> files_;   // sealed, per wanted segment
    std::atomic<std::size_t> next_{0};
    std::atomic<bool> failed_{false};
    WarningsOnce warnings_{def_.on_warning};
    std::mutex mutex_;                       // guards what follows
    Status status_;
    StageSeconds busy_;
    std::string renderer_info_;
    int frames_done_ = 0;
    int frames_total_ = 0;
    Clock::time_point started_;
};

}  // namespace

Expected<RenderSummary> render_segments(const RenderDef& def, FrameRange range,
                                        const encode::SinkDef& sink, const std::string& format) {
    const auto started = Clock::now();
    const int count = segment_count(def.plan.scene.video, range);
    encode::SinkDef segment_sink = sink;
    segment_sink.keyint = def.plan.scene.video.segment_frames();
    // One encoder thread per segment: x264's bytes depend on its thread count, and segments
    // side by side use the cores better than one encoder's frame threads.
    segment_sink.threads = 1;

    std::vector<int> wanted;
    std::vector<std::string> paths;
    if (def.plan.segment) {
        if (*def.plan.segment < 0 || *def.plan.segment >= count) {
            return Error{"segment " + std::to_string(*def.plan.segment) +
                         " is not in the clip, which has " +
                         std::to_string(count) + (count == 1 ? " segment" : " segments") +
                         " (0.." + std::to_string(count - 1) + ")"};
        }
        if (def.trace || def.events || def.joints) {
            return Error{"--trace, --events and --joints belong to a whole render, not to one "
                         "segment"};
        }
        wanted = {*def.plan.segment};
        paths = {sink.path};
    } else {
        // Each segment goes to a temporary file beside the output (never committed), so the
        // join reads and writes on one file system.
        const std::filesystem::path dir = std::filesystem::path(sink.path).parent_path();
        for (int k = 0; k < count; ++k) {
            wanted.push_back(k);
            paths.push_back((dir / encode::segment_file_name(k, count, format)).string());
        }
    }
    // The output's temporary file is made first: a target that cannot be written fails
    // before any work.
    std::optional<OutputFile> joined;
    if (!def.plan.segment) {
        auto made = OutputFile::create(sink.path);
        if (!made) return made.error();
        joined.emplace(std::move(*made));
    }
    // The sound of the frames rendered: beside the segment, or a temporary file for the join.
    std::optional<encode::WavWriter> sound;
    if (def.plan.audio) {
        const std::string sound_path =
            def.plan.segment ? std::filesystem::path(sink.path).replace_extension(".wav").string()
                        : sink.path + ".sound.wav";
        auto opened = encode::WavWriter::open(sound_path, sound_rate, 2);
        if (!opened) return opened.error();
        sound.emplace(std::move(*opened));
    }
    std::optional<SideOutputs> outputs;
    const GroundTruthPaths& truth = def.truth;
    if (def.trace || def.events || def.joints || truth.shapes || truth.camera || truth.masks ||
        truth.boxes) {
        auto opened = SideOutputs::open(def.trace, def.events, def.joints, def.plan.scene, truth);
        if (!opened) return opened.error();
        outputs.emplace(std::move(*opened));
    }
    const int asked = std::min(def.jobs > 0 ? def.jobs : usable_cores(),
                               segments_memory_holds(def.plan.scene.video.width,
                                                     def.plan.scene.video.height));
    const int workers = def.threaded ? std::clamp(asked, 1, static_cast<int>(wanted.size())) : 1;

    SegmentRun run(def, range, segment_sink, wanted, paths);
    Status sounded;
    std::thread sound_thread;
    if (sound) {
        const FrameRange heard =
            def.plan.segment ? segment_frames(def.plan.scene.video, range, *def.plan.segment)
                             : range;
        sound_thread = std::thread([&, heard] {   // `heard` by value: it ends with this block
            sounded = write_soundtrack(
                def.plan.scene, heard,
                [&](std::span<const std::int16_t> samples) { return sound->write(samples); },
                def.should_stop);
            if (sounded) sounded = sound->seal();
        });
    }
    Status done = run.run(workers, outputs ? &*outputs : nullptr);
    if (sound_thread.joinable()) sound_thread.join();
    if (!done) return done.error();
    if (!sounded) return sounded.error();

    std::vector<OutputFile*> files;
    if (def.plan.segment) {
        files.push_back(&*run.files().front());
        if (sound) files.push_back(&sound->file());
    } else {
        encode::SegmentSet set{format, {}, {}};
        for (const auto& file : run.files()) set.paths.push_back(file->temp_path());
        if (sound) set.sound.push_back(sound->file().temp_path());
        if (Status done = encode::join_segments(set, *joined); !done) return done.error();
        files.push_back(&*joined);
    }
    if (outputs) {
        if (Status sealed = outputs->seal(); !sealed) return sealed.error();
        for (OutputFile* file : outputs->files()) files.push_back(file);
    }
    if (def.should_stop && def.should_stop()) return cancelled;
    if (Status committed = commit_together(files); !committed) return committed.error();
    const FrameRange written =
        def.plan.segment ? segment_frames(def.plan.scene.video, range, *def.plan.segment) : range;
    return RenderSummary{.frames = written.last - written.first + 1,
                         .range = written,
                         .seconds = seconds_since(started),
                         .busy = run.busy(),
                         .renderer = run.renderer_info()};
}

int segments_memory_holds(int width, int height) {
    const double each = 48.0 * (1 << 20) + 48.0 * width * height;
    const auto available = available_memory();
    if (!available) return 1 << 20;
    // Three quarters: the rest is the process's own and the system's.
    return static_cast<int>(std::clamp(0.75 * *available / each, 1.0, 1e6));
}

}  // namespace discreel::job
