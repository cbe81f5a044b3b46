// pipeline_bench: where a render's time goes, and whether the pipeline keeps the encoder busy.
// For 100, 1 000 and 10 000 moving discs it measures, on the same frames:
//   render only     simulate + draw + readback, timing the draws alone (its CPU time
//                   includes the simulation and keeping the frames)
//   encode only     the pre-rendered RGBA frames through the mp4 sink (colour conversion +
//                   libx264)
//   render | ffmpeg drawing frames and writing raw RGBA into the ffmpeg CLI (the usual way)
//   pipeline        the discreel binary end to end (process start and scene load included),
//                   with its peak memory as it reports it with --verbose
// All at libx264 veryfast, crf 23, 2 encoder threads. Prints a Markdown table.
//     pipeline_bench [--frames 600] [--size 1280x720] [--discs 100,1000,10000] [--repeat 1]
//                    [--hd-seconds 0]
// --repeat K runs the three encoding columns K times in turn and reports each one's median.
// --hd-seconds S also renders S seconds of 1 000 discs at 1920x1080 and reports peak memory.
// Each row is also appended to bench/results/pipeline_bench.csv (bench_results.hpp); the
// 1080p run is a row of its own with only the pipeline's fps and peak memory.
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_results.hpp"
#include "child_process.hpp"
#include "gas_scene.hpp"
#include "discreel/encode.hpp"
#include "discreel/job.hpp"
#include "discreel/render.hpp"
#include "discreel/scene.hpp"

