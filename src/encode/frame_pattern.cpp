#include "frame_pattern.hpp"

namespace discreel::encode {

std::string FramePattern::path_of(int index) const {
    std::string number = std::to_string(index);
    if (static_cast<int>(number.size()) < digits) {
        number.insert(0, static_cast<std::size_t>(digits) - number.size(), '0');
    }
    return prefix + number + suffix;
}

Expected<std::optional<FramePattern>> parse_frame_pattern(const std::string& path) {
    if (path.find('%') == std::string::npos) {
        return std::optional<FramePattern>{};
    }
    const Error bad{"'" + path +
                    "': a '%' in an output name must be one frame number, %d or %0Nd such as "
                    "%04d (write %% for a percent sign)"};
    FramePattern pattern;
    bool have_number = false;
    std::string* text = &pattern.prefix;
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i] != '%') {
            *text += path[i];
            continue;
        }
        if (i + 1 < path.size() && path[i + 1] == '%') {
            *text += '%';
            ++i;
            continue;
        }
        if (have_number) {
            return bad;
        }
        std::size_t j = i + 1;
        if (j + 2 < path.size() && path[j] == '0' && path[j + 1] >= '1' && path[j + 1] <= '9' &&
            path[j + 2] == 'd') {
            pattern.digits = path[j + 1] - '0';
            i = j + 2;
        } else if (j < path.size() && path[j] == 'd') {
            i = j;
        } else {
            return bad;
        }
        have_number = true;
        text = &pattern.suffix;
    }
    if (!have_number) {
        return bad;
    }
    return std::optional<FramePattern>{std::move(pattern)};
}

}  // namespace discreel::encode
