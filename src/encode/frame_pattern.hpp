#pragma once
// Numbered output names for image sequences, printf style: "out/frame_%04d.png" names
// out/frame_0000.png, out/frame_0001.png, ... Only one conversion is allowed, %d or %0Nd
// (N from 1 to 9); "%%" is a literal percent sign. The name is formatted here, never handed to
// printf, so a stray "%s" in a user's path cannot reach a format function.
#include <optional>
#include <string>

#include "discreel/expected.hpp"

namespace discreel::encode {

struct FramePattern {
    std::string prefix;   // before the number, with %% already turned into %
    int digits = 0;       // minimum width, zero-padded; 0 for plain %d
    std::string suffix;   // after the number, likewise

    std::string path_of(int index) const;
};

// Nothing when the path has no '%'; an error when its '%'s are not exactly one frame number
// (plus any number of %%).
Expected<std::optional<FramePattern>> parse_frame_pattern(const std::string& path);

}  // namespace discreel::encode
