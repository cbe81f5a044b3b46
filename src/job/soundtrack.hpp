#pragma once
// A scene's soundtrack: its physics played from t = 0, each new contact heard as a hit
// (docs/sound.md), written as 48 kHz stereo 16-bit PCM.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "discreel/encode.hpp"
#include "discreel/job.hpp"

namespace discreel::job {

constexpr int sound_rate = 48000;   // samples per second

// The first sample of `frame`: round(frame * rate / fps). Frames [a, b] sound from sample_of(a)
// to sample_of(b + 1), so the segments' sounds tile the clip's.
std::size_t sample_of_frame(int frame, int fps);

// Gives the sound of frames `range` (resolved) of `scene` to `write` (interleaved stereo, in
// order, in blocks). Stops when `should_stop` says so, or with write's first error.
using SampleWriter = std::function<Status(std::span<const std::int16_t>)>;
Status write_soundtrack(const scene::Scene& scene, FrameRange range, const SampleWriter& write,
                        const std::function<bool()>& should_stop);

// job::render of a .wav: the soundtrack alone, committed.
Expected<RenderSummary> render_soundtrack(const RenderDef& def, FrameRange range);

}  // namespace discreel::job
