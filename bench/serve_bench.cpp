// serve_bench: the service against the command line on 320x180 stills (docs/serve.md, "Speed").
//   1. submit-to-done latency with one warm worker: each still a new job (a distinct scene), the
//      time from POST to the final event of its stream; p50 and p99;
//   2. throughput: 40 clients at once, --workers 2, each sending stills one after another;
//   3. the command line: `discreel render scene.yaml -o still.png`, one process per still.
// The server runs in this process (serve::Server) on 127.0.0.1 with a temporary --data.
// Appends to bench/results/serve_bench.csv.
#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench_results.hpp"
#include "discreel/serve.hpp"

namespace {

using discreel::bench::percentile;

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string scene_text(int n) {
    return "# still " + std::to_string(n) +
           "\nversion: 1\nvideo:\n  size: [320, 180]\n  fps: 30\n  duration: 1\n"
           "walls:\n  - box: [[0, 0], [3.2, 1.8]]\ndiscs:\n  - random:\n      count: 30\n"
           "      region: [[0.2, 0.2], [3.0, 1.6]]\n      radius: [0.05, 0.12]\n";
}

// Submits still `n` and reads its event stream to the end; seconds, or a negative number when
// it did not succeed.
double render_still(httplib::Client& client, int n) {
    const auto start = Clock::now();
    auto accepted = client.Post("/v1/renders",
                                json{{"scene", scene_text(n)}, {"output", "png"}}.dump(),
                                "application/json");
    if (!accepted || (accepted->status != 202 && accepted->status != 200)) return -1;
    const std::string id = json::parse(accepted->body)["id"];
    std::string stream;
    auto events = client.Get("/v1/renders/" + id + "/events",
                             [&](const char* data, std::size_t size) {
                                 stream.append(data, size);
                                 return true;
                             });
    if (events && events->status == 200) {
        if (stream.find("\"status\":\"succeeded\"") == std::string::npos) return -1;
        return seconds_since(start);
    }
    // Too many streams open at once (503): poll, as the web page does.
    for (int polls = 0; polls < 60000; ++polls) {
        auto job = client.Get("/v1/renders/" + id);
        if (!job) return -1;
        const std::string status = json::parse(job->body)["status"];
        if (status == "succeeded") return seconds_since(start);
        if (status == "failed" || status == "cancelled") return -1;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return -1;
}

struct Running {
    discreel::serve::Server server;
    std::thread thread;
    ~Running() {
        server.stop();
        thread.join();
    }
};

std::unique_ptr<Running> start(const std::filesystem::path& data, int workers) {
    discreel::serve::ServeDef def;
    def.port = 0;
    def.data_dir = data.string();
    def.workers = workers;
    def.max_queue = 1000;
    def.version = "bench";
    def.log_requests = false;
    auto server = discreel::serve::Server::open(def);
    if (!server) {
        std::fprintf(stderr, "serve_bench: %s\n", server.error().message.c_str());
        std::exit(1);
    }
    auto running = std::unique_ptr<Running>(new Running{std::move(*server), {}});
    running->thread = std::thread([r = running.get()] { (void)r->server.run(); });
    return running;
}

httplib::Client client_for(int port) {
    httplib::Client client("127.0.0.1", port);
    client.set_read_timeout(60);
    return client;
}

}  // namespace

int main(int argc, char** argv) {
    const int stills = argc > 1 ? std::atoi(argv[1]) : 60;
    const auto dir = std::filesystem::temp_directory_path() /
                     ("serve_bench_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // Job transitions log a line each; the bench measures the service, not the terminal.
    std::freopen("/dev/null", "w", stderr);
    discreel::bench::ResultsFile results("serve_bench", {"measure", "workers", "clients",
                                                         "stills", "value", "unit"});
    const auto report = [&](const char* measure, int workers, int clients, int count,
                            double value, const char* unit) {
        std::printf("%-34s workers %d clients %2d stills %4d: %8.1f %s\n", measure, workers,
                    clients, count, value, unit);
        results.append({measure, std::to_string(workers), std::to_string(clients),
                        std::to_string(count), discreel::bench::csv_number(value, 1), unit});
    };

    {   // 1. Latency, one warm worker, one client.
        auto running = start(dir / "latency", 1);
        auto client = client_for(running->server.port());
        render_still(client, -1);   // warms the worker: the context and llvmpipe's shaders
        std::vector<double> times;
        for (int n = 0; n < stills; ++n) {
            const double s = render_still(client, n);
            if (s < 0) return std::fprintf(stdout, "serve_bench: still %d failed\n", n), 1;
            times.push_back(s * 1000);
        }
        report("submit_to_done_p50", 1, 1, stills, percentile(times, 0.5), "ms");
        report("submit_to_done_p99", 1, 1, stills, percentile(times, 0.99), "ms");
    }
    {   // 2. Throughput: 40 clients, two workers.
        auto running = start(dir / "throughput", 2);
        const int clients = 40, each = std::max(1, stills * 2 / clients);
        std::atomic<int> failed{0};
        const auto begun = Clock::now();
        std::vector<std::thread> threads;
        for (int c = 0; c < clients; ++c) {
            threads.emplace_back([&, c] {
                auto client = client_for(running->server.port());
                for (int k = 0; k < each; ++k) {
                    if (render_still(client, 100000 + c * each + k) < 0) ++failed;
                }
            });
        }
        for (auto& thread : threads) thread.join();
        const double wall = seconds_since(begun);
        if (failed > 0) return std::printf("serve_bench: %d stills failed\n", failed.load()), 1;
        report("stills_per_s_service", 2, clients, clients * each, clients * each / wall,
               "stills/s");
    }
    {   // 3. The command line, one process per still.
        const int count = std::max(5, stills / 4);
        const auto begun = Clock::now();
        for (int n = 0; n < count; ++n) {
            const auto scene = dir / "cli.yaml";
            std::FILE* file = std::fopen(scene.c_str(), "w");
            std::fputs(scene_text(200000 + n).c_str(), file);
            std::fclose(file);
            const std::string command = std::string(DISCREEL_BIN) + " render " + scene.string() +
                                        " -o " + (dir / "cli.png").string() + " -q";
            if (std::system(command.c_str()) != 0) return std::printf("serve_bench: CLI failed\n"), 1;
        }
        const double wall = seconds_since(begun);
        report("stills_per_s_cli", 1, 1, count, count / wall, "stills/s");
        report("cli_ms_per_still", 1, 1, count, 1000 * wall / count, "ms");
    }
    std::filesystem::remove_all(dir);
    if (!results.path().empty()) std::printf("appended to %s\n", results.path().c_str());
    return 0;
}
