// Modal synthesis of contact sounds and the limiter that keeps their mix below full scale.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "discreel/audio.hpp"

namespace discreel::audio {
namespace {

// A struck circular plate's lowest modes (frequency ratios) with the amplitudes and decay
// exponents that make a short "tock": higher partials are quieter and die sooner.
constexpr std::array<double, 4> partial_ratio{1.0, 1.594, 2.136, 2.653};
constexpr std::array<double, 4> partial_amplitude{1.0, 0.55, 0.35, 0.2};
constexpr double voice_level = 0.35;        // a full-strength hit before the limiter
constexpr double attack_seconds = 0.0005;   // a linear rise, so no hit starts with a click
constexpr double steal_fade_seconds = 0.002;
constexpr double release_seconds = 0.05;    // the limiter's return to unity gain
constexpr double lookahead_seconds = 0.001; // how far ahead the limiter sees a peak coming
constexpr double silent = 1e-4;             // a voice below this is over (-80 dB)

struct Partial {
    double amplitude = 0;
    double decay = 1;                       // per sample
    double cos_step = 1, sin_step = 0;      // rotation by the partial's angular step
    double c = 1, s = 0;                    // the oscillator: (cos, sin) of its phase
};

struct Voice {
    std::size_t start = 0;                  // frame of its first sample
    std::size_t age = 0;                    // samples played
    double left = 0, right = 0;             // pan gains
    double fade = 1;                        // 1; below once stolen, to silence in 2 ms
    double fade_step = 1;
    std::vector<Partial> partials;

    double level() const { return partials.empty() ? 0.0 : partials.front().amplitude * fade; }
};

struct Frame {
    double left = 0, right = 0;
    double allowed = 1;                     // the gain that keeps this frame under the ceiling
};

}  // namespace

double hit_gain(double speed) {
    if (!(speed >= 0.001)) return 0.0;
    // Loudness on a log scale: 1 mm/s to 10 m/s (80 dB of speed) become -40 to 0 dB.
    return std::min(1.0, std::sqrt(speed / 10.0));
}

double hit_pitch(double size) {
    // Pitch falls as the body grows, as a plate's does with its diameter (here more gently,
    // so that large and small bodies both stay in a comfortable range).
    if (!(size > 0)) return 4000.0;
    return std::clamp(520.0 * std::sqrt(0.1 / size), 80.0, 4000.0);
}

struct Synthesizer::Impl {
    explicit Impl(const SynthDef& d)
        : def(d),
          total(static_cast<std::size_t>(std::max(0.0, std::round(d.duration * d.sample_rate)))),
          lookahead(std::max<std::size_t>(1, static_cast<std::size_t>(
                                                 std::lround(lookahead_seconds * d.sample_rate)))),
          attack(std::max(1.0, attack_seconds * d.sample_rate)),
          release_step(1.0 / (release_seconds * d.sample_rate)),
          ceiling(std::clamp(d.volume, 0.0, 1.0)) {}

    SynthDef def;
    std::size_t total;                 // frames in the soundtrack
    std::size_t lookahead;             // frames
    double attack;                     // frames
    double release_step;               // gain per frame
    double ceiling;                    // of full scale
    std::vector<Hit> waiting;          // added, not started; in time order
    std::size_t next_waiting = 0;
    std::vector<Voice> voices;
    std::vector<Frame> mixed;          // frames [out_pos, mix_pos)
    std::size_t mixed_start = 0;       // index in `mixed` of frame out_pos
    std::size_t mix_pos = 0;           // frames mixed
    std::size_t out_pos = 0;           // frames written
    double gain = 1;                   // the limiter's, at out_pos - 1
    std::size_t dropped = 0;
    std::vector<std::int16_t> block;

    Voice make_voice(const Hit& hit, std::size_t start) const {
        Voice voice;
        voice.start = start;
        const double pan = std::clamp(hit.pan, -1.0, 1.0);
        const double angle = (pan + 1.0) * M_PI / 4.0;   // equal power: left² + right² = 1
        voice.left = std::cos(angle);
        voice.right = std::sin(angle);
        const double f0 = hit_pitch(hit.size);
        const double tau0 =
            std::clamp(0.12 * std::sqrt(std::max(hit.size, 1e-6) / 0.1), 0.03, 0.6);
        const double level = voice_level * hit_gain(hit.speed);
        const double rate = def.sample_rate;
        for (std::size_t k = 0; k < partial_ratio.size(); ++k) {
            const double f = f0 * partial_ratio[k];
            if (f >= 0.45 * rate) break;
            const double step = 2.0 * M_PI * f / rate;
            const double tau = tau0 / std::pow(partial_ratio[k], 1.5);
            voice.partials.push_back({.amplitude = level * partial_amplitude[k],
                                      .decay = std::exp(-1.0 / (tau * rate)),
                                      .cos_step = std::cos(step),
                                      .sin_step = std::sin(step)});
        }
        return voice;
    }

