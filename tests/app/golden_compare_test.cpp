// The image comparison behind `discreel golden`, on small synthetic images whose expected
// counts follow from their construction.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "golden_compare.hpp"
#include "golden_junit.hpp"

namespace discreel::golden {
namespace {

using Colour = std::array<std::uint8_t, 4>;

Image flat(int width, int height, Colour c) {
    Image image{width, height, {}};
    for (int i = 0; i < width * height; ++i) image.rgba.insert(image.rgba.end(), c.begin(), c.end());
    return image;
}

void set(Image& image, int x, int y, Colour c) {
    std::copy(c.begin(), c.end(), image.rgba.begin() + 4 * (y * image.width + x));
}

Colour at(const Image& image, int x, int y) {
    Colour c;
    std::copy_n(image.rgba.begin() + 4 * (y * image.width + x), 4, c.begin());
    return c;
}

constexpr Colour kBackground{15, 20, 25, 255};
constexpr Colour kDisc{228, 87, 46, 255};
constexpr Colour kRed{255, 0, 0, 255};
constexpr Colour kYellow{255, 210, 0, 255};

TEST(GoldenCompareTest, IdenticalImagesTakeTheFastPath) {
    const Image a = flat(20, 10, kBackground);
    const Comparison c = compare_images(a.view(), a.view(), {});
    EXPECT_TRUE(c.identical);
    EXPECT_EQ(c.differing_pixels, 0);
    EXPECT_EQ(c.pixel_count, 200);
    EXPECT_TRUE(c.diff.rgba.empty());   // nothing computed beyond the byte comparison
}

TEST(GoldenCompareTest, SmallColourShiftsStayWithinTheThreshold) {
    const Image golden = flat(20, 10, kBackground);
    Image actual = golden;
    // 3 units on every channel: a distance of about 0.01, far below the default 0.1.
    set(actual, 5, 5, {18, 23, 28, 255});
    const Comparison c = compare_images(actual.view(), golden.view(), {});
    EXPECT_FALSE(c.identical);
    EXPECT_EQ(c.differing_pixels, 0);
    EXPECT_EQ(c.anti_aliased_pixels, 0);
    EXPECT_GT(c.max_delta, 0);
    EXPECT_LT(c.max_delta, 0.02);
    // With threshold 0 every changed pixel counts.
    EXPECT_EQ(compare_images(actual.view(), golden.view(), {.threshold = 0}).differing_pixels, 1);
}

TEST(GoldenCompareTest, AChangedColourCountsEveryPixelAndIsRedInTheDiff) {
    const Image golden = flat(20, 10, kBackground);
    Image actual = golden;
    // A 4x4 block: each of its pixels has at least three neighbours of its own colour, so none
    // of them can pass for anti-aliasing.
    for (int y = 3; y < 7; ++y)
        for (int x = 8; x < 12; ++x) set(actual, x, y, kDisc);
    const Comparison c = compare_images(actual.view(), golden.view(), {});
    EXPECT_EQ(c.differing_pixels, 16);
    EXPECT_EQ(c.anti_aliased_pixels, 0);
    EXPECT_GT(c.max_delta, 0.3);
    ASSERT_EQ(c.diff.width, 20);
    EXPECT_EQ(at(c.diff, 9, 4), kRed);
    // Elsewhere: the golden's background faded towards white, grey and opaque.
    const Colour backdrop = at(c.diff, 0, 0);
    EXPECT_EQ(backdrop[0], backdrop[1]);
    EXPECT_EQ(backdrop[1], backdrop[2]);
    EXPECT_GT(backdrop[0], 180);
    EXPECT_EQ(backdrop[3], 255);
}

TEST(GoldenCompareTest, ANewOnePixelLineIsARealChange) {
    const Image golden = flat(20, 10, kBackground);
    Image actual = golden;
    // Same brightness on both sides of the line: not a blend between two areas.
    for (int y = 0; y < 10; ++y) set(actual, 10, y, kDisc);
    EXPECT_EQ(compare_images(actual.view(), golden.view(), {}).differing_pixels, 10);
}

// Dark on the left, bright on the right, a column of blended edge pixels between them whose
// shade differs between the two images, as a different rasteriser's coverage would make it.
TEST(GoldenCompareTest, AntiAliasedEdgePixelsAreToldApartAndYellow) {
    constexpr Colour kDark{0, 0, 0, 255}, kBright{255, 255, 255, 255};
    Image golden = flat(20, 10, kDark);
    for (int y = 0; y < 10; ++y)
        for (int x = 11; x < 20; ++x) set(golden, x, y, kBright);
    Image actual = golden;
    for (int y = 0; y < 10; ++y) {
        set(golden, 10, y, {128, 128, 128, 255});
        set(actual, 10, y, {90, 90, 90, 255});   // 38 units darker: a distance of about 0.14
    }
    const Comparison c = compare_images(actual.view(), golden.view(), {});
    EXPECT_EQ(c.differing_pixels, 0);
    EXPECT_EQ(c.anti_aliased_pixels, 10);
    EXPECT_EQ(at(c.diff, 10, 5), kYellow);

    const Comparison strict =
        compare_images(actual.view(), golden.view(), {.detect_anti_aliasing = false});
    EXPECT_EQ(strict.differing_pixels, 10);
    EXPECT_EQ(strict.anti_aliased_pixels, 0);
}

TEST(GoldenCompareTest, DifferentSizesAreReportedNotCompared) {
    const Comparison c =
        compare_images(flat(20, 10, kBackground).view(), flat(10, 20, kBackground).view(), {});
    EXPECT_FALSE(c.same_size);
    EXPECT_FALSE(c.identical);
}

TEST(GoldenCompareTest, ColourDistanceIsPerceptual) {
    const std::uint8_t black[4] = {0, 0, 0, 255}, white[4] = {255, 255, 255, 255};
    const std::uint8_t clear[4] = {0, 0, 0, 0};
    EXPECT_NEAR(color_distance(black, white), 0.966, 0.001);
    EXPECT_EQ(color_distance(black, black), 0);
    // Fully transparent black looks like the white page under it.
    EXPECT_EQ(color_distance(clear, white), 0);
    // The eye is more sensitive to green than to blue: the same step weighs more.
    const std::uint8_t green[4] = {0, 40, 0, 255}, blue[4] = {0, 0, 40, 255};
    EXPECT_GT(color_distance(black, green), color_distance(black, blue));
}

TEST(GoldenJunitTest, OneSuiteOneCasePerFrameWithEscapedFailures) {
    const std::string xml = junit_xml(
        "discreel golden",
        {{.scene = "demo", .name = "frame_0", .passed = true, .message = "identical", .details = {},
          .seconds = 0.25},
         {.scene = "a<b>&\"c\"", .name = "frame_1", .passed = false,
          .message = "3 pixels differ", .details = "3 pixels differ\nwrote 'x'", .seconds = 1.5}});
    // Times per case, and their sum per suite, in seconds (JUnit's `time`).
    EXPECT_EQ(xml,
              "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
              "<testsuites name=\"discreel golden\" tests=\"2\" failures=\"1\" errors=\"0\" "
              "time=\"1.750\">\n"
              "  <testsuite name=\"discreel golden\" tests=\"2\" failures=\"1\" errors=\"0\" "
              "time=\"1.750\">\n"
              "    <testcase classname=\"demo\" name=\"frame_0\" time=\"0.250\"/>\n"
              "    <testcase classname=\"a&lt;b&gt;&amp;&quot;c&quot;\" name=\"frame_1\" "
              "time=\"1.500\">\n"
              "      <failure message=\"3 pixels differ\" type=\"golden mismatch\">3 pixels "
              "differ\nwrote &apos;x&apos;</failure>\n"
              "    </testcase>\n"
              "  </testsuite>\n"
              "</testsuites>\n");
}

TEST(GoldenJunitTest, ControlCharactersCannotBreakTheXml) {
    EXPECT_EQ(xml_escape(std::string("a\x01" "b\tc")), "a\xEF\xBF\xBD" "b\tc");
}

}  // namespace
}  // namespace discreel::golden
