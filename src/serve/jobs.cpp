#include "jobs.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>
#include <iostream>

#include "digest.hpp"
#include "tar.hpp"
#include "discreel/job.hpp"
#include "discreel/printable.hpp"
#include "discreel/render.hpp"

namespace discreel::serve {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::int64_t unix_now() {
    return std::chrono::duration_cast<std::chrono::seconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::string utc_now() {
    const auto now = std::chrono::system_clock::now();
    const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                        now.time_since_epoch()).count() % 1000;
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[64];
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                  utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                  static_cast<int>(ms));
    return text;
}

// The directory entry of a renamed file is durable only once its directory is synced.
void sync_directory(const std::filesystem::path& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)fsync(fd);
    ::close(fd);
}

// A job's error must not show the server's own paths: the temporary output is "the output".
std::string without_path(std::string message, const std::string& path) {
    for (std::size_t at = 0; (at = message.find(path, at)) != std::string::npos;) {
        message.replace(at, path.size(), "the output");
    }
    return message;
}

// What a server leaves in DATA/tmp: a job's directory, named by its 32-digit id (and, from
// earlier versions, files named after the id). Nothing else there is the server's to delete.
bool is_job_temporary(const std::string& name) {
    std::string_view id = name;
    if (!id.empty() && id.front() == '.') id.remove_prefix(1);
    if (id.size() < 32) return false;
    for (std::size_t i = 0; i < 32; ++i) {
        const char c = id[i];
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
    }
    return id.size() == 32 || id[32] == '.';
}

Submission answer(Submitted what, json job) {
    Submission submission;
    submission.what = what;
    submission.job = std::move(job);
    return submission;
}

}  // namespace

Status check_data_dir(const std::string& dir) {
    if (dir.empty()) {
        return Error{"--data must name a directory; an empty one means none (use --data . for "
                     "this one)"};
    }
    const std::filesystem::path data(dir);
    std::error_code failed;
    const auto status = std::filesystem::status(data, failed);
    if (!std::filesystem::exists(status)) return {};   // created when the server opens it
    if (!std::filesystem::is_directory(status)) {
        return Error{"--data '" + dir + "' is not a directory"};
    }
    if (std::filesystem::exists(data / "jobs.sqlite3", failed)) return {};
    const std::filesystem::directory_iterator entries(data, failed);
    if (failed) return Error{"cannot read --data '" + dir + "': " + failed.message()};
    if (entries != std::filesystem::directory_iterator()) {
        return Error{"--data '" + dir + "' holds files but no job store (jobs.sqlite3): give "
                     "serve a new or empty directory, or the --data of an earlier server"};
    }
    return {};
}

json job_json(const Job& job) {
    json output = nullptr;
    if (job.status == JobStatus::succeeded && job.output) {
        output = {{"url", "/v1/renders/" + job.id + "/output"},
                  {"bytes", job.output->bytes},
                  {"sha256", job.output->sha256},
                  {"content_type", content_type_of(job.output->extension)}};
    }
    json error = nullptr;
    if (job.error) error = {{"message", *job.error}};
    json answer = {{"id", job.id},
                   {"status", to_string(job.status)},
                   {"progress",
                    {{"frames_done", job.frames_done}, {"frames_total", job.frames_total}}},
                   {"error", error},
                   {"output", output},
                   {"warnings", job.warnings}};
    if (job.status == JobStatus::succeeded && !job.extras.empty()) {
        json outputs = json::object();
        for (const auto& [name, info] : job.extras) {
            outputs[name] = {{"url", "/v1/renders/" + job.id + "/" + name},
                             {"bytes", info.bytes},
                             {"sha256", info.sha256},
                             {"content_type", content_type_of(info.extension)}};
        }
        answer["outputs"] = std::move(outputs);
    }
    return answer;
}

void log_line(const std::string& event, const json& fields) {
    static std::mutex mutex;
    json line = {{"time", utc_now()}, {"event", event}};
    line.update(fields);
    const std::string text = line.dump(-1, ' ', false, json::error_handler_t::replace) + '\n';
    std::lock_guard lock(mutex);
    std::cerr << text << std::flush;
}

