#pragma once
// SHA-256 (libavutil's), in lower-case hex: job ids and the names outputs are stored under.
#include <string>
#include <string_view>

#include "discreel/expected.hpp"

namespace discreel::serve {

std::string sha256_hex(std::string_view bytes);
Expected<std::string> sha256_hex_of_file(const std::string& path);

}  // namespace discreel::serve
