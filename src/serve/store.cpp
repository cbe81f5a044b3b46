#include "store.hpp"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <utility>

namespace discreel::serve {
namespace {

struct StatementCloser {
    void operator()(sqlite3_stmt* statement) const { sqlite3_finalize(statement); }
};
using Statement = std::unique_ptr<sqlite3_stmt, StatementCloser>;

Error sqlite_error(sqlite3* db, const std::string& doing) {
    return Error{"cannot " + doing + ": " + sqlite3_errmsg(db)};
}

Expected<Statement> prepare(sqlite3* db, const char* sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db, sql, -1, &statement, nullptr) != SQLITE_OK) {
        return sqlite_error(db, "prepare a query of the job store");
    }
    return Statement(statement);
}

std::string column_text(sqlite3_stmt* statement, int column) {
    const auto* text = sqlite3_column_text(statement, column);
    return text == nullptr ? std::string() : reinterpret_cast<const char*>(text);
}

std::optional<std::string> optional_text(sqlite3_stmt* statement, int column) {
    if (sqlite3_column_type(statement, column) == SQLITE_NULL) return std::nullopt;
    return column_text(statement, column);
}

JobStatus status_of(const std::string& text) {
    if (text == "running") return JobStatus::running;
    if (text == "succeeded") return JobStatus::succeeded;
    if (text == "failed") return JobStatus::failed;
    if (text == "cancelled") return JobStatus::cancelled;
    return JobStatus::queued;
}

// seq keeps the order of first acceptance, which is the order jobs are queued again after a
// restart.
constexpr const char* schema = R"sql(
CREATE TABLE IF NOT EXISTS jobs (
    seq INTEGER PRIMARY KEY AUTOINCREMENT,
    id TEXT NOT NULL UNIQUE,
    request TEXT NOT NULL,
    status TEXT NOT NULL,
    frames_total INTEGER NOT NULL,
    error TEXT,
    sha256 TEXT,
    bytes INTEGER,
    extension TEXT,
    warnings TEXT,
    created INTEGER,
    extras TEXT
);
)sql";

// Whether the jobs table has `column`: a store written before jobs had warnings or a time of
// acceptance gets the column added (NULL there: none known).
Expected<bool> has_column(sqlite3* db, const std::string& column) {
    auto statement = prepare(db, "PRAGMA table_info(jobs)");
    if (!statement) return statement.error();
    bool found = false;
    while (sqlite3_step(statement->get()) == SQLITE_ROW) {
        found = found || column_text(statement->get(), 1) == column;
    }
    return found;
}

}  // namespace

Expected<StoreLock> StoreLock::take(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) {
        return Error{"cannot open the store's lock '" + path.string() + "': " +
                     std::strerror(errno)};
    }
    StoreLock lock(fd);
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        if (errno == EWOULDBLOCK) {
            return Error{"another discreel serve is using the store in '" +
                         path.parent_path().string() +
                         "' (it holds serve.lock); stop it, or give this one another --data"};
        }
        return Error{"cannot lock '" + path.string() + "': " + std::strerror(errno)};
    }
    return lock;
}

StoreLock::~StoreLock() {
    if (fd_ >= 0) ::close(fd_);   // closing releases the lock
}

