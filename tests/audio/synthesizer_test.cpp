// The synthesizer against what it promises (docs/sound.md): each hit is heard from its own
// sample on, silence is exact zeros, no mix reaches full scale, placement follows the pan, and
// the same hits give the same samples, however the output is cut into blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "discreel/audio.hpp"

namespace discreel::audio {
namespace {

// Runs the synthesizer, rendering up to each hit's time as a caller playing the physics
// forward would (every `step` seconds), and returns the interleaved samples.
std::vector<std::int16_t> synthesize(const SynthDef& def, const std::vector<Hit>& hits,
                                     double step = 1.0 / 60) {
    Synthesizer synth(def);
    std::vector<std::int16_t> samples;
    const auto write = [&](std::span<const std::int16_t> block) {
        samples.insert(samples.end(), block.begin(), block.end());
        return true;
    };
    std::size_t next = 0;
    for (double t = step; t < def.duration + step; t += step) {
        while (next < hits.size() && hits[next].t <= t) synth.add(hits[next++]);
        EXPECT_TRUE(synth.render_until(synth.frame_of(t), write));
    }
    EXPECT_TRUE(synth.finish(write));
    EXPECT_EQ(samples.size(), 2 * synth.frames());
    return samples;
}

// The first frame at or after `from` whose left or right sample exceeds `threshold`.
std::size_t onset(const std::vector<std::int16_t>& samples, std::size_t from, int threshold) {
    for (std::size_t frame = from; 2 * frame + 1 < samples.size(); ++frame) {
        if (std::abs(samples[2 * frame]) > threshold || std::abs(samples[2 * frame + 1]) > threshold)
            return frame;
    }
    return samples.size();
}

TEST(SynthesizerTest, NoHitsIsDigitalSilenceOfTheClipsLength) {
    const auto samples = synthesize({.duration = 2.5}, {});
    EXPECT_EQ(samples.size(), 2u * 120000u);
    EXPECT_TRUE(std::all_of(samples.begin(), samples.end(), [](std::int16_t s) { return s == 0; }));
}

// Hits at times that fall between samples and between the caller's steps: each is heard within
// 1 ms of its time (the attack ramp reaches the threshold of -60 dB of full scale within
// 0.5 ms), and not before it.
TEST(SynthesizerTest, EachHitIsHeardWithinOneMillisecondOfItsTime) {
    const std::vector<Hit> hits{{.t = 0.1003, .speed = 3, .size = 0.05, .pan = 0},
                                {.t = 0.61234, .speed = 0.02, .size = 0.3, .pan = -0.5},
                                {.t = 1.25001, .speed = 10, .size = 0.01, .pan = 0.9}};
    const auto samples = synthesize({.duration = 2}, hits);
    for (const Hit& hit : hits) {
        SCOPED_TRACE(hit.t);
        const auto expected = static_cast<std::size_t>(std::lround(hit.t * 48000));
        const std::size_t heard = onset(samples, expected - 480, 32);
        EXPECT_GE(heard, expected);
        EXPECT_LE(heard, expected + 48);   // 1 ms at 48 kHz
    }
}

// 300 discs hitting at once, again and again, at full strength: the limiter keeps every sample
// at or under the volume, so nothing clips; it is loud all the same.
TEST(SynthesizerTest, ThreeHundredHitsAtOnceNeverReachFullScale) {
    std::vector<Hit> hits;
    for (int round = 0; round < 10; ++round) {
        for (int i = 0; i < 300; ++i) {
            hits.push_back({.t = 0.05 + 0.1 * round + 1e-5 * i, .speed = 10,
                            .size = 0.02 + 0.001 * (i % 50), .pan = -1 + 2.0 * (i % 7) / 6});
        }
    }
    for (const double volume : {0.8, 1.0}) {
        SCOPED_TRACE(volume);
        const auto samples = synthesize({.duration = 1.5, .volume = volume}, hits);
        const int peak = std::abs(*std::max_element(samples.begin(), samples.end(),
                                                    [](std::int16_t a, std::int16_t b) {
                                                        return std::abs(a) < std::abs(b);
                                                    }));
        EXPECT_LE(peak, static_cast<int>(std::lround(volume * 32767)));
        EXPECT_LT(peak, 32767 + (volume < 1 ? 0 : 1));
        EXPECT_GT(peak, volume * 32767 * 0.9);
    }
}

TEST(SynthesizerTest, LoudnessGrowsWithSpeedOnALogScaleAndPitchFallsWithSize) {
    EXPECT_EQ(hit_gain(0.0005), 0.0);
    EXPECT_NEAR(hit_gain(0.001), 0.01, 1e-12);   // -40 dB: a tap is still heard
    EXPECT_NEAR(hit_gain(0.1), 0.1, 1e-12);
    EXPECT_EQ(hit_gain(10), 1.0);
    EXPECT_EQ(hit_gain(1000), 1.0);
    EXPECT_GT(hit_pitch(0.01), hit_pitch(0.1));
    EXPECT_GT(hit_pitch(0.1), hit_pitch(1.0));
    EXPECT_NEAR(hit_pitch(0.1), 520, 1e-9);
}

TEST(SynthesizerTest, PanPlacesTheSoundLeftOrRight) {
    const auto energy = [](const std::vector<std::int16_t>& samples, int channel) {
        double sum = 0;
        for (std::size_t i = static_cast<std::size_t>(channel); i < samples.size(); i += 2)
            sum += static_cast<double>(samples[i]) * samples[i];
        return sum;
    };
    const auto left = synthesize({.duration = 0.5}, {{.t = 0.1, .speed = 2, .pan = -0.8}});
    EXPECT_GT(energy(left, 0), 10 * energy(left, 1));
    const auto centre = synthesize({.duration = 0.5}, {{.t = 0.1, .speed = 2, .pan = 0}});
    EXPECT_NEAR(energy(centre, 0) / energy(centre, 1), 1.0, 1e-3);
}

// The same hits give the same samples, rendered in big or small steps.
TEST(SynthesizerTest, TheSameHitsGiveTheSameSamples) {
    std::vector<Hit> hits;
    for (int i = 0; i < 200; ++i) {
        hits.push_back({.t = 0.01 * i + 0.003, .speed = 0.01 * (i % 40 + 1),
                        .size = 0.03 + 0.01 * (i % 9), .pan = std::sin(i)});
    }
    const SynthDef def{.duration = 2.5, .voices = 8};
    const auto once = synthesize(def, hits, 1.0 / 60);
    EXPECT_EQ(synthesize(def, hits, 1.0 / 60), once);
    EXPECT_EQ(synthesize(def, hits, 1.0 / 7), once);
    Synthesizer counting(def);
    for (const Hit& hit : hits) counting.add(hit);
    EXPECT_TRUE(counting.finish([](std::span<const std::int16_t>) { return true; }));
    EXPECT_GT(counting.hits_dropped(), 0u);   // 8 voices for 200 overlapping hits: some stolen
}

}  // namespace
}  // namespace discreel::audio