Jobs::Jobs(const ServeDef& def, Metrics& metrics, Store store)
    : def_(def), metrics_(metrics), store_(std::move(store)),
      outputs_(std::filesystem::path(def.data_dir) / "outputs"),
      tmp_(std::filesystem::path(def.data_dir) / "tmp") {}

Jobs::~Jobs() { stop(); }

Expected<std::unique_ptr<Jobs>> Jobs::open(const ServeDef& def, Metrics& metrics) {
    if (Status usable = check_data_dir(def.data_dir); !usable) return usable.error();
    const std::filesystem::path data(def.data_dir);
    std::error_code failed;
    for (const char* sub : {"outputs", "tmp"}) {
        std::filesystem::create_directories(data / sub, failed);
        if (failed) {
            return Error{"cannot create '" + (data / sub).string() + "': " + failed.message()};
        }
    }
    // Before anything in the directory is touched: one server per store.
    auto lock = StoreLock::take(data / "serve.lock");
    if (!lock) return lock.error();
    // What a killed server was writing is rendered again from the start. Only what a server
    // makes there goes: a job's own directory, named by its id.
    for (const auto& entry : std::filesystem::directory_iterator(data / "tmp", failed)) {
        if (is_job_temporary(entry.path().filename().string())) {
            std::filesystem::remove_all(entry.path(), failed);
        }
    }
    auto store = Store::open((data / "jobs.sqlite3").string());
    if (!store) return store.error();
    auto loaded = store->load();
    if (!loaded) return loaded.error();
    std::unique_ptr<Jobs> jobs(new Jobs(def, metrics, std::move(*store)));
    jobs->callbacks_ = std::make_unique<Callbacks>(CallbackPolicy{.first_wait = def.callback_retry});
    jobs->lock_ = std::move(*lock);
    for (StoredJob& stored : *loaded) {
        Job job{.id = stored.id,
                .status = stored.status,
                .frames_done = stored.status == JobStatus::succeeded ? stored.frames_total : 0,
                .frames_total = stored.frames_total,
                .error = std::move(stored.error),
                .output = std::move(stored.output),
                .extras = {},
                .warnings = json::parse(stored.warnings, nullptr, false),
                .version = 1};
        if (!job.warnings.is_array()) job.warnings = json::array();
        const json extras = json::parse(stored.extras, nullptr, false);
        if (extras.is_object()) {
            for (const auto& [name, info] : extras.items()) {
                job.extras[name] = OutputInfo{.sha256 = info.value("sha256", ""),
                                              .bytes = info.value("bytes", std::int64_t{0}),
                                              .extension = info.value("extension", "")};
            }
        }
        job.seq = ++jobs->last_seq_;
        // A store from before jobs had a time: its jobs count from this start.
        job.created = stored.created > 0 ? stored.created : unix_now();
        if (!is_final(job.status)) {
            job.status = JobStatus::queued;
            jobs->queue_.push_back(job.id);
        }
        jobs->jobs_.emplace(job.id, std::move(job));
    }
    jobs->counted();
    if (!jobs->queue_.empty()) {
        log_line("resume", {{"queued", jobs->queue_.size()}});
    }
    return jobs;
}

void Jobs::start_workers() {
    for (int i = 0; i < std::max(1, def_.workers); ++i) {
        workers_.emplace_back([this] { worker_loop(); });
    }
    if (def_.keep_seconds || def_.keep_bytes) sweeper_ = std::thread([this] { sweeper_loop(); });
}

void Jobs::stop() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        for (auto& [id, job] : jobs_) job.cancel->store(true);
        for (const auto& [handle, watch] : watches_) watch.wake();
    }
    work_ready_.notify_all();
    changed_.notify_all();
    sweeper_wake_.notify_all();
    for (std::thread& worker : workers_) worker.join();
    workers_.clear();
    if (sweeper_.joinable()) sweeper_.join();
    if (callbacks_) callbacks_->stop();
}

void Jobs::changed(Job& job) {
    ++job.version;
    changed_.notify_all();
    for (const auto& [handle, watch] : watches_) {
        if (watch.id == job.id) watch.wake();
    }
}

std::uint64_t Jobs::watch(const std::string& id, std::function<void()> wake) {
    std::lock_guard lock(mutex_);
    const std::uint64_t handle = next_watch_++;
    watches_.emplace(handle, Watch{id, std::move(wake)});
    return handle;
}

