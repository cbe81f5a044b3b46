#include "discreel/read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>

namespace discreel {
namespace {

constexpr std::size_t chunk_size = 1 << 16;   // bytes per read()

class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    ~Descriptor() {
        if (fd_ >= 0) close(fd_);
    }
    int get() const { return fd_; }

private:
    int fd_;
};

}  // namespace

Expected<ReadResult> read_file_bounded(const std::string& path, std::uintmax_t max_bytes) {
    // O_NONBLOCK: opening a FIFO with no writer must not hang; reads below wait as usual.
    const Descriptor fd(open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (fd.get() < 0) {
        return Error{std::strerror(errno)};
    }
    struct stat info {};
    if (fstat(fd.get(), &info) == 0 && S_ISDIR(info.st_mode)) {
        return Error{"this is a directory, not a file"};
    }
    const int flags = fcntl(fd.get(), F_GETFL);
    if (flags >= 0) fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK);

    ReadResult result;
    // Never more than the limit plus one byte, whatever the file claims to be or hold.
    const std::uintmax_t wanted =
        max_bytes == std::numeric_limits<std::uintmax_t>::max() ? max_bytes : max_bytes + 1;
    while (result.bytes.size() < wanted) {
        const std::size_t room = static_cast<std::size_t>(
            std::min<std::uintmax_t>(chunk_size, wanted - result.bytes.size()));
        const std::size_t old_size = result.bytes.size();
        result.bytes.resize(old_size + room);
        const ssize_t got = read(fd.get(), result.bytes.data() + old_size, room);
        if (got < 0) {
            result.bytes.resize(old_size);
            if (errno == EINTR) continue;
            return Error{std::strerror(errno)};
        }
        result.bytes.resize(old_size + static_cast<std::size_t>(got));
        if (got == 0) break;
    }
    result.too_large = result.bytes.size() > max_bytes;
    return result;
}

}  // namespace discreel
