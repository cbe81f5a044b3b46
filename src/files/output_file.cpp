#include "discreel/output_file.hpp"

#include "discreel/temporary_files.hpp"

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

}  // namespace

Error write_error(const std::string& path, const std::string& reason) {
    return Error{"cannot write '" + path + "': " + reason};
}

Expected<OutputFile> OutputFile::create(const std::string& target_path) {
    const std::filesystem::path target(target_path);
    if (!target.has_filename()) {
        return write_error(target_path, "the path names a directory, not a file");
    }
    const std::filesystem::path directory =
        target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    std::error_code status_error;
    const auto directory_status = std::filesystem::status(directory, status_error);
    if (!std::filesystem::exists(directory_status)) {
        return write_error(target_path,
                           std::string("directory '") + directory.string() + "' does not exist");
    }
    if (!std::filesystem::is_directory(directory_status)) {
        return write_error(target_path, std::string("'") + directory.string() + "' is not a directory");
    }

    // A dot-name hides the partial file from casual listings; the suffix makes it unique, so
    // two writers aiming at the same target never share a temporary file.
    std::string pattern =
        (directory / (std::string(".") + target.filename().string() + ".tmp-XXXXXX")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int fd = mkstemp(name.data());
    if (fd < 0) {
        return write_error(target_path, errno_text(errno));
    }
    // mkstemp creates 0600; the output is an ordinary document, with the permissions any
    // other new file would get.
    fchmod(fd, 0666 & ~file_creation_mask());
    return OutputFile(target_path, std::string(name.data()), fd);
}

OutputFile::OutputFile(std::string target_path, std::string temp_path, int fd)
    : target_path_(std::move(target_path)),
      temp_path_(std::move(temp_path)),
      fd_(fd),
      registration_(register_temporary_file(temp_path_)) {}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : target_path_(std::move(other.target_path_)),
      temp_path_(std::move(other.temp_path_)),
      fd_(std::exchange(other.fd_, -1)),
      committed_(std::exchange(other.committed_, true)),
      registration_(other.registration_) {}

OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
    if (this != &other) {
        discard();
        target_path_ = std::move(other.target_path_);
        temp_path_ = std::move(other.temp_path_);
        fd_ = std::exchange(other.fd_, -1);
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
    // old file used to be.
    if (fsync(fd_) != 0) {
        return write_error(target_path_, errno_text(errno));
    }
    close(fd_);
    fd_ = -1;
    return {};
}

Status OutputFile::commit() {
    if (auto sealed = seal(); !sealed) {
        return sealed;
    }
    if (std::rename(temp_path_.c_str(), target_path_.c_str()) != 0) {
        return write_error(target_path_, errno_text(errno));
    }
    unregister_temporary_file(registration_);
    committed_ = true;
    return {};
}

}  // namespace discreel
