#pragma once
// Sound from the simulation: every new contact strikes a short percussive sound (modal
// synthesis: a few exponentially damped partials), mixed in stereo at 48 kHz, through a
// look-ahead limiter, into 16-bit samples. Plain C++ on doubles, no third-party library, no
// random numbers: the same hits give the same samples on every machine.
//     audio::Synthesizer synth({.duration = 8.0});
//     synth.add({.t = 0.5, .speed = 2.0, .size = 0.1, .pan = -0.3});   // in time order
//     synth.render_until(synth.sample_of(1.0), write);   // write(span<const int16_t>)
//     synth.finish(write);
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

namespace discreel::audio {

struct SynthDef {
    int sample_rate = 48000;       // Hz
    double duration = 0;           // seconds: the soundtrack has round(duration * rate) frames
    double volume = 0.8;           // 0..1 of full scale: the loudest a sample may be
    int voices = 48;               // sounds at once; a new one takes the quietest's place
};

// One contact, heard.
struct Hit {
    double t = 0;                  // seconds from the start: the sound's first sample
    double speed = 0;              // m/s: the speed change the contact gave the lighter body
    double size = 0.1;             // metres: the smaller body's radius; pitch falls with it
    double pan = 0;                // -1 (left) .. 1 (right)
};

// The loudness and pitch a hit gets, for tests and docs.
double hit_gain(double speed);     // 0 (inaudible, under 1 mm/s) .. 1 (10 m/s and above)
double hit_pitch(double size);     // Hz of the lowest partial

class Synthesizer {
public:
    // Interleaved stereo (left, right) 16-bit samples, in blocks of any length.
    using Write = std::function<bool(std::span<const std::int16_t>)>;

    explicit Synthesizer(const SynthDef& def);
    ~Synthesizer();
    Synthesizer(Synthesizer&&) noexcept;
    Synthesizer& operator=(Synthesizer&&) noexcept;

    // Hits in time order (ties in any order, kept as given); a hit earlier than the samples
    // already rendered, or past the end, is dropped.
    void add(const Hit& hit);
    // Renders the frames before `frame` (stereo frames, not samples) that no hit added later
    // can change: a hit is only heard from its own time on, so the caller passes the time up to
    // which every hit has been added. Returns false as soon as write() does.
    bool render_until(std::size_t frame, const Write& write);
    // Renders the rest, to round(duration * rate) frames.
    bool finish(const Write& write);

    std::size_t frame_of(double t) const;    // round(t * rate), clamped to the end
    std::size_t frames() const;              // the soundtrack's length in frames
    std::size_t hits_dropped() const;        // the quietest, when more than `voices` sounded

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace discreel::audio
