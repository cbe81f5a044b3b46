// segments_bench: `discreel render --jobs N` against the ffmpeg CLI encoding the same RGBA
// frames alone (read from a file in the page cache, libx264 veryfast crf 23, ffmpeg's default
// threads), on the 1 000-disc gas clip at 1280x720, 600 frames, in the same run.
//     segments_bench [--frames 600] [--discs 1000] [--jobs 1,2] [--repeat 1] [--sound 1]
// --sound 1 also renders each --jobs with the soundtrack (--audio, AAC), the cost of sound.
// --repeat K runs every column K times in turn and reports each one's median. Prints a Markdown
// table and appends one row per column to bench/results/segments_bench.csv: wall fps, the
// ratio to ffmpeg, CPU ms per frame and discreel's peak memory (its --verbose VmHWM).
#include <unistd.h>

#include <algorithm>
#include <chrono>
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
#include "discreel/job.hpp"
#include "discreel/render.hpp"
#include "discreel/scene.hpp"
#include "gas_scene.hpp"

namespace {

using namespace discreel;

[[noreturn]] void die(const std::string& message) {
    std::cerr << "segments_bench: " << message << '\n';
    std::exit(1);
}

using Run = discreel::bench::ChildRun;
using discreel::bench::run_child;

Run median(std::vector<Run> runs) {
    std::sort(runs.begin(), runs.end(),
              [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
    return runs[runs.size() / 2];
}

// Draws every frame of the scene into a raw RGBA file, the ffmpeg column's input.
void write_raw_frames(const scene::Scene& scene, const std::string& path) {
    render::set_rasterizer_threads(0);
    auto renderer = render::Renderer::create({.width = scene.video.width,
                                              .height = scene.video.height});
    if (!renderer) die(renderer.error().message);
    std::ofstream raw(path, std::ios::binary);
    job::Playback playback(scene);
    const Status played = playback.play({}, [&](const job::ShownFrame& shown) -> Status {
        auto image = renderer->draw(*shown.view);
        if (!image) return image.error();
        raw.write(reinterpret_cast<const char*>(image->rgba.data()),
                  static_cast<std::streamsize>(image->rgba.size()));
        return {};
    });
    if (!played) die(played.error().message);
    if (!raw.flush()) die("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
    int frames = 600, discs = 1000, repeat = 1;
    bool sound = false;
    std::vector<int> jobs{1, 2};
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string name = argv[i], value = argv[i + 1];
        if (name == "--frames") {
            frames = std::stoi(value);
        } else if (name == "--discs") {
            discs = std::stoi(value);
        } else if (name == "--repeat") {
            repeat = std::max(1, std::stoi(value));
        } else if (name == "--sound") {
            sound = value == "1";
        } else if (name == "--jobs") {
            jobs.clear();
            std::istringstream list(value);
            for (std::string n; std::getline(list, n, ',');) jobs.push_back(std::stoi(n));
        } else {
            die("unknown option " + name);
        }
    }
    const auto dir = std::filesystem::temp_directory_path() /
                     ("discreel-segments-bench-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const std::string scene_path = (dir / "gas.yaml").string();
    std::ofstream(scene_path) << bench::gas_scene(discs, 1280, 720, frames);
    const scene::LoadResult loaded = scene::load_scene_file(scene_path);
    if (!loaded.ok()) die("the bench scene does not load");
    const std::string raw = (dir / "frames.rgba").string();
    write_raw_frames(loaded.scene, raw);

    const std::vector<std::string> ffmpeg{
        "ffmpeg", "-v",   "error",   "-y",      "-f",  "rawvideo", "-pix_fmt", "rgba",
        "-s",     "1280x720", "-r",  "60",      "-i",  raw,        "-c:v",     "libx264",
        "-preset", "veryfast", "-crf", "23",    "-pix_fmt", "yuv420p", (dir / "ffmpeg.mp4").string()};
    std::vector<Run> ffmpeg_runs;
    // Each --jobs without sound, then (--sound 1) with it.
    std::vector<std::pair<int, bool>> columns;
    for (const int j : jobs) columns.emplace_back(j, false);
    if (sound) {
        for (const int j : jobs) columns.emplace_back(j, true);
    }
    std::vector<std::vector<Run>> discreel_runs(columns.size());
    for (int r = 0; r < repeat; ++r) {
        ffmpeg_runs.push_back(run_child(ffmpeg, (dir / "ffmpeg.err").string()));
        for (std::size_t c = 0; c < columns.size(); ++c) {
            discreel_runs[c].push_back(run_child(
                {DISCREEL_BIN, "render", scene_path, "-o", (dir / "out.mp4").string(), "--crf",
                 "23", "--preset", "veryfast", "--jobs", std::to_string(columns[c].first),
                 columns[c].second ? "--audio" : "--no-audio", "--verbose"},
                (dir / "discreel.err").string()));
        }
    }
    std::filesystem::remove_all(dir);

    double load[1] = {0};
    getloadavg(load, 1);
    std::printf("%d discs, 1280x720, %d frames at 60 fps, libx264 veryfast crf 23; %u cores; "
                "median of %d; load average %.1f at the end\n\n",
                discs, frames, std::thread::hardware_concurrency(), repeat, load[0]);
    std::printf("| command | fps | vs ffmpeg | CPU ms/frame | peak memory |\n|---|---:|---:|---:|---:|\n");
    bench::ResultsFile results("segments_bench",
                               {"frames", "discs", "repeat", "command", "jobs", "fps",
                                "over_ffmpeg", "cpu_ms_per_frame", "peak_mib", "load_avg_end"});
    const Run base = median(ffmpeg_runs);
    const auto row = [&](const std::string& command, int job_count, const Run& run) {
        const double fps = frames / run.seconds;
        const double ratio = base.seconds / run.seconds;
        const double cpu_ms = 1000.0 * run.cpu_seconds / frames;
        std::printf("| %s | %.1f | %.2f | %.1f | %s |\n", command.c_str(), fps, ratio, cpu_ms,
                    run.peak_mib > 0 ? (std::to_string(static_cast<int>(run.peak_mib)) + " MiB").c_str() : "");
        results.append({std::to_string(frames), std::to_string(discs), std::to_string(repeat),
                        command, job_count > 0 ? std::to_string(job_count) : "",
                        bench::csv_number(fps, 1), bench::csv_number(ratio, 3),
                        bench::csv_number(cpu_ms, 1),
                        run.peak_mib > 0 ? bench::csv_number(run.peak_mib, 1) : "",
                        bench::csv_number(load[0], 2)});
    };
    row("ffmpeg (RGBA file, default threads)", 0, base);
    for (std::size_t c = 0; c < columns.size(); ++c) {
        row("discreel render --jobs " + std::to_string(columns[c].first) +
                (columns[c].second ? " --audio" : ""),
            columns[c].first, median(discreel_runs[c]));
    }
    if (!results.path().empty()) std::printf("\nappended to %s\n", results.path().c_str());
    return 0;
}
