// studio_bench: the studio's latency as the page sees it (docs/serve.md, "Studio"), over HTTP
// to a server in this process, for every gallery scene (configs/*.yaml) at 480x270:
//   edit    an edited text (a new session: the physics from t = 0 to the scrubber's frame,
//           once) with the scrubber at 0 s, 1 s and the middle of the clip; then, untimed, the
//           timeline, which the page asks for next (it plays the clip to its end once);
//   scrub   then frames across the clip in a shuffled order (from the checkpoints);
//   play    the frames one after another from the start;
//   typing  then, as the page does while someone types: six texts, each one's frame at the
//           middle of the clip (asked again 100 ms later when the studio answers 429) and then
//           its timeline in the background, the next text 150 ms after the preview came;
//           `typing` with the page's tab (a tab's newer text stops its older timelines),
//           `typing_untabbed` without (every timeline plays its clip to the end); and the
//           same three times over for rain lengthened to a minute, typed at 4 s
//           (`typing_long`, `typing_long_untabbed`), where the timelines take seconds;
// each from POST to the last byte of the PNG; p50 and p99 per kind over all scenes. Also the
// memory a session's checkpoints hold once it has played its whole clip (malloc's count of
// bytes in use with and without them). Appends to bench/results/studio_bench.csv.
//     studio_bench [EDITS_PER_POSITION]   (default 3)
#include <httplib.h>
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_results.hpp"
#include "discreel/job.hpp"
#include "discreel/serve.hpp"

namespace {

using discreel::bench::percentile;

using nlohmann::json;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

struct Running {
    discreel::serve::Server server;
    std::thread thread;
    ~Running() {
        server.stop();
        thread.join();
    }
};

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Bytes malloc holds in use (arena and mmapped chunks).
double heap_bytes() {
    const struct mallinfo2 info = mallinfo2();
    return static_cast<double>(info.uordblks + info.hblkhd);
}

// What a session's checkpoints hold after playing the whole clip: the heap with them, less
// the heap of the same playback without.
double checkpoint_bytes(const fs::path& path) {
    auto loaded = discreel::scene::load_scene_file(path);
    if (!loaded.ok()) return 0;
    loaded.scene.video.width = 480;
    loaded.scene.video.height = 270;
    double held[2] = {0, 0};
    for (const int with : {0, 1}) {
        malloc_trim(0);
        const double before = heap_bytes();
        discreel::job::Playback playback(loaded.scene,
                                         {.checkpoint_every = with ? loaded.scene.video.fps : 0,
                                          .max_checkpoints = 1 << 20,
                                          .max_checkpoint_bytes = 0});
        if (!playback.show(playback.frame_count() - 1, false)) return 0;
        held[with] = heap_bytes() - before;
    }
    return held[1] - held[0];
}

}  // namespace

