#pragma once
// Which pairs of bodies may touch (BodyDef::category and collides, a wall's too, and sensors):
// decided in the broad phase, so a pair left out costs no contact, sweep or overlap check.
#include <cstdint>
#include <vector>

#include "discreel/physics.hpp"

namespace discreel::physics::detail {

class PairFilter {
public:
    // Body i (bodies and the walls' fixed bodies, in one numbering) is of `category` (one bit)
    // and meets the categories of `collides` (bits); a sensor meets nothing, it watches.
    void set(std::uint32_t i, std::uint32_t category, std::uint32_t collides, bool sensor) {
        if (i >= category_.size()) {
            category_.resize(i + 1, physics::default_category);
            collides_.resize(i + 1, all_categories);
            sensor_.resize(i + 1, 0);
        }
        category_[i] = category;
        collides_[i] = collides;
        sensor_[i] = sensor ? 1 : 0;
        any_ = any_ || collides != all_categories || sensor;
        sensors_ = sensors_ || sensor;
    }
    // Whether any pair is left out (else every question below is a plain "no").
    bool any() const { return any_; }
    bool any_sensor() const { return sensors_; }
    // Whether each of bodies i and j is of a category the other meets.
    bool meets(std::uint32_t i, std::uint32_t j) const {
        return !any_ || i >= category_.size() || j >= category_.size() ||
               ((category_[i] & collides_[j]) != 0 && (category_[j] & collides_[i]) != 0);
    }
    // Whether bodies i and j make no contact: their categories exclude each other, or one is a
    // sensor.
    bool excludes(std::uint32_t i, std::uint32_t j) const {
        return any_ && (!meets(i, j) || sensor(i) || sensor(j));
    }
    // Whether the pair is watched for overlap: a sensor and a body it meets.
    bool senses(std::uint32_t i, std::uint32_t j) const {
        return sensors_ && (sensor(i) || sensor(j)) && meets(i, j);
    }
    bool sensor(std::uint32_t i) const { return i < sensor_.size() && sensor_[i] != 0; }

private:
    std::vector<std::uint32_t> category_, collides_;
    std::vector<unsigned char> sensor_;
    bool any_ = false, sensors_ = false;
};

}  // namespace discreel::physics::detail