void Jobs::unwatch(std::uint64_t handle) {
    std::lock_guard lock(mutex_);
    watches_.erase(handle);
}

// Counted apart from the lock, which store writes (fsync) may hold: /healthz and /metrics
// answer at once.
std::size_t Jobs::queued() const { return queued_count_.load(); }

std::size_t Jobs::running() const { return running_count_.load(); }

void Jobs::counted() {
    queued_count_ = queue_.size();
    running_count_ = running_;
}

Submission Jobs::submit(const JobRequest& request, int frames_total, const json& warnings) {
    std::unique_lock lock(mutex_);
    const auto found = jobs_.find(request.id);
    if (found != jobs_.end()) {
        Job& job = found->second;
        if (job.status == JobStatus::queued || job.status == JobStatus::running) {
            return answer(Submitted::existing, job_json(job));
        }
        const auto kept = [&] {
            return std::filesystem::exists(outputs_ /
                                           (job.output->sha256 + "." + job.output->extension));
        };
        if (job.status == JobStatus::succeeded && job.output && kept()) {
            metrics_.cache_hit();
            return answer(Submitted::cached, job_json(job));
        }
        // Failed, cancelled, or its output gone: the same request runs again.
    }
    if (queue_.size() >= def_.max_queue) {
        metrics_.rejected_busy();
        const double wait = mean_seconds_ * static_cast<double>(queue_.size()) /
                            std::max(1, def_.workers);
        Submission busy = answer(Submitted::busy, nullptr);
        busy.retry_after = static_cast<int>(std::clamp(std::ceil(wait), 1.0, 3600.0));
        return busy;
    }
    // Durable before the answer: a 202 promises the job will finish.
    const std::int64_t now = unix_now();
    if (Status stored =
            store_.accept(request.id, request.stored(), frames_total, warnings.dump(), now);
        !stored) {
        Submission failed = answer(Submitted::store_failed, nullptr);
        failed.error = stored.error().message;
        return failed;
    }
    Job& job = jobs_[request.id];
    if (job.seq == 0) job.seq = ++last_seq_;
    job.created = now;
    job.id = request.id;
    job.status = JobStatus::queued;
    job.frames_done = 0;
    job.frames_total = frames_total;
    job.warnings = warnings;
    job.error.reset();
    job.output.reset();
    job.extras.clear();
    job.cancel = std::make_shared<std::atomic<bool>>(stopping_.load());
    changed(job);
    queue_.push_back(request.id);
    counted();
    metrics_.accepted();
    log_line("job", {{"id", job.id}, {"status", "queued"}});
    json accepted = job_json(job);
    lock.unlock();
    work_ready_.notify_one();
    return answer(Submitted::accepted, std::move(accepted));
}

std::optional<json> Jobs::get(const std::string& id) {
    std::lock_guard lock(mutex_);
    const auto found = jobs_.find(id);
    if (found == jobs_.end()) return std::nullopt;
    return job_json(found->second);
}

std::optional<CallbackUrl> Jobs::callback_of(const std::string& id) {
    auto text = store_.request(id);
    if (!text) return std::nullopt;
    const json request = json::parse(*text, nullptr, false);
    if (!request.is_object() || !request.contains("callback") || !request["callback"].is_string()) {
        return std::nullopt;
    }
    auto url = parse_callback_url(request["callback"].get<std::string>());
    if (!url) return std::nullopt;
    return *url;
}

void Jobs::call_back(const Job& job, const std::optional<CallbackUrl>& url) {
    if (!url || !callbacks_) return;
    // The allowance of this server, not the one that accepted the job (a restart may narrow it).
    const bool allowed = std::any_of(def_.callback_allow.begin(), def_.callback_allow.end(),
                                     [&](const std::string& host) {
                                         return lower_host(host) == url->host;
                                     });
    if (!allowed) {
        log_line("callback_refused", {{"id", job.id}, {"host", url->host}});
        return;
    }
    callbacks_->post(*url, job_json(job).dump(-1, ' ', false, json::error_handler_t::replace),
                     job.id);
}

