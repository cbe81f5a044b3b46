#include "discreel/output_file.hpp"

#include "discreel/commit.hpp"
#include "discreel/file_identity.hpp"
#include "discreel/printable.hpp"
#include "discreel/temporary_files.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace discreel {
namespace {

std::string errno_text(int error_number) { return std::strerror(error_number); }

// Read once, on the first call (on the main thread, before any other starts): umask() can
// only be read by setting it, which would race with other threads creating files.
mode_t file_creation_mask() {
    static const mode_t mask = [] {
        const mode_t current = umask(0);
        umask(current);
        return current;
    }();
    return mask;
}

std::atomic<bool> committing{false};
static_assert(std::atomic<bool>::is_always_lock_free);

// A unique hidden name beside `target` for a file of this process: ".NAME.<kind>-XXXXXX",
// created empty; -1 and errno when it cannot be.
int make_hidden_file(const std::filesystem::path& target, const char* kind, std::string& name) {
    std::string hidden = ".";
    hidden.append(target.filename().string()).append(".").append(kind).append("-XXXXXX");
    const std::string pattern = (target.parent_path() / hidden).string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const int fd = mkstemp(buffer.data());
    if (fd >= 0) name.assign(buffer.data());
    return fd;
}

}  // namespace

Error write_error(const std::string& path, const std::string& reason) {
    return Error{"cannot write '" + printable(path) + "': " + reason};
}

bool commit_in_progress() { return committing.load(std::memory_order_relaxed); }

Expected<OutputFile> OutputFile::create(const std::string& target_path) {
    const std::filesystem::path named(target_path);
    if (!named.has_filename()) {
        return write_error(target_path, "the path names a directory, not a file");
    }
    const std::filesystem::path target(real_path(target_path));
    struct stat existing {};
    if (stat(target.c_str(), &existing) == 0) {
        if (S_ISDIR(existing.st_mode)) {
            return write_error(target_path, "it is a directory; name a file inside it");
        }
        if (!S_ISREG(existing.st_mode)) {
            // A device, FIFO or socket: written in place, never replaced. Opened without
            // waiting: a FIFO that no process reads fails at once (ENXIO) rather than blocking
            // the run where no signal can end it; writes wait for the reader as usual.
            const int fd = open(target.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK);
            if (fd < 0) {
                if (errno == ENXIO && S_ISFIFO(existing.st_mode)) {
                    return write_error(target_path, "it is a FIFO that no process is reading");
                }
                return write_error(target_path, errno_text(errno));
            }
            const int flags = fcntl(fd, F_GETFL);
            if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
            return OutputFile(target_path, target.string(), target.string(), fd, true);
        }
    }
    const std::filesystem::path directory = target.parent_path();
    std::error_code status_error;
    const auto directory_status = std::filesystem::status(directory, status_error);
    const std::filesystem::path shown_directory =
        named.has_parent_path() ? named.parent_path() : std::filesystem::path(".");
    std::string shown = "'";
    shown.append(printable(shown_directory.string())).append("'");
    if (!std::filesystem::exists(directory_status)) {
        return write_error(target_path, "directory " + shown + " does not exist");
    }
    if (!std::filesystem::is_directory(directory_status)) {
        return write_error(target_path, shown + " is not a directory");
    }

    // A dot-name hides the partial file from casual listings; the suffix makes it unique, so
    // two writers aiming at the same target never share a temporary file.
    std::string temp;
    const int fd = make_hidden_file(target, "tmp", temp);
    if (fd < 0) {
        return write_error(target_path, errno_text(errno));
    }
    // mkstemp creates 0600; the output is an ordinary document, with the permissions any
    // other new file would get.
    fchmod(fd, 0666 & ~file_creation_mask());
    return OutputFile(target_path, target.string(), temp, fd, false);
}

OutputFile::OutputFile(std::string target_path, std::string real_target, std::string temp_path,
                       int fd, bool direct)
    : target_path_(std::move(target_path)),
      real_target_(std::move(real_target)),
      temp_path_(std::move(temp_path)),
      fd_(fd),
      direct_(direct),
      committed_(direct),
      registration_(direct ? 0 : register_temporary_file(temp_path_)) {}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : target_path_(std::move(other.target_path_)),
      real_target_(std::move(other.real_target_)),
      temp_path_(std::move(other.temp_path_)),
      fd_(std::exchange(other.fd_, -1)),
      direct_(other.direct_),
      committed_(std::exchange(other.committed_, true)),
      registration_(other.registration_) {}

OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
    if (this != &other) {
        discard();
        target_path_ = std::move(other.target_path_);
        real_target_ = std::move(other.real_target_);
        temp_path_ = std::move(other.temp_path_);
        fd_ = std::exchange(other.fd_, -1);
        direct_ = other.direct_;
        committed_ = std::exchange(other.committed_, true);
        registration_ = other.registration_;
    }
    return *this;
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() {
    if (fd_ >= 0) {
        close(fd_);
        fd_ = -1;
    }
    if (!committed_) {
        unlink(temp_path_.c_str());
        unregister_temporary_file(registration_);
        committed_ = true;   // nothing left to clean up
    }
}

Status OutputFile::write_all(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t written = write(fd_, bytes, size);
        if (written < 0) {
            if (errno == EINTR) {
                continue;
            }
            return write_error(target_path_, errno_text(errno));
        }
        bytes += written;
        size -= static_cast<std::size_t>(written);
    }
    return {};
}

Status OutputFile::seal() {
    if (fd_ < 0) {
        return {};
    }
    // Without the fsync a crash right after the rename could leave an empty target where the
    // old file used to be. A special file has nothing to make durable (and a pipe refuses).
    if (!direct_ && fsync(fd_) != 0) {
        return write_error(target_path_, errno_text(errno));
    }
    if (close(std::exchange(fd_, -1)) != 0 && !direct_) {
        return write_error(target_path_, errno_text(errno));
    }
    return {};
}

Status OutputFile::commit() {
    OutputFile* self = this;
    return commit_together(&self, 1);
}

namespace {

// One target's state during commit_together.
struct Step {
    OutputFile* file;
    bool existed = false;    // the target was there before
    std::string backup;      // hard link to the old target; empty when none could be made
    std::size_t backup_registration = 0;
};

// Holds commit_in_progress() for its lifetime.
struct CommitFlag {
    CommitFlag() { committing.store(true, std::memory_order_relaxed); }
    CommitFlag(const CommitFlag&) = delete;
    CommitFlag& operator=(const CommitFlag&) = delete;
    ~CommitFlag() { committing.store(false, std::memory_order_relaxed); }
};

}  // namespace

Status commit_together(OutputFile* const* files, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) {
        if (Status sealed = files[i]->seal(); !sealed) return sealed;
    }
    const CommitFlag flag;
    std::vector<Step> steps;
    steps.reserve(count);
    const auto drop_backups = [&] {
        for (Step& step : steps) {
            if (step.backup.empty()) continue;
            unlink(step.backup.c_str());
            unregister_temporary_file(step.backup_registration);
        }
    };
    for (std::size_t i = 0; i < count; ++i) {
        OutputFile& file = *files[i];
        if (file.committed_) continue;   // already committed, or written directly
        Step step{.file = &file, .existed = false, .backup = {}};
        // A hard link keeps the old target reachable without ever leaving the target path
        // empty. Where links are impossible (some file systems) the target is replaced without
        // a way back, as a single rename would.
        struct stat existing {};
        step.existed = lstat(file.real_target_.c_str(), &existing) == 0;
        if (step.existed) {
            std::string name;
            const int fd = make_hidden_file(file.real_target_, "old", name);
            if (fd >= 0) {
                close(fd);
                unlink(name.c_str());
                if (link(file.real_target_.c_str(), name.c_str()) == 0) {
                    step.backup = name;
                    step.backup_registration = register_temporary_file(name);
                }
            }
        }
        steps.push_back(std::move(step));
    }
    for (std::size_t i = 0; i < steps.size(); ++i) {
        OutputFile& file = *steps[i].file;
        if (std::rename(file.temp_path_.c_str(), file.real_target_.c_str()) == 0) continue;
        const Error failed = write_error(file.target_path_, errno_text(errno));
        // Put back what was replaced: the old file where there was one, nothing where not.
        for (std::size_t done = 0; done < i; ++done) {
            const Step& back = steps[done];
            if (!back.backup.empty()) {
                std::rename(back.backup.c_str(), back.file->real_target_.c_str());
            } else if (!back.existed) {
                unlink(back.file->real_target_.c_str());
            }
        }
        drop_backups();
        return failed;
    }
    for (Step& step : steps) {
        unregister_temporary_file(step.file->registration_);
        step.file->committed_ = true;
    }
    drop_backups();
    return {};
}

}  // namespace discreel