StoreLock::StoreLock(StoreLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

StoreLock& StoreLock::operator=(StoreLock&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
}

const char* to_string(JobStatus status) {
    switch (status) {
        case JobStatus::queued: return "queued";
        case JobStatus::running: return "running";
        case JobStatus::succeeded: return "succeeded";
        case JobStatus::failed: return "failed";
        case JobStatus::cancelled: return "cancelled";
    }
    return "queued";
}

bool is_final(JobStatus status) {
    return status == JobStatus::succeeded || status == JobStatus::failed ||
           status == JobStatus::cancelled;
}

void Store::Closer::operator()(sqlite3* db) const { sqlite3_close(db); }

Store::Store(sqlite3* db) : db_(db) {}
Store::~Store() = default;
Store::Store(Store&&) noexcept = default;
Store& Store::operator=(Store&&) noexcept = default;

Expected<Store> Store::open(const std::string& path) {
    sqlite3* db = nullptr;
    const int opened = sqlite3_open_v2(path.c_str(), &db,
                                       SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE |
                                           SQLITE_OPEN_FULLMUTEX, nullptr);
    Store store(db);   // closes db on every path, also when opening failed
    if (opened != SQLITE_OK) return sqlite_error(db, "open the job store '" + path + "'");
    sqlite3_busy_timeout(db, 5000);
    // WAL with synchronous=FULL: a commit is on disk when it returns, readers never block the
    // writer. A small autocheckpoint keeps the log short (it is rewritten from its start after
    // each checkpoint), which also bounds what a nearly full disk must hold.
    for (const char* sql : {"PRAGMA journal_mode=WAL;", "PRAGMA synchronous=FULL;",
                            "PRAGMA wal_autocheckpoint=64;", schema}) {
        if (Status done = store.exec(sql); !done) return done.error();
    }
    for (const auto& [column, add] :
         {std::pair{"warnings", "ALTER TABLE jobs ADD COLUMN warnings TEXT;"},
          std::pair{"created", "ALTER TABLE jobs ADD COLUMN created INTEGER;"},
          std::pair{"extras", "ALTER TABLE jobs ADD COLUMN extras TEXT;"}}) {
        const auto has = has_column(db, column);
        if (!has) return has.error();
        if (*has) continue;
        if (Status done = store.exec(add); !done) return done.error();
    }
    return store;
}

Status Store::exec(const char* sql) {
    char* message = nullptr;
    if (sqlite3_exec(db_.get(), sql, nullptr, nullptr, &message) != SQLITE_OK) {
        Error error{std::string("cannot set up the job store: ") +
                    (message != nullptr ? message : "unknown error")};
        sqlite3_free(message);
        return error;
    }
    return {};
}

// Binds text parameters 1..n (NULL for nullopt), then the numbers after them, and steps.
Status Store::update(const char* sql, const std::vector<std::optional<std::string>>& text,
                     const std::vector<std::int64_t>& numbers) {
    auto statement = prepare(db_.get(), sql);
    if (!statement) return statement.error();
    int index = 1;
    for (const auto& value : text) {
        if (value) {
            sqlite3_bind_text(statement->get(), index, value->data(),
                              static_cast<int>(value->size()), SQLITE_TRANSIENT);
        } else {
            sqlite3_bind_null(statement->get(), index);
        }
        ++index;
    }
    for (const std::int64_t value : numbers) sqlite3_bind_int64(statement->get(), index++, value);
    if (sqlite3_step(statement->get()) != SQLITE_DONE) {
        return sqlite_error(db_.get(), "write to the job store");
    }
    return {};
}

Expected<std::vector<StoredJob>> Store::load() {
    auto statement = prepare(db_.get(),
                             "SELECT id, status, frames_total, error, sha256, bytes, extension, "
                             "warnings, created, extras FROM jobs ORDER BY seq");
    if (!statement) return statement.error();
    std::vector<StoredJob> jobs;
    int step = SQLITE_ROW;
    while ((step = sqlite3_step(statement->get())) == SQLITE_ROW) {
        sqlite3_stmt* row = statement->get();
        StoredJob job;
        job.id = column_text(row, 0);
        job.status = status_of(column_text(row, 1));
        job.frames_total = sqlite3_column_int(row, 2);
        job.error = optional_text(row, 3);
        if (auto sha = optional_text(row, 4)) {
            job.output = OutputInfo{.sha256 = *sha,
                                    .bytes = sqlite3_column_int64(row, 5),
                                    .extension = column_text(row, 6)};
        }
        if (auto warnings = optional_text(row, 7)) job.warnings = std::move(*warnings);
        job.created = sqlite3_column_int64(row, 8);   // 0 for NULL
        if (auto extras = optional_text(row, 9)) job.extras = std::move(*extras);
        jobs.push_back(std::move(job));
    }
    if (step != SQLITE_DONE) return sqlite_error(db_.get(), "read the job store");
    return jobs;
}

Expected<std::string> Store::request(const std::string& id) {
    auto statement = prepare(db_.get(), "SELECT request FROM jobs WHERE id = ?1");
    if (!statement) return statement.error();
    sqlite3_bind_text(statement->get(), 1, id.data(), static_cast<int>(id.size()),
                      SQLITE_TRANSIENT);
    if (sqlite3_step(statement->get()) != SQLITE_ROW) {
        return sqlite_error(db_.get(), "read job " + id + " from the job store");
    }
    return column_text(statement->get(), 0);
}

Status Store::accept(const std::string& id, const std::string& request, int frames_total,
                     const std::string& warnings, std::int64_t created) {
    return update("INSERT INTO jobs (id, request, status, frames_total, warnings, created) "
                  "VALUES (?1, ?2, 'queued', ?4, ?3, ?5) "
                  "ON CONFLICT(id) DO UPDATE SET status = 'queued', error = NULL, "
                  "sha256 = NULL, bytes = NULL, extension = NULL, warnings = ?3, created = ?5, "
                  "extras = NULL",
                  {id, request, warnings}, {frames_total, created});
}

Status Store::remove(const std::string& id) {
    return update("DELETE FROM jobs WHERE id = ?1", {id}, {});
}

Status Store::set_running(const std::string& id) {
    return update("UPDATE jobs SET status = 'running' WHERE id = ?1", {id}, {});
}

Status Store::set_succeeded(const std::string& id, const OutputInfo& output,
                            const std::string& extras) {
    return update("UPDATE jobs SET status = 'succeeded', error = NULL, sha256 = ?2, "
                  "extension = ?3, extras = ?4, bytes = ?5 WHERE id = ?1",
                  {id, output.sha256, output.extension, extras}, {output.bytes});
}

Status Store::set_ended(const std::string& id, JobStatus status, const std::string& error) {
    return update("UPDATE jobs SET status = ?2, error = ?3 WHERE id = ?1",
                  {id, std::string(to_string(status)), error}, {});
}

}  // namespace discreel::serve
