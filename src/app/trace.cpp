#include "trace.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace discreel::app {

void append_number(std::string& out, double v) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.append(buffer, result.ptr);
}

AtomicTextFile::AtomicTextFile(std::string path, std::string temp_path, std::FILE* file)
    : path_(std::move(path)), temp_path_(std::move(temp_path)), file_(file) {}

AtomicTextFile::AtomicTextFile(AtomicTextFile&& other) noexcept
    : path_(std::move(other.path_)),
      temp_path_(std::move(other.temp_path_)),
      file_(std::exchange(other.file_, nullptr)),
      failed_(other.failed_) {}

AtomicTextFile::~AtomicTextFile() {
    if (file_) {
        std::fclose(file_);
        std::remove(temp_path_.c_str());
    }
}

Expected<AtomicTextFile> AtomicTextFile::create(const std::string& path) {
    const std::filesystem::path target(path);
    std::filesystem::path dir = target.parent_path();
    if (dir.empty()) dir = ".";
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp-XXXXXX";
    std::string temp = (dir / name).string();
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) {
        return Error{"cannot write '" + path + "': " + std::strerror(errno)};
    }
    std::FILE* file = ::fdopen(fd, "w");
    if (!file) {
        ::close(fd);
        std::remove(temp.c_str());
        return Error{"cannot write '" + path + "': " + std::strerror(errno)};
    }
    return AtomicTextFile(path, std::move(temp), file);
}

void AtomicTextFile::write(std::string_view text) {
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) failed_ = true;
}

Status AtomicTextFile::commit() {
    const bool closed = std::fclose(std::exchange(file_, nullptr)) == 0;
    const int write_errno = errno;
    if (failed_ || !closed) {
        std::remove(temp_path_.c_str());
        return Error{"cannot write '" + path_ + "': " + std::strerror(write_errno)};
    }
    // mkstemp creates files readable by the owner only; give the result ordinary permissions.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    std::filesystem::permissions(temp_path_,
                                 static_cast<std::filesystem::perms>(0666 & ~mask));
    if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
        const int rename_errno = errno;
        std::remove(temp_path_.c_str());
        return Error{"cannot write '" + path_ + "': " + std::strerror(rename_errno)};
    }
    return {};
}

Expected<TraceWriter> TraceWriter::create(const std::string& path, const scene::Scene& scene) {
    auto file = AtomicTextFile::create(path);
    if (!file) return file.error();
    return TraceWriter(std::move(*file), scene);
}

TraceWriter::TraceWriter(AtomicTextFile file, const scene::Scene& scene)
    : file_(std::move(file)), scene_(&scene) {
    file_.write("frame,t,id,x,y,angle,vx,vy,omega,radius,mass\n");
}

void TraceWriter::write_frame(int frame, double t, std::span<const physics::DiscState> discs) {
    for (std::size_t i = 0; i < discs.size(); ++i) {
        const scene::Disc& def = scene_->discs[i];
        const physics::DiscState& s = discs[i];
        row_.clear();
        row_ += std::to_string(frame);
        row_ += ',';
        append_number(row_, t);
        row_ += ',';
        row_ += def.id;
        for (double v : {s.position.x, s.position.y, s.angle, s.velocity.x, s.velocity.y,
                         s.angular_velocity, def.radius, def.is_static ? 0.0 : def.mass}) {
            row_ += ',';
            append_number(row_, v);
        }
        row_ += '\n';
        file_.write(row_);
    }
}

Expected<EventWriter> EventWriter::create(const std::string& path, const scene::Scene& scene) {
    auto file = AtomicTextFile::create(path);
    if (!file) return file.error();
    return EventWriter(std::move(*file), scene);
}

EventWriter::EventWriter(AtomicTextFile file, const scene::Scene& scene)
    : file_(std::move(file)), scene_(&scene) {
    file_.write("t,a,b,impulse\n");
}

void EventWriter::write(std::span<const physics::ContactEvent> events) {
    for (const physics::ContactEvent& e : events) {
        row_.clear();
        append_number(row_, e.t);
        row_ += ',';
        row_ += scene_->discs[e.a].id;
        row_ += ',';
        if (e.other_kind == physics::ContactEvent::Other::wall) {
            row_ += "wall:" + std::to_string(e.other);
        } else {
            row_ += scene_->discs[e.other].id;
        }
        row_ += ',';
        append_number(row_, e.impulse);
        row_ += '\n';
        file_.write(row_);
    }
}

}  // namespace discreel::app
