#pragma once
// Text for messages and files. Names that come from users (file names, ids) are shown in messages with their control bytes
// escaped: an ESC would drive the terminal, a newline would forge a message line, a NUL would
// cut it short. "\n", "\t", "\r" and "\xHH" for the other bytes below 0x20 and 0x7f; bytes
// of 0x80 and above pass, so UTF-8 names read as written, and a name without control bytes is
// shown unchanged.
#include <charconv>
#include <string>
#include <string_view>

namespace discreel {

// Shortest round-trip decimal form of v ("0.1", "1e-09", "-3"): read back, the same double.
inline void append_number(std::string& out, double v) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    out.append(buffer, result.ptr);
}

inline std::string printable(std::string_view text) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte != 0x7f) {
            out += c;
            continue;
        }
        out += '\\';
        switch (c) {
            case '\n': out += 'n'; break;
            case '\t': out += 't'; break;
            case '\r': out += 'r'; break;
            default:
                out += 'x';
                out += hex[byte >> 4];
                out += hex[byte & 0xf];
        }
    }
    return out;
}

}  // namespace discreel