    // Starts the hits whose first sample is `frame`, taking the quietest voice's place (it fades
    // out over 2 ms) when all are sounding and the new hit is louder.
    void start_hits(std::size_t frame) {
        while (next_waiting < waiting.size()) {
            const Hit& hit = waiting[next_waiting];
            const std::size_t start = frame_of(hit.t);
            if (start > frame) break;
            ++next_waiting;
            if (start < frame || hit_gain(hit.speed) <= 0) {
                ++dropped;
                continue;
            }
            Voice voice = make_voice(hit, start);
            const auto sounding = std::count_if(voices.begin(), voices.end(),
                                                [](const Voice& v) { return v.fade == 1; });
            if (sounding >= def.voices) {
                auto quietest = voices.end();
                for (auto it = voices.begin(); it != voices.end(); ++it) {
                    if (it->fade == 1 && (quietest == voices.end() || it->level() < quietest->level()))
                        quietest = it;
                }
                if (quietest == voices.end() || quietest->level() >= voice.level()) {
                    ++dropped;
                    continue;
                }
                quietest->fade_step = std::exp(-1.0 / (steal_fade_seconds * def.sample_rate));
                quietest->fade *= quietest->fade_step;
                ++dropped;
            }
            voices.push_back(std::move(voice));
        }
        if (next_waiting > 4096) {
            waiting.erase(waiting.begin(), waiting.begin() + static_cast<std::ptrdiff_t>(next_waiting));
            next_waiting = 0;
        }
    }

    Frame mix_one(std::size_t frame) {
        start_hits(frame);
        Frame out;
        for (Voice& voice : voices) {
            const double rise = std::min(1.0, static_cast<double>(voice.age + 1) / attack);
            double sample = 0;
            for (Partial& p : voice.partials) {
                sample += p.amplitude * p.s;
                const double c = p.c * p.cos_step - p.s * p.sin_step;
                p.s = p.s * p.cos_step + p.c * p.sin_step;
                p.c = c;
                p.amplitude *= p.decay;
            }
            sample *= rise * voice.fade;
            out.left += sample * voice.left;
            out.right += sample * voice.right;
            ++voice.age;
            if (voice.fade < 1) voice.fade *= voice.fade_step;
        }
        std::erase_if(voices, [](const Voice& v) { return v.level() < silent; });
        const double peak = std::max(std::abs(out.left), std::abs(out.right));
        out.allowed = peak > ceiling ? ceiling / peak : 1.0;
        return out;
    }

    void mix_until(std::size_t frame) {
        for (; mix_pos < frame; ++mix_pos) mixed.push_back(mix_one(mix_pos));
    }

    // The gain for frame out_pos: at most what each frame in the look-ahead window allows,
    // reached by a straight ramp over the window, and released slowly.
    double next_gain() const {
        double target = 1.0;
        for (std::size_t k = 0; k <= lookahead; ++k) {
            const std::size_t i = mixed_start + k;
            if (i >= mixed.size()) break;
            const double allowed = mixed[i].allowed;
            const double ramp = allowed + (1.0 - allowed) * static_cast<double>(k) / lookahead;
            target = std::min(target, ramp);
        }
        return std::min(target, gain + release_step);
    }

    static std::int16_t to_pcm(double x) {
        return static_cast<std::int16_t>(std::clamp(std::lround(x * 32767.0), -32767L, 32767L));
    }

    // Writes frames [out_pos, frame), which must be mixed along with their look-ahead.
    bool write_until(std::size_t frame, const Write& write) {
        block.clear();
        while (out_pos < frame) {
            gain = next_gain();
            const Frame& f = mixed[mixed_start];
            block.push_back(to_pcm(f.left * gain));
            block.push_back(to_pcm(f.right * gain));
            ++mixed_start;
            ++out_pos;
            if (block.size() >= 8192 || out_pos == frame) {
                if (!write(block)) return false;
                block.clear();
            }
        }
        if (mixed_start > 4096) {
            mixed.erase(mixed.begin(), mixed.begin() + static_cast<std::ptrdiff_t>(mixed_start));
            mixed_start = 0;
        }
        return true;
    }

    std::size_t frame_of(double t) const {
        if (!(t > 0)) return 0;
        const double frame = std::round(t * def.sample_rate);
        return frame >= static_cast<double>(total) ? total : static_cast<std::size_t>(frame);
    }
};

Synthesizer::Synthesizer(const SynthDef& def) : impl_(std::make_unique<Impl>(def)) {}
Synthesizer::~Synthesizer() = default;
Synthesizer::Synthesizer(Synthesizer&&) noexcept = default;
Synthesizer& Synthesizer::operator=(Synthesizer&&) noexcept = default;

void Synthesizer::add(const Hit& hit) {
    if (impl_->frame_of(hit.t) >= impl_->total) {
        ++impl_->dropped;
        return;
    }
    impl_->waiting.push_back(hit);
}

bool Synthesizer::render_until(std::size_t frame, const Write& write) {
    Impl& s = *impl_;
    frame = std::min(frame, s.total);
    s.mix_until(frame);
    if (frame < s.lookahead) return true;
    const std::size_t ready = std::min(frame - s.lookahead, s.total);
    if (ready <= s.out_pos) return true;
    return s.write_until(ready, write);
}

bool Synthesizer::finish(const Write& write) {
    Impl& s = *impl_;
    s.mix_until(s.total);
    return s.write_until(s.total, write);
}

std::size_t Synthesizer::frame_of(double t) const { return impl_->frame_of(t); }
std::size_t Synthesizer::frames() const { return impl_->total; }
std::size_t Synthesizer::hits_dropped() const { return impl_->dropped; }

}  // namespace discreel::audio