bool Jobs::has_output(const std::string& id, const std::string& name) {
    {
        std::lock_guard lock(mutex_);
        const auto found = jobs_.find(id);
        if (found == jobs_.end()) return false;
        if (found->second.extras.count(name) > 0) return true;
        if (found->second.status == JobStatus::succeeded) return false;
    }
    // Not done yet: what it asked for is in its request.
    auto text = store_.request(id);
    if (!text) return false;
    const json request = json::parse(*text, nullptr, false);
    if (!request.is_object() || !request.contains("outputs") || !request["outputs"].is_array()) {
        return false;
    }
    for (const auto& item : request["outputs"]) {
        if (item.is_string() && item.get<std::string>() == name) return true;
    }
    return false;
}

std::optional<Jobs::OpenOutput> Jobs::open_output(const std::string& id,
                                                  const std::string& name) {
    std::lock_guard lock(mutex_);
    const auto found = jobs_.find(id);
    if (found == jobs_.end() || found->second.status != JobStatus::succeeded ||
        !found->second.output) {
        return std::nullopt;
    }
    const Job& job = found->second;
    const auto extra = job.extras.find(name);
    if (name != "output" && extra == job.extras.end()) return std::nullopt;
    const OutputInfo& info = name == "output" ? *job.output : extra->second;
    const auto path = outputs_ / (info.sha256 + "." + info.extension);
    return OpenOutput{::open(path.c_str(), O_RDONLY | O_CLOEXEC), info};
}

json Jobs::list(const std::optional<JobStatus>& state, std::size_t limit,
                const std::optional<std::string>& before) {
    std::lock_guard lock(mutex_);
    std::vector<const Job*> all;
    for (const auto& [id, job] : jobs_) all.push_back(&job);
    // Newest first: by time of acceptance, then by order of acceptance.
    std::sort(all.begin(), all.end(), [](const Job* a, const Job* b) {
        return a->created != b->created ? a->created > b->created : a->seq > b->seq;
    });
    auto from = all.begin();
    if (before) {
        from = std::find_if(all.begin(), all.end(), [&](const Job* j) { return j->id == *before; });
        if (from == all.end()) return nullptr;   // no such job (any more)
        ++from;
    }
    json page = json::array();
    std::optional<std::string> last;
    bool more = false;
    for (auto it = from; it != all.end(); ++it) {
        if (state && (*it)->status != *state) continue;
        if (page.size() == limit) {
            more = true;
            break;
        }
        json entry = job_json(**it);
        entry["created"] = (*it)->created;
        page.push_back(std::move(entry));
        last = (*it)->id;
    }
    return {{"jobs", std::move(page)}, {"next", more && last ? json(*last) : json(nullptr)}};
}

void Jobs::forget(const std::string& id, Swept& swept) {
    const auto found = jobs_.find(id);
    if (found == jobs_.end()) return;
    if (Status removed = store_.remove(id); !removed) {
        log_line("store_error", {{"id", id}, {"message", removed.error().message}});
        return;
    }
    std::vector<OutputInfo> files;
    if (found->second.output) files.push_back(*found->second.output);
    for (const auto& [name, info] : found->second.extras) files.push_back(info);
    jobs_.erase(found);
    ++swept.jobs;
    for (const OutputInfo& file : files) {
        // Outputs are kept by content: another job may have the same bytes.
        if (referenced(file)) continue;
        std::error_code failed;
        if (std::filesystem::remove(outputs_ / (file.sha256 + "." + file.extension), failed)) {
            swept.bytes += static_cast<std::uint64_t>(file.bytes);
        }
    }
}

bool Jobs::referenced(const OutputInfo& info) const {
    if (storing_.count(info.sha256 + "." + info.extension) > 0) return true;
    const auto same = [&](const OutputInfo& other) {
        return other.sha256 == info.sha256 && other.extension == info.extension;
    };
    for (const auto& [id, job] : jobs_) {
        if (job.output && same(*job.output)) return true;
        for (const auto& [name, extra] : job.extras) {
            if (same(extra)) return true;
        }
    }
    return false;
}

