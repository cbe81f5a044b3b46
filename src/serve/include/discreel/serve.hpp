#pragma once
// discreel serve: the render-job layer behind HTTP. Requests become jobs in a durable store,
// workers with warm GL contexts render them through job::render (the bytes `discreel render`
// writes for the same scene and options), outputs are kept by content.
//     auto server = serve::Server::open({.data_dir = "data", .workers = 2});
//     server->run();            // blocks until stop(), from another thread or a signal
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "discreel/expected.hpp"
#include "discreel/scene.hpp"

namespace discreel::serve {

struct ServeDef {
    std::string host = "127.0.0.1";          // a numeric IPv4 or IPv6 address, not a name
    int port = 8080;                         // 0: any free port (see Server::port())
    // Host header names accepted besides the listen address (and localhost, for a loopback or
    // wildcard address): against DNS rebinding, any other is answered 421.
    std::vector<std::string> allow_hosts;
    std::string data_dir = "discreel-data";  // the job store and the outputs
    int workers = 1;                         // jobs rendered at once, each with a warm context
    std::size_t max_queue = 64;              // jobs waiting; beyond it 429 with Retry-After
    std::optional<std::string> token;        // if set, every /v1 request must bear it
    scene::Limits limits;                    // bound every scene, as on the command line
    double job_timeout = 600;                // seconds one job may render before it fails
    // Scenes the studio keeps playing between requests (/v1/studio, docs/serve.md "Studio"),
    // each with its checkpoints and a renderer of its preview size.
    std::size_t studio_sessions = 4;
    std::string version;                     // discreel's, part of every job id
    bool log_requests = true;                // one JSON line per request and job transition
    // Web origins ("https://app.example.com") whose pages may call the API from a browser:
    // preflights answered, Access-Control-Allow-Origin sent to them only. Empty: none.
    std::vector<std::string> cors_origins;
    // The sweeper: finished jobs accepted longer ago than keep_seconds are forgotten with their
    // outputs, and the oldest finished ones while the outputs take more than keep_bytes. A job
    // queued or running, and an output being sent, are never taken. Nullopt: no such bound.
    std::optional<double> keep_seconds = 7.0 * 24 * 3600;
    std::optional<std::uint64_t> keep_bytes;
    // Hosts a job's "callback" URL may name (as written in it: a name or an address); empty:
    // callbacks are refused.
    std::vector<std::string> callback_allow;
    // Waits between a callback's tries: the first, doubled after each failure (6 tries).
    std::chrono::milliseconds callback_retry{1000};
};

// Whether `dir` may be a server's --data: a new or empty directory, or one holding a job
// store. A directory with other files is refused (the server cleans its own temporaries there).
Status check_data_dir(const std::string& dir);

class Server {
public:
    // Opens (or creates) the store in def.data_dir, binds the address, and queues again every
    // job that was accepted and not finished when the last server on that store stopped.
    static Expected<Server> open(const ServeDef& def);
    ~Server();
    Server(Server&&) noexcept;
    Server& operator=(Server&&) noexcept;

    int port() const;               // the bound port
    Status run();                   // serves until stop(); then finishes nothing new
    void stop();                    // safe from any thread; running jobs stay queued in the store

private:
    struct Impl;
    explicit Server(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::serve
