#include "tar.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

namespace discreel::serve {
namespace {

constexpr std::size_t block = 512;

// An octal field of `width` bytes: digits, then a NUL.
void octal(char* field, std::size_t width, std::uint64_t value) {
    std::snprintf(field, width, "%0*llo", static_cast<int>(width - 1),
                  static_cast<unsigned long long>(value));
}

std::array<char, block> header(const std::string& name, std::uint64_t size) {
    std::array<char, block> h{};
    std::memcpy(h.data(), name.data(), std::min<std::size_t>(name.size(), 100));
    octal(&h[100], 8, 0644);   // mode
    octal(&h[108], 8, 0);      // uid
    octal(&h[116], 8, 0);      // gid
    octal(&h[124], 12, size);
    octal(&h[136], 12, 0);     // mtime: fixed, so the bytes do not depend on when
    h[156] = '0';              // a regular file
    std::memcpy(&h[257], "ustar", 6);
    std::memcpy(&h[263], "00", 2);
    // The checksum is computed with its own field as eight spaces.
    std::memset(&h[148], ' ', 8);
    unsigned sum = 0;
    for (const char c : h) sum += static_cast<unsigned char>(c);
    std::snprintf(&h[148], 8, "%06o", sum);
    h[155] = ' ';
    return h;
}

}  // namespace

Status write_tar(const std::filesystem::path& dir, const std::string& prefix,
                 const std::filesystem::path& archive) {
    std::vector<std::filesystem::path> files;
    std::error_code failed;
    for (const auto& entry : std::filesystem::directory_iterator(dir, failed)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
    }
    if (failed) return Error{"cannot read the directory '" + dir.string() + "': " + failed.message()};
    std::sort(files.begin(), files.end());
    std::ofstream out(archive, std::ios::binary | std::ios::trunc);
    std::vector<char> bytes;
    for (const auto& file : files) {
        const std::string name = prefix + "/" + file.filename().string();
        if (name.size() > 100) return Error{"the name '" + name + "' is too long for tar"};
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        if (!in && !in.eof()) return Error{"cannot read '" + file.string() + "'"};
        const auto h = header(name, bytes.size());
        out.write(h.data(), block);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        const std::size_t pad = (block - bytes.size() % block) % block;
        const std::array<char, block> zeros{};
        out.write(zeros.data(), static_cast<std::streamsize>(pad));
    }
    const std::array<char, 2 * block> end{};
    out.write(end.data(), end.size());   // two zero blocks end the archive
    out.flush();
    if (!out) return Error{"cannot write '" + archive.string() + "'"};
    return {};
}

}  // namespace discreel::serve
