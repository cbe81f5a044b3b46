#include "digest.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

extern "C" {
#include <libavutil/mem.h>
#include <libavutil/sha.h>
}

namespace discreel::serve {
namespace {

struct ShaFree {
    void operator()(AVSHA* sha) const { av_free(sha); }
};

class Sha256 {
public:
    Sha256() : sha_(av_sha_alloc()) {
        if (!sha_) throw std::bad_alloc();
        av_sha_init(sha_.get(), 256);
    }
    void add(const void* data, std::size_t size) {
        av_sha_update(sha_.get(), static_cast<const std::uint8_t*>(data), size);
    }
    std::string hex() {
        std::uint8_t digest[32];
        av_sha_final(sha_.get(), digest);
        static constexpr char digits[] = "0123456789abcdef";
        std::string text(64, '0');
        for (std::size_t i = 0; i < 32; ++i) {
            text[2 * i] = digits[digest[i] >> 4];
            text[2 * i + 1] = digits[digest[i] & 15];
        }
        return text;
    }

private:
    std::unique_ptr<AVSHA, ShaFree> sha_;
};

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

std::string sha256_hex(std::string_view bytes) {
    Sha256 sha;
    sha.add(bytes.data(), bytes.size());
    return sha.hex();
}

Expected<std::string> sha256_hex_of_file(const std::string& path) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) return Error{"cannot read '" + path + "': " + std::strerror(errno)};
    Sha256 sha;
    std::vector<char> buffer(1 << 16);
    std::size_t got = 0;
    while ((got = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0) {
        sha.add(buffer.data(), got);
    }
    if (std::ferror(file.get())) return Error{"cannot read '" + path + "'"};
    return sha.hex();
}

}  // namespace discreel::serve