int main(int argc, char** argv) {
    const int edits = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
    const fs::path data =
        fs::temp_directory_path() / ("studio_bench_" + std::to_string(::getpid()));
    fs::create_directories(data);
    discreel::serve::ServeDef def;
    def.port = 0;
    def.data_dir = data.string();
    def.version = "bench";
    def.log_requests = false;
    auto server = discreel::serve::Server::open(def);
    if (!server) {
        std::fprintf(stderr, "studio_bench: %s\n", server.error().message.c_str());
        return 1;
    }
    Running running{std::move(*server), {}};
    running.thread = std::thread([&] { (void)running.server.run(); });
    httplib::Client client("127.0.0.1", running.server.port());
    client.set_read_timeout(120);

    std::vector<fs::path> scenes;
    for (const auto& entry : fs::directory_iterator(fs::path(DISCREEL_SOURCE_DIR) / "configs")) {
        if (entry.path().extension() == ".yaml") scenes.push_back(entry.path());
    }
    std::sort(scenes.begin(), scenes.end());

    std::map<std::string, std::vector<double>> ms;   // by kind
    int frames_total = 0;
    const auto ask = [&](const std::string& text, int frame, const char* kind) {
        const auto start = Clock::now();
        auto res = client.Post("/v1/studio/frame",
                               json{{"scene", text}, {"size", "480x270"}, {"frame", frame}}.dump(),
                               "application/json");
        const double took = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        if (!res || res->status != 200) {
            std::fprintf(stderr, "studio_bench: frame %d: %s\n", frame,
                         res ? res->body.c_str() : "no answer");
            std::exit(1);
        }
        frames_total = std::stoi(res->get_header_value("X-Discreel-Frames"));
        const int fps = std::stoi(res->get_header_value("X-Discreel-Fps"));
        if (kind != nullptr) ms[kind].push_back(took);
        return fps;
    };
    const auto type = [&](const std::string& text, int at, const char* tab, const char* kind,
                          int& typed, const json& set = nullptr) {
        std::vector<std::thread> timelines;
        for (int e = 0; e < 6; ++e) {
            json body{{"scene", text + "# typed " + std::to_string(++typed) + "\n"},
                      {"size", "480x270"}};
            if (tab != nullptr) body["tab"] = tab;
            if (!set.is_null()) body["set"] = set;
            json frame = body;
            frame["frame"] = at;
            const auto start = Clock::now();
            for (int tries = 0;; ++tries) {
                auto res = client.Post("/v1/studio/frame", frame.dump(), "application/json");
                if (res && res->status == 429 && tries < 1200) {
                    std::this_thread::sleep_for(std::chrono::milliseconds(100));
                    continue;
                }
                if (!res || res->status != 200) {
                    std::fprintf(stderr, "studio_bench: typing: %s\n",
                                 res ? res->body.c_str() : "no answer");
                    std::exit(1);
                }
                break;
            }
            ms[kind].push_back(
                std::chrono::duration<double, std::milli>(Clock::now() - start).count());
            timelines.emplace_back([port = running.server.port(), body] {
                httplib::Client own("127.0.0.1", port);
                own.set_read_timeout(120);
                (void)own.Post("/v1/studio/timeline", body.dump(), "application/json");
            });
            std::this_thread::sleep_for(std::chrono::milliseconds(150));
        }
        for (std::thread& t : timelines) t.join();
    };
    discreel::bench::ResultsFile results("studio_bench", {"scene", "measure", "value", "unit"});
    std::mt19937 shuffle(7);
    int edit_number = 0;
    for (const fs::path& path : scenes) {
        const std::string text = read_text(path);
        const int fps = ask(text, 0, nullptr);   // the renderer of this size, warm
        const int frames = frames_total;
        std::vector<double> own;
        for (const int at : {0, std::min(frames - 1, fps), frames / 2}) {
            for (int e = 0; e < edits; ++e) {
                const std::string edited = text + "# edit " + std::to_string(++edit_number) + "\n";
                const std::size_t before = ms["edit"].size();
                ask(edited, at, "edit");
                own.push_back(ms["edit"][before]);
                auto timeline = client.Post("/v1/studio/timeline",
                                            json{{"scene", edited}, {"size", "480x270"}}.dump(),
                                            "application/json");
                if (!timeline || timeline->status != 200) {
                    std::fprintf(stderr, "studio_bench: the timeline failed\n");
                    return 1;
                }
            }
        }
        // The last edit's session: scrub across the clip, then play from the start.
        const std::string edited = text + "# edit " + std::to_string(edit_number) + "\n";
        std::vector<int> order;
        for (int f = 0; f < frames; f += std::max(1, frames / 40)) order.push_back(f);
        std::shuffle(order.begin(), order.end(), shuffle);
        const std::size_t scrubs_before = ms["scrub"].size();
        for (const int f : order) ask(edited, f, "scrub");
        const std::vector<double> scrubs(ms["scrub"].begin() + static_cast<long>(scrubs_before),
                                         ms["scrub"].end());
        for (int f = 0; f < std::min(frames, 2 * fps); ++f) ask(edited, f, "play");
        type(text, frames / 2, "studio-bench", "typing", edit_number);
        type(text, frames / 2, nullptr, "typing_untabbed", edit_number);
        const double memory = checkpoint_bytes(path) / (1 << 20);
        const std::string name = path.stem().string();
        std::printf("%-16s %4d frames  edit p50 %6.1f ms  max %6.1f ms  scrub max %6.1f ms  "
                    "checkpoints %6.2f MiB\n",
                    name.c_str(), frames, percentile(own, 0.5), percentile(own, 1.0),
                    percentile(scrubs, 1.0), memory);
        results.append(
            {name, "edit_p50", discreel::bench::csv_number(percentile(own, 0.5), 1), "ms"});
        results.append({name, "checkpoints", discreel::bench::csv_number(memory, 2), "MiB"});
    }
    const std::string rain = read_text(fs::path(DISCREEL_SOURCE_DIR) / "configs" / "rain.yaml");
    for (int round = 0; round < 3; ++round) {
        const json minute = {{"video.duration", 60}};
        type(rain, 240, "studio-bench", "typing_long", edit_number, minute);
        type(rain, 240, nullptr, "typing_long_untabbed", edit_number, minute);
    }
    for (const char* kind : {"edit", "scrub", "play", "typing", "typing_untabbed", "typing_long",
                             "typing_long_untabbed"}) {
        const double p50 = percentile(ms[kind], 0.5), p99 = percentile(ms[kind], 0.99);
        std::printf("%-20s p50 %6.1f ms  p99 %6.1f ms  (%zu requests)\n", kind, p50, p99,
                    ms[kind].size());
        for (const auto& [name, value] : {std::pair{"_p50", p50}, std::pair{"_p99", p99}}) {
            results.append({"all", std::string(kind) + name,
                            discreel::bench::csv_number(value, 1), "ms"});
        }
    }
    std::error_code ignored;
    fs::remove_all(data, ignored);
    return 0;
}
