// dataset_bench: the throughput of a dataset, as docs/scale.md builds one: N variants of one
// scene (`--set physics.seed=i`), each 60 frames at 128x128 written as a PNG sequence with its
// instance masks, boxes, camera, shapes and trace, through `discreel batch --all --jobs J`.
//     dataset_bench [--scenes 100] [--jobs 1,2] [--repeat 1]
// Prints a Markdown table and appends one row per --jobs to bench/results/dataset_bench.csv:
// scenes per second and CPU seconds per scene (the median of --repeat runs).

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_results.hpp"
#include "child_process.hpp"

namespace {

namespace fs = std::filesystem;

[[noreturn]] void die(const std::string& message) {
    std::cerr << "dataset_bench: " << message << '\n';
    std::exit(1);
}

// Discs and polygons scattered by the seed, falling in a box onto a slope: 60 frames.
constexpr const char* scene_text = R"(version: 1
video: {size: [128, 128], fps: 30, duration: 2}
walls:
  - box: [[0, 0], [4, 4]]
  - {segment: [[0, 1.2], [4, 0.4]], thickness: 0.06}
discs:
  - random: {count: 10, region: [[0.3, 1.8], [3.7, 3.7]], radius: [0.08, 0.2], speed: [0, 2]}
bodies:
  - random_polygons: {count: 6, region: [[0.3, 1.8], [3.7, 3.7]], sides: [3, 6],
                      size: [0.12, 0.25], speed: [0, 2]}
)";

using discreel::bench::ChildRun;

ChildRun run_batch(const std::string& manifest, int jobs, const std::string& err_path) {
    return discreel::bench::run_child(
        {DISCREEL_BIN, "batch", manifest, "--all", "--jobs", std::to_string(jobs)}, err_path);
}

std::vector<int> parse_list(const std::string& text) {
    std::vector<int> out;
    std::stringstream s(text);
    for (std::string item; std::getline(s, item, ',');) out.push_back(std::stoi(item));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    int scenes = 100, repeat = 1;
    std::vector<int> jobs{1, 2};
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--scenes") scenes = std::stoi(value);
        else if (flag == "--jobs") jobs = parse_list(value);
        else if (flag == "--repeat") repeat = std::stoi(value);
        else die("unknown option " + flag);
    }
    const fs::path dir = fs::temp_directory_path() / ("dataset_bench." + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "scene.yaml") << scene_text;
    {
        std::ofstream manifest(dir / "manifest.txt");
        for (int i = 0; i < scenes; ++i) {
            const std::string out = (dir / "out" / std::to_string(i)).string();
            manifest << (dir / "scene.yaml").string() << " -o " << out
                     << "/frame_%04d.png --set physics.seed=" << i << " --masks " << out
                     << "/masks --boxes " << out << "/boxes.csv --camera " << out
                     << "/camera.csv --shapes " << out << "/shapes.json --trace " << out
                     << "/trace.csv -q\n";
        }
    }
    discreel::bench::ResultsFile results(
        "dataset_bench", {"scenes", "size", "frames", "jobs", "seconds", "scenes_per_s",
                          "cpu_s_per_scene"});
    std::cout << "| jobs | seconds | scenes/s | CPU s per scene |\n|---|---|---|---|\n";
    for (const int j : jobs) {
        std::vector<ChildRun> runs;
        for (int r = 0; r < repeat; ++r) {
            fs::remove_all(dir / "out");
            runs.push_back(run_batch((dir / "manifest.txt").string(), j,
                                     (dir / "batch.err").string()));
        }
        std::sort(runs.begin(), runs.end(),
                  [](const ChildRun& a, const ChildRun& b) { return a.seconds < b.seconds; });
        const ChildRun& run = runs[runs.size() / 2];
        const double per_s = scenes / run.seconds, cpu = run.cpu_seconds / scenes;
        std::cout << "| " << j << " | " << discreel::bench::csv_number(run.seconds, 2) << " | "
                  << discreel::bench::csv_number(per_s, 2) << " | "
                  << discreel::bench::csv_number(cpu, 3) << " |\n";
        results.append({std::to_string(scenes), "128x128", "60", std::to_string(j),
                        discreel::bench::csv_number(run.seconds, 3),
                        discreel::bench::csv_number(per_s, 3),
                        discreel::bench::csv_number(cpu, 4)});
    }
    fs::remove_all(dir);
    return 0;
}
