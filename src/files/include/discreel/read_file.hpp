#pragma once
// Reading an input of any kind (a file, a pipe, /dev/zero) without trusting its size: at most
// `max_bytes` + 1 bytes are read, so an endless or huge input costs that much and no more.
#include <cstdint>
#include <string>

#include "discreel/expected.hpp"

namespace discreel {

struct ReadResult {
    std::string bytes;        // the whole input when !too_large, else the first max_bytes + 1
    bool too_large = false;   // the input holds more than max_bytes
};

// Errors: "this is a directory, not a file", or the system's reason ("No such file or
// directory").
Expected<ReadResult> read_file_bounded(const std::string& path, std::uintmax_t max_bytes);

}  // namespace discreel