Jobs::Swept Jobs::sweep(std::int64_t now) {
    std::lock_guard lock(mutex_);
    Swept swept;
    std::vector<std::pair<std::int64_t, std::string>> finished;   // oldest first
    for (const auto& [id, job] : jobs_) {
        if (is_final(job.status)) finished.emplace_back(job.created, id);
    }
    std::sort(finished.begin(), finished.end());
    std::size_t next = 0;
    if (def_.keep_seconds) {
        const auto oldest = static_cast<double>(now) - *def_.keep_seconds;
        for (; next < finished.size() && static_cast<double>(finished[next].first) < oldest;
             ++next) {
            forget(finished[next].second, swept);
        }
    }
    if (def_.keep_bytes) {
        const auto kept = [&] {
            std::uint64_t total = 0;
            std::map<std::string, std::uint64_t> files;   // each output once
            for (const auto& [id, job] : jobs_) {
                if (job.output) {
                    files[job.output->sha256 + "." + job.output->extension] =
                        static_cast<std::uint64_t>(job.output->bytes);
                }
                for (const auto& [name, extra] : job.extras) {
                    files[extra.sha256 + "." + extra.extension] =
                        static_cast<std::uint64_t>(extra.bytes);
                }
            }
            for (const auto& [name, bytes] : files) total += bytes;
            return total;
        };
        for (; next < finished.size() && kept() > *def_.keep_bytes; ++next) {
            forget(finished[next].second, swept);
        }
    }
    if (swept.jobs > 0) {
        metrics_.swept(swept.jobs, swept.bytes);
        log_line("sweep", {{"jobs", swept.jobs}, {"bytes", swept.bytes}});
    }
    return swept;
}

void Jobs::sweeper_loop() {
    // Often enough that nothing outlives its time by more than a tenth of it (at most a
    // minute), and outputs pass their size cap for a second at most.
    double interval = def_.keep_seconds ? std::clamp(*def_.keep_seconds / 10, 0.2, 60.0) : 60.0;
    if (def_.keep_bytes) interval = std::min(interval, 1.0);
    std::unique_lock lock(mutex_);
    while (!stopping_) {
        sweeper_wake_.wait_for(lock, std::chrono::duration<double>(interval),
                               [&] { return stopping_.load(); });
        if (stopping_) return;
        lock.unlock();
        sweep(unix_now());
        lock.lock();
    }
}

std::pair<int, json> Jobs::cancel(const std::string& id) {
    std::unique_lock lock(mutex_);
    auto found = jobs_.find(id);
    if (found == jobs_.end()) return {404, {{"error", {{"message", "no job " + id}}}}};
    Job& job = found->second;
    if (is_final(job.status)) {
        return {409, {{"error", {{"message", std::string("the job has ") +
                                                 (job.status == JobStatus::succeeded
                                                      ? "succeeded"
                                                      : job.status == JobStatus::failed
                                                            ? "failed"
                                                            : "been cancelled") +
                                                 "; there is nothing to cancel"}}}}};
    }
    if (job.status == JobStatus::queued) {
        // The store first: if it cannot be written, the job stays queued, in memory as on disk.
        if (Status stored = store_.set_ended(id, JobStatus::cancelled, "cancelled"); !stored) {
            return {503, {{"error", {{"message", "cannot cancel the job: " +
                                                      stored.error().message}}}}};
        }
        queue_.erase(std::remove(queue_.begin(), queue_.end(), id), queue_.end());
        counted();
        job.status = JobStatus::cancelled;
        job.error = "cancelled";
        metrics_.ended("cancelled", 0);
        log_line("job", {{"id", id}, {"status", "cancelled"}});
        changed(job);
        call_back(job, callback_of(id));
        return {200, job_json(job)};
    }
    job.cancel->store(true);
    // The worker stops within a physics step; a slow one is waited for, but not for ever.
    // The sweeper may forget it as soon as it is final: looked up again, never assumed.
    const auto final_or_gone = [&] {
        const auto now = jobs_.find(id);
        return now == jobs_.end() || is_final(now->second.status);
    };
    changed_.wait_for(lock, std::chrono::seconds(5), [&] { return final_or_gone() || stopping_; });
    const auto now = jobs_.find(id);
    if (now == jobs_.end()) return {200, {{"id", id}, {"status", "cancelled"}}};
    return {is_final(now->second.status) ? 200 : 202, job_json(now->second)};
}

