#pragma once
// The job store: one SQLite database in the data directory (WAL, synchronous commits), so a
// job the server answered 202 for survives a crash of the process or the machine.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "discreel/expected.hpp"

struct sqlite3;

namespace discreel::serve {

enum class JobStatus { queued, running, succeeded, failed, cancelled };

const char* to_string(JobStatus status);
bool is_final(JobStatus status);

struct OutputInfo {
    std::string sha256;        // hex, of the file's bytes; names the file in outputs/
    std::int64_t bytes = 0;
    std::string extension;     // "mp4", "webm", "mkv", "gif", "png"
};

struct StoredJob {
    std::string id;
    JobStatus status = JobStatus::queued;
    int frames_total = 0;
    std::optional<std::string> error;     // failed, cancelled
    std::optional<OutputInfo> output;     // succeeded
    std::string warnings = "[]";          // the scene's warnings, a JSON array (job_json)
    std::int64_t created = 0;             // Unix seconds of its (last) acceptance; 0: unknown
    // Side outputs of a succeeded job (trace, masks, ...), a JSON object of
    // {"name": {"sha256", "bytes", "extension"}}.
    std::string extras = "{}";
};

// An exclusive lock on a store (flock on DATA/serve.lock), held while the object lives: a
// second server on the same --data is refused instead of deleting the first's files.
class StoreLock {
public:
    static Expected<StoreLock> take(const std::filesystem::path& path);
    StoreLock() = default;
    ~StoreLock();
    StoreLock(StoreLock&& other) noexcept;
    StoreLock& operator=(StoreLock&& other) noexcept;
    StoreLock(const StoreLock&) = delete;
    StoreLock& operator=(const StoreLock&) = delete;

private:
    explicit StoreLock(int fd) : fd_(fd) {}
    int fd_ = -1;
};

class Store {
public:
    // Opens or creates `path`; the schema is created if missing.
    static Expected<Store> open(const std::string& path);
    ~Store();
    Store(Store&&) noexcept;
    Store& operator=(Store&&) noexcept;

    // Every job, in the order they were first accepted.
    Expected<std::vector<StoredJob>> load();
    // The request JSON a job was accepted with.
    Expected<std::string> request(const std::string& id);

    // Accepts a job (new, or one that failed or was cancelled before): queued, durable when
    // this returns. `warnings`: the scene's, a JSON array.
    Status accept(const std::string& id, const std::string& request, int frames_total,
                  const std::string& warnings, std::int64_t created);
    // Forgets a job (the sweeper's): its row goes.
    Status remove(const std::string& id);
    Status set_running(const std::string& id);
    // `extras`: the side outputs, as StoredJob::extras.
    Status set_succeeded(const std::string& id, const OutputInfo& output,
                         const std::string& extras = "{}");
    Status set_ended(const std::string& id, JobStatus status, const std::string& error);

private:
    struct Closer {
        void operator()(sqlite3* db) const;
    };
    explicit Store(sqlite3* db);
    Status exec(const char* sql);
    Status update(const char* sql, const std::vector<std::optional<std::string>>& text,
                  const std::vector<std::int64_t>& numbers);

    std::unique_ptr<sqlite3, Closer> db_;
};

}  // namespace discreel::serve
