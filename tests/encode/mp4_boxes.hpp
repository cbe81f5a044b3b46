#pragma once
// The top-level boxes (atoms) of an ISO BMFF / MP4 file, in file order.
#include <cstdint>
#include <string>
#include <vector>

namespace discreel::encode::test {

inline std::vector<std::string> top_level_boxes(const std::vector<std::uint8_t>& bytes) {
    std::vector<std::string> types;
    std::uint64_t offset = 0;
    const auto read_be = [&](std::uint64_t at, int count) {
        std::uint64_t value = 0;
        for (int i = 0; i < count; ++i) {
            value = (value << 8) | bytes[at + static_cast<std::uint64_t>(i)];
        }
        return value;
    };
    while (offset + 8 <= bytes.size()) {
        std::uint64_t size = read_be(offset, 4);
        types.emplace_back(bytes.begin() + static_cast<std::ptrdiff_t>(offset + 4),
                           bytes.begin() + static_cast<std::ptrdiff_t>(offset + 8));
        if (size == 1 && offset + 16 <= bytes.size()) {   // 64-bit "largesize"
            size = read_be(offset + 8, 8);
        } else if (size == 0) {                             // box runs to the end of the file
            size = bytes.size() - offset;
        }
        if (size < 8) {
            types.push_back("<malformed>");
            break;
        }
        offset += size;
    }
    return types;
}

}  // namespace discreel::encode::test
