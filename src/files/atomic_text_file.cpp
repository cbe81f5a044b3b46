#include "discreel/atomic_text_file.hpp"

#include <utility>

namespace discreel {
namespace {

constexpr std::size_t flush_size = 1 << 16;   // bytes

}  // namespace

Expected<AtomicTextFile> AtomicTextFile::create(const std::string& path) {
    auto file = OutputFile::create(path);
    if (!file) return file.error();
    return AtomicTextFile(std::move(*file));
}

void AtomicTextFile::write(std::string_view text) {
    buffer_ += text;
    if (buffer_.size() >= flush_size) flush();
}

void AtomicTextFile::flush() {
    if (written_ && !buffer_.empty()) written_ = file_.write_all(buffer_.data(), buffer_.size());
    buffer_.clear();
}

Status AtomicTextFile::seal() {
    flush();
    if (!written_) return written_;
    return file_.seal();
}

Status AtomicTextFile::commit() {
    if (Status sealed = seal(); !sealed) return sealed;
    return file_.commit();
}

}  // namespace discreel
