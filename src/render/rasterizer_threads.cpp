#include <cstdlib>
#include <string>

#include "discreel/render.hpp"

namespace discreel::render {

void set_rasterizer_threads(int count) {
    setenv("LP_NUM_THREADS", std::to_string(count).c_str(), /*overwrite=*/0);
}

}  // namespace discreel::render
