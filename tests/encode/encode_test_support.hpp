#pragma once
// Shared helpers for the encode tests: a fresh scratch directory per test, synthetic frames
// (moving coloured shapes, since the renderer is another module), and file inspection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "discreel/image.hpp"
#include "test_support.hpp"

namespace discreel::encode::test {

using discreel::testing::directory_entries;
using discreel::testing::write_file;

// A directory named after the running test, emptied before the test starts.
inline std::filesystem::path scratch_directory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const auto directory = std::filesystem::path(DISCREEL_BINARY_DIR) / "encode-test-scratch" /
                           (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::remove_all(directory);
    std::filesystem::create_directories(directory);
    return directory;
}

inline std::vector<std::uint8_t> file_bytes(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

inline Image solid_image(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b,
                         std::uint8_t a = 255) {
    Image image{width, height, {}};
    image.rgba.reserve(std::size_t{4} * static_cast<std::size_t>(width * height));
    for (int i = 0; i < width * height; ++i) {
        image.rgba.insert(image.rgba.end(), {r, g, b, a});
    }
    return image;
}

// Frame `index` of a little animation: a dark background with a red disc moving right and a
// green square moving down, so consecutive frames differ the way rendered ones do.
inline Image moving_shapes_frame(int width, int height, int index) {
    Image image = solid_image(width, height, 20, 24, 40);
    const int disc_x = (index * 3) % width;
    const int disc_y = height / 2;
    const int radius = height / 6;
    const int square_x = width / 4;
    const int square_y = (index * 2) % height;
    const int side = height / 5;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::uint8_t* pixel = &image.rgba[4 * static_cast<std::size_t>(y * width + x)];
            if ((x - disc_x) * (x - disc_x) + (y - disc_y) * (y - disc_y) <= radius * radius) {
                pixel[0] = 230; pixel[1] = 40; pixel[2] = 30;
            } else if (x >= square_x && x < square_x + side && y >= square_y &&
                       y < square_y + side) {
                pixel[0] = 40; pixel[1] = 200; pixel[2] = 60;
            }
        }
    }
    return image;
}

}  // namespace discreel::encode::test
