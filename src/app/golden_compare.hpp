#pragma once
// Compares a rendered frame with its golden image the way a person would: identical bytes pass
// at once; otherwise each pixel's colour difference is measured perceptually (YIQ, as
// pixelmatch does), and differing pixels that look like anti-aliasing (an edge drawn a shade
// lighter or darker) are told apart from real changes and not counted.
//     const auto r = golden::compare_images(actual, golden, {.threshold = 0.1});
//     if (r.differing_pixels > allowed) write_png(path, r.diff);
#include <cstdint>

#include "discreel/image.hpp"

namespace discreel::golden {

struct CompareDef {
    // Largest perceptual colour distance that still counts as the same colour, 0..1: 0 demands
    // equal colours, 1 accepts anything. 0.1 lets through differences a viewer does not notice
    // (about 25 units of brightness) and catches any change of a disc's colour.
    double threshold = 0.1;
    bool detect_anti_aliasing = true;   // false: AA-looking pixels count as differing too
};

struct Comparison {
    bool identical = false;           // every byte equal (the fast path: nothing else computed)
    bool same_size = true;            // false: nothing else is meaningful
    std::int64_t pixel_count = 0;     // of the actual image
    std::int64_t differing_pixels = 0;        // beyond the threshold and not anti-aliasing
    std::int64_t anti_aliased_pixels = 0;     // beyond the threshold, but anti-aliasing
    double max_delta = 0;             // the largest colour distance seen, on the 0..1 scale
    // Same size as the inputs when neither identical nor of different size: the golden in faded
    // grey, differing pixels red, anti-aliased ones yellow.
    Image diff;
};

Comparison compare_images(const ImageView& actual, const ImageView& golden, const CompareDef& def);

// The perceptual distance between two RGBA colours on a 0..1 scale (black against white: 0.97).
// Translucent colours are first blended onto white, so transparency differences show.
double color_distance(const std::uint8_t* a, const std::uint8_t* b);

}  // namespace discreel::golden