std::optional<Jobs::Snapshot> Jobs::snapshot(const std::string& id) {
    std::lock_guard lock(mutex_);
    auto found = jobs_.find(id);
    if (found == jobs_.end()) return std::nullopt;
    const Job& job = found->second;
    return Snapshot{job_json(job), job.version, is_final(job.status)};
}

void Jobs::worker_loop() {
    // Kept from job to job: the context, its compiled shaders and llvmpipe's JIT output.
    std::optional<render::Renderer> warm;
    for (;;) {
        std::string id;
        {
            std::unique_lock lock(mutex_);
            work_ready_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            id = queue_.front();
            queue_.pop_front();
            Job& job = jobs_.at(id);
            job.status = JobStatus::running;
            ++running_;
            counted();
            changed(job);
        }
        if (Status stored = store_.set_running(id); !stored) {
            log_line("store_error", {{"id", id}, {"message", stored.error().message}});
        }
        log_line("job", {{"id", id}, {"status", "running"}});
        run_job(id, warm);
        std::lock_guard lock(mutex_);
        --running_;
        counted();
    }
}

Expected<OutputInfo> Jobs::keep_output(const std::string& tmp, const std::string& extension,
                                       std::vector<std::string>& stored) {
    auto sha = sha256_hex_of_file(tmp);
    if (!sha) return sha.error();
    std::error_code failed;
    const auto bytes = std::filesystem::file_size(tmp, failed);
    if (failed) return Error{"cannot read the output: " + failed.message()};
    // Content-addressed: the same bytes are kept once, whichever job made them. Named as being
    // stored before the rename: a sweep that forgets another job of the same bytes keeps it.
    const std::string name = *sha + "." + extension;
    {
        std::lock_guard lock(mutex_);
        ++storing_[name];
    }
    stored.push_back(name);
    const std::filesystem::path target = outputs_ / name;
    std::filesystem::rename(tmp, target, failed);
    if (failed) return Error{"cannot keep the output: " + failed.message()};
    sync_directory(outputs_);
    return OutputInfo{.sha256 = *sha, .bytes = static_cast<std::int64_t>(bytes),
                      .extension = extension};
}

