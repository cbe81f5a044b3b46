#pragma once
// The jobs a server knows: their state in memory (the store holds what must survive), the
// queue, and the workers that render them, each with a warm GL context.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "discreel/serve.hpp"
#include "callbacks.hpp"
#include "metrics.hpp"
#include "request.hpp"
#include "store.hpp"

namespace discreel::serve {

struct Job {
    std::string id;
    JobStatus status = JobStatus::queued;
    int frames_done = 0;
    int frames_total = 0;
    std::optional<std::string> error;
    std::optional<OutputInfo> output;
    std::map<std::string, OutputInfo> extras;          // side outputs by name (request.hpp)
    // The scene's warnings: [{"line", "column", "message"}, ...] (request.hpp, PlannedJob).
    nlohmann::json warnings = nlohmann::json::array();
    std::uint64_t version = 0;                         // bumped on every change
    std::uint64_t seq = 0;                             // order of first acceptance
    std::int64_t created = 0;                          // Unix seconds of its last acceptance
    std::shared_ptr<std::atomic<bool>> cancel = std::make_shared<std::atomic<bool>>(false);
};

nlohmann::json job_json(const Job& job);   // the body GET /v1/renders/<id> answers

// One JSON line on standard error: {"time": ..., "event": ..., fields...}.
void log_line(const std::string& event, const nlohmann::json& fields);

// What POST /v1/renders did with a request.
enum class Submitted { accepted, existing, cached, busy, store_failed };

// nlohmann::json's move constructor is noexcept; the check follows the assertions inside it.
// NOLINTNEXTLINE(bugprone-exception-escape)
struct Submission {
    Submitted what = Submitted::accepted;
    nlohmann::json job;          // the job, for accepted, existing and cached
    int retry_after = 1;         // seconds, for busy
    std::string error;           // store_failed
};

class Jobs {
public:
    // Loads the store; every job accepted and not finished is queued again, in its order.
    static Expected<std::unique_ptr<Jobs>> open(const ServeDef& def, Metrics& metrics);
    ~Jobs();

    void start_workers();
    void stop();                 // workers end; a job being rendered stays queued in the store

    // `warnings`: the scene's (PlannedJob), kept with the job.
    Submission submit(const JobRequest& request, int frames_total, const nlohmann::json& warnings);
    std::optional<nlohmann::json> get(const std::string& id);
    // A succeeded job's output opened for reading, under the lock the sweeper deletes under:
    // once open, its bytes stay readable whatever the sweeper does. fd -1: it cannot be opened;
    // nullopt: there is no output (yet).
    struct OpenOutput {
        int fd = -1;
        OutputInfo info;
    };
    // Whether job `id` asked for side output `name` (it need not have succeeded yet).
    bool has_output(const std::string& id, const std::string& name);
    // `name`: "output" for the main one, or a side output's name.
    std::optional<OpenOutput> open_output(const std::string& id, const std::string& name);
    // GET /v1/renders: jobs newest first, at most `limit`, only of `state` when given, only
    // those listed after the job `before` (the previous page's "next"); null when there is no
    // job `before`.
    nlohmann::json list(const std::optional<JobStatus>& state, std::size_t limit,
                        const std::optional<std::string>& before);
    // One pass of the sweeper at `now` (Unix seconds); what it deleted.
    struct Swept {
        std::size_t jobs = 0;
        std::uint64_t bytes = 0;
    };
    Swept sweep(std::int64_t now);
    // DELETE: 404 unknown, 409 finished, otherwise cancelled (waits for a running job to stop,
    // which it does within a physics step; 202 if it has not after a few seconds).
    std::pair<int, nlohmann::json> cancel(const std::string& id);
    // The job now, its version (bumped on every change) and whether it is final; nullopt for
    // an unknown id.
    struct Snapshot {
        nlohmann::json job;
        std::uint64_t version = 0;
        bool final = false;
    };
    std::optional<Snapshot> snapshot(const std::string& id);
    // Calls `wake` after every change of job `id`, and at stop(), until unwatch(the handle).
    // `wake` runs with the jobs' lock held: it must only hand the news on (post, notify).
    std::uint64_t watch(const std::string& id, std::function<void()> wake);
    void unwatch(std::uint64_t handle);
    bool stopping() const { return stopping_; }
    std::size_t queued() const;
    std::size_t running() const;

private:
    Jobs(const ServeDef& def, Metrics& metrics, Store store);
    void worker_loop();
    void sweeper_loop();
    // Forgets a finished job, and its output where no other job has it; with mutex_ held.
    void forget(const std::string& id, Swept& swept);
    // Whether a job kept keeps the file of `info` (its main output or a side one).
    bool referenced(const OutputInfo& info) const;
    void run_job(const std::string& id, std::optional<render::Renderer>& warm);
    void changed(Job& job);      // with mutex_ held
    void counted();              // with mutex_ held: queued_count_, running_count_ from the queue
    // Moves a finished file into outputs/ under its hash; `stored` gains its name, which the
    // sweeper leaves alone until the job is recorded (storing_).
    Expected<OutputInfo> keep_output(const std::string& tmp, const std::string& extension,
                                     std::vector<std::string>& stored);

    ServeDef def_;
    Metrics& metrics_;
    StoreLock lock_;
    Store store_;
    std::filesystem::path outputs_, tmp_;
    mutable std::mutex mutex_;   // guards what follows
    std::condition_variable work_ready_, changed_;
    std::map<std::string, Job> jobs_;
    struct Watch {
        std::string id;
        std::function<void()> wake;
    };
    std::map<std::uint64_t, Watch> watches_;
    std::uint64_t next_watch_ = 1;
    std::deque<std::string> queue_;
    std::size_t running_ = 0;
    std::atomic<std::size_t> queued_count_{0}, running_count_{0};
    double mean_seconds_ = 1;    // of recent jobs, for Retry-After
    std::atomic<bool> stopping_{false};
    std::vector<std::thread> workers_;
    std::thread sweeper_;
    std::unique_ptr<Callbacks> callbacks_;
    // The job's callback, from its stored request; nullopt when it has none.
    std::optional<CallbackUrl> callback_of(const std::string& id);
    // Hands a job that reached a final status to its callback; with mutex_ held.
    void call_back(const Job& job, const std::optional<CallbackUrl>& url);
    std::condition_variable sweeper_wake_;
    std::uint64_t last_seq_ = 0;
    // Outputs moved into outputs/ by jobs not yet recorded as succeeded, by file name: the
    // sweeper must not take a file another job shares while that job is still storing it.
    std::map<std::string, int> storing_;
};

}  // namespace discreel::serve