namespace {

using namespace discreel;
using bench::gas_scene;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU seconds (user + system) used so far by this process's threads, or by its waited-for
// children. On a shared machine wall time depends on the neighbours; CPU time much less.
double cpu_seconds(int who) {
    rusage usage{};
    getrusage(who, &usage);
    const auto seconds = [](const timeval& t) { return t.tv_sec + t.tv_usec / 1e6; };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double all_cpu_seconds() { return cpu_seconds(RUSAGE_SELF) + cpu_seconds(RUSAGE_CHILDREN); }

struct Settings {
    int frames = 600;
    int width = 1280;
    int height = 720;
    std::vector<int> disc_counts{100, 1000, 10000};
    int hd_seconds = 0;
    int repeat = 1;                 // runs of each encoding column; the median is reported
};

struct Rendered {
    std::vector<std::uint8_t> frames;   // every frame, one after the other
    double draw_seconds = 0;
};

// Simulates and draws every frame; `each` gets every image as it is drawn.
template <class Each>
double draw_all(const scene::Scene& scene, int frames, Each each) {
    auto renderer = render::Renderer::create({.width = scene.video.width,
                                              .height = scene.video.height});
    if (!renderer) {
        std::cerr << renderer.error().message << '\n';
        std::exit(1);
    }
    job::Playback playback(scene);
    double draw_seconds = 0;
    const Status played = playback.play(
        {.last = frames - 1, .drawn = {}, .look = true, .should_stop = {}, .until = {}},
        [&](const job::ShownFrame& shown) -> Status {
            const auto start = Clock::now();
            auto image = renderer->draw(*shown.view);
            draw_seconds += seconds_since(start);
            if (!image) return image.error();
            each(*image);
            return {};
        });
    if (!played) {
        std::cerr << played.error().message << '\n';
        std::exit(1);
    }
    return draw_seconds;
}

encode::SinkDef mp4(const std::string& path, const scene::Scene& scene) {
    return {.path = path, .width = scene.video.width, .height = scene.video.height,
            .fps = scene.video.fps, .crf = 23, .preset = "veryfast", .threads = 2, .codec = "",
            .pixel_format = "", .lossless = false, .stream_container = "", .key_colours = {}};
}

double encode_only(const std::vector<std::uint8_t>& frames, const scene::Scene& scene, int count,
                   const std::string& path) {
    const std::size_t bytes = std::size_t{4} * static_cast<std::size_t>(scene.video.width) *
                              static_cast<std::size_t>(scene.video.height);
    const auto start = Clock::now();
    auto sink = encode::open_sink(mp4(path, scene));
    if (!sink) {
        std::cerr << sink.error().message << '\n';
        std::exit(1);
    }
    for (int i = 0; i < count; ++i) {
        const ImageView view{scene.video.width, scene.video.height,
                             std::span(frames).subspan(static_cast<std::size_t>(i) * bytes, bytes)};
        if (Status ok = (*sink)->write(view); !ok) {
            std::cerr << ok.error().message << '\n';
            std::exit(1);
        }
    }
    if (Status ok = (*sink)->finish(); !ok) {
        std::cerr << ok.error().message << '\n';
        std::exit(1);
    }
    return seconds_since(start);
}

double render_into_ffmpeg(const scene::Scene& scene, int frames, const std::string& path) {
    const std::string command =
        "ffmpeg -v error -y -f rawvideo -pix_fmt rgba -s " + std::to_string(scene.video.width) +
        "x" + std::to_string(scene.video.height) + " -r 60 -i - -c:v libx264 -preset veryfast "
        "-crf 23 -threads 2 -pix_fmt yuv420p " + path;
    const auto start = Clock::now();
    FILE* pipe = popen(command.c_str(), "w");
    if (pipe == nullptr) {
        std::perror("popen ffmpeg");
        std::exit(1);
    }
    draw_all(scene, frames, [&](const ImageView& image) {
        std::fwrite(image.rgba.data(), 1, image.rgba.size(), pipe);
    });
    if (pclose(pipe) != 0) {
        std::cerr << "ffmpeg failed\n";
        std::exit(1);
    }
    return seconds_since(start);
}

// One timed run of a column: wall seconds and CPU milliseconds per frame.
struct Run {
    double seconds = 0;
    double cpu_ms = 0;
};

// The run with the median wall time (the upper one of the middle two for an even count).
Run median(std::vector<Run> runs) {
    std::sort(runs.begin(), runs.end(),
              [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
    return runs[runs.size() / 2];
}

Settings parse(int argc, char** argv) {
    Settings s;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string name = argv[i];
        const std::string value = argv[i + 1];
        if (name == "--frames") {
            s.frames = std::stoi(value);
        } else if (name == "--size") {
            std::sscanf(value.c_str(), "%dx%d", &s.width, &s.height);
        } else if (name == "--discs") {
            s.disc_counts.clear();
            std::istringstream list(value);
            for (std::string n; std::getline(list, n, ',');) s.disc_counts.push_back(std::stoi(n));
        } else if (name == "--repeat") {
            s.repeat = std::max(1, std::stoi(value));
        } else if (name == "--hd-seconds") {
            s.hd_seconds = std::stoi(value);
        } else {
            std::cerr << "unknown option " << name << '\n';
            std::exit(2);
        }
    }
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const Settings settings = parse(argc, argv);
    // The process settings of `discreel render` (which the pipeline column runs), so every
    // column draws and encodes alike: llvmpipe drawing on the calling thread (LP_NUM_THREADS in
    // the environment overrides it for all columns) and no transparent huge pages.
    render::set_rasterizer_threads(0);
    prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0);
    const auto dir = std::filesystem::temp_directory_path() /
                     ("discreel-pipeline-bench-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);

    double load[1] = {0};
    getloadavg(load, 1);
    std::printf("%d frames at %dx%d, 60 fps, libx264 veryfast crf 23, 2 encoder threads; "
                "LP_NUM_THREADS=%s; %u cores, load average %.1f at the start\n\n",
                settings.frames, settings.width, settings.height, std::getenv("LP_NUM_THREADS"),
                std::thread::hardware_concurrency(), load[0]);
    std::printf("fps = frames / wall seconds; in brackets: CPU ms per frame, all threads and "
                "child processes; encoding columns: median of %d runs taken in turn\n\n",
                settings.repeat);
    std::printf("| discs | render only | encode only | render \\| ffmpeg | pipeline | "
                "pipeline / encode | pipeline / ffmpeg | pipeline peak memory |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    const std::string load_start = bench::csv_number(load[0], 2);
    bench::ResultsFile results(
        "pipeline_bench",
        {"frames", "width", "height", "discs", "repeat", "lp_num_threads", "load_avg_start",
         "load_avg_end", "render_only_fps", "render_only_cpu_ms_per_frame", "encode_only_fps",
         "encode_only_cpu_ms_per_frame", "render_ffmpeg_fps", "render_ffmpeg_cpu_ms_per_frame",
         "pipeline_fps", "pipeline_cpu_ms_per_frame", "pipeline_over_encode",
         "pipeline_over_ffmpeg", "pipeline_peak_mib"});
    const auto number = [](double value, int decimals) {
        return bench::csv_number(value, decimals);
    };
    // The 1-minute load average when a row is written: on a shared machine, how much other
    // work the row was measured beside.
    const auto load_now = [] {
        double now[1] = {0};
        getloadavg(now, 1);
        return bench::csv_number(now[0], 2);
    };
    for (const int discs : settings.disc_counts) {
        const std::string scene_path = (dir / ("gas" + std::to_string(discs) + ".yaml")).string();
        std::ofstream(scene_path) << gas_scene(discs, settings.width, settings.height,
                                               settings.frames);
        const scene::LoadResult loaded = scene::load_scene_file(scene_path);
        if (!loaded.ok()) {
            for (const auto& d : loaded.diagnostics) std::cerr << d.to_string() << '\n';
            return 1;
        }
        const int frames = settings.frames;
        const double fps = frames;   // frames / seconds below

        double cpu = all_cpu_seconds();
        const auto cpu_ms_per_frame = [&] {
            const double now = all_cpu_seconds();
            const double ms = 1000.0 * (now - cpu) / frames;
            cpu = now;
            return ms;
        };
        std::vector<std::uint8_t> stored;
        stored.reserve(std::size_t{4} * static_cast<std::size_t>(settings.width) *
                       static_cast<std::size_t>(settings.height) *
                       static_cast<std::size_t>(frames));
        const double draw_seconds = draw_all(loaded.scene, frames, [&](const ImageView& image) {
            stored.insert(stored.end(), image.rgba.begin(), image.rgba.end());
        });
        const double render_cpu = cpu_ms_per_frame();
        // A shared machine's speed drifts within minutes, so the three encoding columns are
        // run in turn `repeat` times and each reports its median run.
        std::vector<Run> encoded, piped, pipelined;
        double peak_mib = 0;
        for (int r = 0; r < settings.repeat; ++r) {
            const double encode_seconds =
                encode_only(stored, loaded.scene, frames, (dir / "encode.mp4").string());
            encoded.push_back({encode_seconds, cpu_ms_per_frame()});
            const double piped_seconds =
                render_into_ffmpeg(loaded.scene, frames, (dir / "piped.mp4").string());
            piped.push_back({piped_seconds, cpu_ms_per_frame()});
            const discreel::bench::ChildRun pipeline = discreel::bench::run_child(
                {DISCREEL_BIN, "render", scene_path, "-o", (dir / "pipe.mp4").string(), "--crf",
                 "23", "--preset", "veryfast", "--verbose"},
                (dir / "pipe.err").string());
            pipelined.push_back({pipeline.seconds, cpu_ms_per_frame()});
            peak_mib = std::max(peak_mib, pipeline.peak_mib);
        }
        std::vector<std::uint8_t>().swap(stored);
        const Run encode = median(encoded), pipe = median(piped), pipeline = median(pipelined);

        const double encode_fps = fps / encode.seconds;
        const double piped_fps = fps / pipe.seconds;
        const double pipeline_fps = fps / pipeline.seconds;
        std::printf("| %d | %.1f (%.1f) | %.1f (%.1f) | %.1f (%.1f) | %.1f (%.1f) | %.2f | %.2f "
                    "| %.0f MiB |\n",
                    discs, fps / draw_seconds, render_cpu, encode_fps, encode.cpu_ms, piped_fps,
                    pipe.cpu_ms, pipeline_fps, pipeline.cpu_ms, pipeline_fps / encode_fps,
                    pipeline_fps / piped_fps, peak_mib);
        std::fflush(stdout);
        results.append({std::to_string(frames), std::to_string(settings.width),
                        std::to_string(settings.height), std::to_string(discs),
                        std::to_string(settings.repeat), lp_threads ? lp_threads : "",
                        load_start, load_now(), number(fps / draw_seconds, 1),
                        number(render_cpu, 1), number(encode_fps, 1), number(encode.cpu_ms, 1),
                        number(piped_fps, 1), number(pipe.cpu_ms, 1), number(pipeline_fps, 1),
                        number(pipeline.cpu_ms, 1), number(pipeline_fps / encode_fps, 3),
                        number(pipeline_fps / piped_fps, 3), number(peak_mib, 1)});
    }

    if (settings.hd_seconds > 0) {
        const std::string scene_path = (dir / "hd.yaml").string();
        std::ofstream(scene_path) << gas_scene(1000, 1920, 1080, settings.hd_seconds * 60);
        const discreel::bench::ChildRun hd =
            discreel::bench::run_child({DISCREEL_BIN, "render", scene_path, "-o", (dir / "hd.mp4").string(),
                          "--crf", "23", "--preset", "veryfast", "--verbose"},
                         (dir / "hd.err").string());
        std::printf("\n1920x1080, 1 000 discs, %d s (%d frames): %.1f fps, peak memory %.0f MiB\n",
                    settings.hd_seconds, settings.hd_seconds * 60,
                    settings.hd_seconds * 60 / hd.seconds, hd.peak_mib);
        results.append({std::to_string(settings.hd_seconds * 60), "1920", "1080", "1000", "1",
                        lp_threads ? lp_threads : "", load_start, load_now(), "", "", "", "",
                        "", "", number(settings.hd_seconds * 60 / hd.seconds, 1), "", "", "",
                        number(hd.peak_mib, 1)});
    }
    getloadavg(load, 1);
    std::printf("\nload average %.1f at the end\n", load[0]);
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    std::filesystem::remove_all(dir);
    return 0;
}
