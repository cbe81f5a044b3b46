// The soundtrack alone (-o F.wav, docs/sound.md): through the binary (it builds each frame's
// description as a render does, so GL in the suite name); ffprobe checks the stream, and the
// samples are read from the file's data chunk.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

#include "test_support.hpp"

namespace discreel {
namespace {

using testing::read_file;
using testing::run_command;
using testing::TempDir;
using testing::write_file;

const std::string bin = DISCREEL_BIN;

// The interleaved samples of a 48 kHz stereo 16-bit WAV, checked by ffprobe.
std::vector<std::int16_t> samples_of(const std::string& path) {
    const auto probe = run_command({"ffprobe", "-v", "error", "-show_entries",
                                    "stream=codec_name,sample_rate,channels", "-of", "csv=p=0",
                                    path});
    EXPECT_EQ(probe.out, "pcm_s16le,48000,2\n");
    const std::string bytes = read_file(path);
    const std::size_t data = bytes.find("data");
    EXPECT_NE(data, std::string::npos);
    std::vector<std::int16_t> samples((bytes.size() - data - 8) / 2);
    std::memcpy(samples.data(), bytes.data() + data + 8, samples.size() * 2);
    return samples;
}

// A disc crossing a 4 m box at 3 m/s hits a wall every 1.27 s, long enough for each sound to
// die away: each onset in the WAV is within 1 ms of its row in the events file.
TEST(SoundGLTest, OnsetsAreTheContactsTimesWithinOneMillisecond) {
    TempDir dir;
    write_file(dir / "s.yaml", "version: 1\nvideo: {size: [160, 90], fps: 30, duration: 4}\n"
                               "physics: {gravity: [0, 0], restitution: 1}\n"
                               "walls:\n  - box: [[0, 0], [4, 2.25]]\n"
                               "discs:\n  - {position: [2, 1], velocity: [3, 0], radius: 0.1}\n");
    auto run = run_command({bin, "render", dir / "s.yaml", "-o", dir / "s.wav"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.out.rfind("wrote " + dir / "s.wav" + ": 4.00 s of sound, 48 kHz stereo (", 0), 0u)
        << run.out;
    run = run_command({bin, "simulate", dir / "s.yaml", "--events", dir / "e.csv"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::vector<double> contacts;
    std::istringstream rows(read_file(dir / "e.csv"));
    std::string row;
    std::getline(rows, row);   // header
    while (std::getline(rows, row)) contacts.push_back(std::stod(row.substr(0, row.find(','))));
    ASSERT_EQ(contacts.size(), 3u);

    const auto samples = samples_of(dir / "s.wav");
    ASSERT_EQ(samples.size(), 2u * 4 * 48000);
    std::vector<double> onsets;   // the first loud sample after 0.5 s of quiet
    std::size_t last_loud = 0;
    bool heard = false;
    for (std::size_t frame = 0; 2 * frame < samples.size(); ++frame) {
        if (std::abs(samples[2 * frame]) <= 32 && std::abs(samples[2 * frame + 1]) <= 32) continue;
        if (!heard || frame - last_loud > 24000) onsets.push_back(frame / 48000.0);
        heard = true;
        last_loud = frame;
    }
    ASSERT_EQ(onsets.size(), contacts.size());
    for (std::size_t i = 0; i < onsets.size(); ++i) EXPECT_NEAR(onsets[i], contacts[i], 0.001);
    // Same scene, same bytes.
    ASSERT_EQ(run_command({bin, "render", dir / "s.yaml", "-o", dir / "again.wav", "-q"}).exit_code, 0);
    EXPECT_EQ(read_file(dir / "again.wav"), read_file(dir / "s.wav"));
}

// A range of frames is heard as in the whole clip: its samples are the whole soundtrack's
// between its first frame and the one after its last, also where a hit rings across the cut.
TEST(SoundGLTest, ARangeOfFramesIsASliceOfTheWholeSoundtrack) {
    TempDir dir;
    write_file(dir / "s.yaml", "version: 1\nvideo: {size: [160, 90], fps: 30, duration: 4}\n"
                               "physics: {gravity: [0, 0], restitution: 1}\n"
                               "walls:\n  - box: [[0, 0], [4, 2.25]]\n"
                               "discs:\n  - {position: [2, 1], velocity: [3, 0], radius: 0.1}\n");
    ASSERT_EQ(run_command({bin, "render", dir / "s.yaml", "-o", dir / "all.wav", "-q"}).exit_code,
              0);
    // Frames 40..79: the hit at 1.27 s (frame 38) still rings at the start, the next (2.6 s,
    // frame 78) comes just before the end.
    ASSERT_EQ(run_command({bin, "render", dir / "s.yaml", "--frames", "40-79", "-o",
                           dir / "part.wav", "-q"})
                  .exit_code,
              0);
    const auto all = samples_of(dir / "all.wav");
    const auto part = samples_of(dir / "part.wav");
    ASSERT_EQ(part.size(), 2u * 40 * 1600);   // 40 frames of 1 600 samples, two channels
    const std::vector<std::int16_t> slice(all.begin() + 2 * 40 * 1600,
                                          all.begin() + 2 * 80 * 1600);
    EXPECT_TRUE(part == slice);
    EXPECT_TRUE(std::any_of(part.begin(), part.end(), [](std::int16_t v) { return v != 0; }));
}

TEST(SoundGLTest, NoContactsIsDigitalSilence) {
    TempDir dir;
    write_file(dir / "s.yaml", "version: 1\nvideo: {duration: 1}\naudio: {volume: 1}\n"
                               "discs:\n  - {position: [0, 0], velocity: [1, 0], radius: 0.1}\n");
    ASSERT_EQ(run_command({bin, "render", dir / "s.yaml", "-o", dir / "s.wav", "-q"}).exit_code, 0);
    const auto samples = samples_of(dir / "s.wav");
    EXPECT_EQ(samples.size(), 2u * 48000);
    EXPECT_EQ(std::count(samples.begin(), samples.end(), 0), static_cast<long>(samples.size()));
}

// 300 discs bouncing in a box, many contacts at once: no sample reaches the volume, let alone
// full scale, and the limiter is working (the loudest is within 10 % of the volume).
TEST(SoundGLTest, ThreeHundredBouncingDiscsNeverClip) {
    TempDir dir;
    write_file(dir / "s.yaml", "version: 1\nvideo: {size: [160, 90], fps: 30, duration: 2}\n"
                               "audio: {volume: 0.9}\nphysics: {restitution: 0.9}\n"
                               "walls:\n  - box: [[0, 0], [8, 4.5]]\n"
                               "discs:\n  - random: {count: 300, region: [[0.2, 0.2], [7.8, 4.3]],"
                               " radius: [0.05, 0.09], speed: [2, 6]}\n");
    const auto run = run_command({bin, "render", dir / "s.yaml", "-o", dir / "s.wav", "-q"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto samples = samples_of(dir / "s.wav");
    int peak = 0;
    for (const std::int16_t s : samples) peak = std::max(peak, std::abs(static_cast<int>(s)));
    EXPECT_LE(peak, 29490);   // round(0.9 * 32767)
    EXPECT_GT(peak, 26500);
}

// A stream on standard output carries the sound too (Matroska and fragmented MP4), the same
// bytes twice; a reader that stops early ends the render (SIGPIPE) without a hang, though the
// sound's thread is then waiting on a full queue.
TEST(SoundGLTest, AStreamOnStandardOutputCarriesTheSound) {
    TempDir dir;
    write_file(dir / "s.yaml", "version: 1\nvideo: {size: [160, 90], fps: 30, duration: 2}\n"
                               "audio: {enabled: true}\n"
                               "walls:\n  - box: [[0, 0], [4, 2.25]]\n"
                               "discs:\n  - {position: [2, 1], velocity: [5, 2], radius: 0.2}\n");
    for (const std::string container : {"mkv", "mp4"}) {
        SCOPED_TRACE(container);
        const auto first = run_command({bin, "render", dir / "s.yaml", "-o", "-", "--format",
                                        container, "-q"});
        ASSERT_EQ(first.exit_code, 0) << first.err;
        const auto second = run_command({bin, "render", dir / "s.yaml", "-o", "-", "--format",
                                         container, "-q"});
        EXPECT_EQ(first.out, second.out);
        write_file(dir / ("s." + container), first.out);
        const auto streams = run_command({"ffprobe", "-v", "error", "-show_entries",
                                          "stream=codec_name,sample_rate", "-of", "csv=p=0",
                                          dir / ("s." + container)});
        EXPECT_EQ(streams.out, "h264\naac,48000\n");
    }
    const auto started = std::chrono::steady_clock::now();
    const auto cut = run_command(
        {"bash", "-c", "\"$0\" render \"$1\" -o - --duration 600 | head -c 20000 >/dev/null; "
                       "exit ${PIPESTATUS[0]}",
         bin, dir / "s.yaml"});
    EXPECT_EQ(cut.exit_code, 128 + 13) << cut.err;   // SIGPIPE's
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(20));
}

TEST(SoundGLTest, EncoderSettingsAndBadVolumesAreRefused) {
    TempDir dir;
    write_file(dir / "s.yaml", "version: 1\naudio: {volume: 1.5}\n");
    auto run = run_command({bin, "render", dir / "s.yaml", "-o", dir / "s.wav"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, dir / "s.yaml" + ":2:17: audio.volume: must be between 0 and 1, got 1.5\n");
    write_file(dir / "s.yaml", "version: 1\n");
    run = run_command({bin, "render", dir / "s.yaml", "-o", dir / "s.wav", "--crf", "20"});
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(run.err, "discreel: crf does not apply to WAV (the soundtrack alone)\n");
    EXPECT_EQ(testing::directory_entries(dir.path()), std::vector<std::string>{"s.yaml"});
}

}  // namespace
}  // namespace discreel