void Jobs::run_job(const std::string& id, std::optional<render::Renderer>& warm) {
    const auto started = Clock::now();
    std::shared_ptr<std::atomic<bool>> cancel;
    {
        std::lock_guard lock(mutex_);
        cancel = jobs_.at(id).cancel;
    }
    // The job's own directory: everything its render writes, temporaries included.
    const std::string tmp = (tmp_ / id).string();
    std::error_code made;
    std::filesystem::create_directories(tmp, made);
    std::atomic<bool> timed_out{false};   // set by whichever stage polls should_stop
    struct Kept {
        OutputInfo output;
        std::map<std::string, OutputInfo> extras;
    };
    std::optional<CallbackUrl> callback;
    std::vector<std::string> stored_files;   // names in storing_, released below
    const auto outcome = [&]() -> Expected<Kept> {
        auto text = store_.request(id);
        if (!text) return text.error();
        auto parsed = parse_job_request(*text, def_.limits, def_.version);
        if (auto* refused = std::get_if<Refusal>(&parsed)) {
            return Error{refused->body["error"]["message"].get<std::string>()};
        }
        const JobRequest& request = std::get<JobRequest>(parsed);
        callback = request.callback;
        auto planned = plan_job(request, def_.limits);
        if (auto* refused = std::get_if<Refusal>(&planned)) {
            return Error{refused->body["errors"][0]["message"].get<std::string>()};
        }
        job::RenderPlan& plan = std::get<PlannedJob>(planned).plan;
        const render::RendererDef size{.width = plan.scene.video.width,
                                       .height = plan.scene.video.height};
        if (!warm || warm->def().width != size.width || warm->def().height != size.height) {
            warm.reset();
            auto made = render::Renderer::create(size);
            if (!made) return made.error();
            warm = std::move(*made);
        }
        const auto deadline = started + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(def_.job_timeout));
        job::RenderDef def;
        def.plan = std::move(plan);
        def.plan.sink.path = tmp + "/render." + request.format;
        def.renderer = &*warm;
        // Side outputs, each a file of the job's directory (the masks a directory, archived).
        const auto side = [&](const std::string& name) -> std::optional<std::string> {
            if (std::find(request.extras.begin(), request.extras.end(), name) ==
                request.extras.end()) {
                return std::nullopt;
            }
            return tmp + "/" + name + (name == "masks" ? "" : std::string(".") + extension_of(name));
        };
        def.trace = side("trace");
        def.events = side("events");
        def.joints = side("joints");
        def.truth = {.shapes = side("shapes"),
                     .camera = side("camera"),
                     .masks = side("masks"),
                     .boxes = side("boxes")};
        if (def.truth.masks) std::filesystem::create_directories(*def.truth.masks, made);
        // One segment at a time: the service's parallelism is its workers, each on its warm
        // renderer. The bytes are those of any --jobs.
        def.jobs = 1;
        def.on_progress = [&](const job::Progress& p) {
            std::lock_guard lock(mutex_);
            Job& job = jobs_.at(id);
            job.frames_done = p.frames_done;
            job.frames_total = p.frames_total;
            changed(job);
        };
        def.should_stop = [&] {
            if (Clock::now() > deadline) timed_out = true;
            return cancel->load() || timed_out.load();
        };
        // A warning of the run (a body that left its walls) joins the scene's, placed nowhere.
        def.on_warning = [&](const std::string& message) {
            std::lock_guard lock(mutex_);
            Job& job = jobs_.at(id);
            job.warnings.push_back({{"line", nullptr}, {"column", nullptr}, {"message", message}});
            changed(job);
        };
        auto rendered = job::render(def);
        if (!rendered) return rendered.error();
        Kept kept;
        for (const std::string& name : request.extras) {
            std::string file = *side(name);
            if (name == "masks") {
                if (Status archived = write_tar(file, "masks", tmp + "/masks.tar"); !archived) {
                    return archived.error();
                }
                file = tmp + "/masks.tar";
            }
            auto extra = keep_output(file, extension_of(name), stored_files);
            if (!extra) return extra.error();
            kept.extras[name] = *extra;
        }
        auto output = keep_output(def.plan.sink.path, request.format, stored_files);
        if (!output) return output.error();
        kept.output = *output;
        return kept;
    }();
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);

    std::lock_guard lock(mutex_);
    // Recorded below (or failed): the sweeper judges these files by the jobs from now on.
    for (const std::string& name : stored_files) {
        if (--storing_[name] == 0) storing_.erase(name);
    }
    Job& job = jobs_.at(id);
    if (stopping_ && !outcome && !timed_out) {
        // Shutting down: the store still says running, so the next server renders it again.
        job.status = JobStatus::queued;
        changed(job);
        return;
    }
    Status stored;
    if (outcome) {
        job.status = JobStatus::succeeded;
        job.output = outcome->output;
        job.extras = outcome->extras;
        job.frames_done = job.frames_total;
        json extras = json::object();
        for (const auto& [name, info] : outcome->extras) {
            extras[name] = {{"sha256", info.sha256}, {"bytes", info.bytes},
                            {"extension", info.extension}};
        }
        stored = store_.set_succeeded(id, outcome->output, extras.dump());
        mean_seconds_ = 0.8 * mean_seconds_ + 0.2 * seconds;
    } else {
        const bool cancelled = cancel->load() && !timed_out;
        job.status = cancelled ? JobStatus::cancelled : JobStatus::failed;
        // Temporaries are named after the output's path: the job's directory stands for all.
        std::string message = without_path(outcome.error().message, tmp + "/render");
        message = without_path(std::move(message), tmp);
        if (timed_out) {
            std::string limit;
            append_number(limit, def_.job_timeout);
            message = "the render took longer than the limit of " + limit +
                      " s (--job-timeout); nothing was kept";
        }
        if (cancelled) message = "cancelled";
        job.error = message;
        stored = store_.set_ended(id, job.status, message);
    }
    if (!stored) log_line("store_error", {{"id", id}, {"message", stored.error().message}});
    metrics_.ended(to_string(job.status), seconds);
    json fields = {{"id", id}, {"status", to_string(job.status)}, {"seconds", seconds}};
    if (job.error) fields["error"] = *job.error;
    log_line("job", fields);
    changed(job);
    call_back(job, callback);
}

}  // namespace discreel::serve
