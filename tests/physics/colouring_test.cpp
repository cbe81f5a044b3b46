// White-box: the resting stage's colouring (colour_greedily, contact_solver.hpp). The solver runs the
// rows of one colour side by side in vector lanes, which gives the same result as one after the
// other only if no two rows of a colour share a moving body: no two contacts of a colour may
// share a disc (wall features never move, so any number may).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "broad_phase.hpp"
#include "discreel/physics.hpp"
#include "geometry.hpp"
#include "scenes.hpp"
#include "contact_solver.hpp"

namespace discreel::physics::detail {
namespace {

Contact contact(std::uint32_t a, std::uint32_t b) {
    Contact c;
    c.a = a;
    c.b = b;
    return c;
}

std::vector<std::uint8_t> colour(const std::vector<Contact>& contacts, std::size_t disc_count) {
    std::vector<std::uint64_t> used;
    std::vector<std::uint8_t> colour_of;
    colour_greedily(contacts, disc_count, used, colour_of);
    EXPECT_EQ(colour_of.size(), contacts.size());
    return colour_of;
}

// The promises: within a colour below overflow_colour no disc is in two contacts; and each
// contact has the lowest colour that none of its discs' earlier contacts has (which keeps the
// colours few: at most one more than the most contacts of a disc), or overflow_colour if
// they have them all.
void expect_valid_colouring(const std::vector<Contact>& contacts, std::size_t disc_count,
                            const std::vector<std::uint8_t>& colour_of) {
    ASSERT_EQ(colour_of.size(), contacts.size());
    // Per disc, the colours of its contacts so far (bit c).
    std::vector<std::uint64_t> taken(disc_count, 0);
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const Contact& c = contacts[i];
        const bool b_disc = c.b < disc_count;
        const std::uint64_t neighbours = taken[c.a] | (b_disc ? taken[c.b] : 0);
        unsigned lowest_free = 0;
        while (lowest_free < overflow_colour && (neighbours >> lowest_free & 1) != 0) {
            ++lowest_free;
        }
        ASSERT_EQ(unsigned{colour_of[i]}, lowest_free)
            << "contact " << i << " (" << c.a << ", " << c.b << ")";
        if (colour_of[i] == overflow_colour) continue;
        const std::uint64_t bit = std::uint64_t{1} << colour_of[i];
        ASSERT_EQ(taken[c.a] & bit, 0u) << "disc " << c.a << " twice in colour " << +colour_of[i];
        taken[c.a] |= bit;
        if (b_disc) {
            ASSERT_EQ(taken[c.b] & bit, 0u)
                << "disc " << c.b << " twice in colour " << +colour_of[i];
            taken[c.b] |= bit;
        }
    }
}

TEST(Colouring, ContactsOfAPileShareNoDiscWithinAColour) {
    // The broad phase's list for a crowd in a box (pegs and walls included), as the solver
    // gets it.
    const WorldDef def = testing::pile({.count = 2000, .radius = 0.2, .spacing = 0.41});
    std::vector<Body> bodies;
    for (const BodyDef& d : def.bodies) {
        Body b;
        b.x = V2(d.position.x, d.position.y);
        b.radius = d.radius;
        b.motion = bodies.size() % 10 == 0 ? Motion::fixed : Motion::dynamic;
        bodies.push_back(b);
    }
    const std::size_t disc_count = bodies.size();
    const std::vector<Feature> features = features_of(def.walls);
    bodies.resize(disc_count + features.size());
    BroadPhase broad;
    std::vector<Contact> contacts;
    broad.update(bodies, disc_count, features, 1.0 / 480, 9.81, contacts, false);
    ASSERT_GT(contacts.size(), disc_count);
    const std::vector<std::uint8_t> colour_of = colour(contacts, disc_count);
    expect_valid_colouring(contacts, disc_count, colour_of);
    // A grid: at most eight neighbours and a wall or two, so no overflow.
    EXPECT_LT(*std::max_element(colour_of.begin(), colour_of.end()), 12);
}

TEST(Colouring, RandomContactListsShareNoDiscWithinAColour) {
    std::mt19937_64 rng(99);
    for (int round = 0; round < 20; ++round) {
        const std::size_t discs = 2 + rng() % 300;
        const std::size_t features = rng() % 6;
        std::vector<Contact> contacts;
        for (std::size_t n = rng() % 2000; n > 0; --n) {
            const auto a = static_cast<std::uint32_t>(rng() % discs);
            const auto b = static_cast<std::uint32_t>(rng() % (discs + features));
            if (a != b) contacts.push_back(contact(std::min(a, b), std::max(a, b)));
        }
        std::sort(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) {
            return x.a != y.a ? x.a < y.a : x.b < y.b;
        });
        SCOPED_TRACE(round);
        expect_valid_colouring(contacts, discs, colour(contacts, discs));
    }
}

TEST(Colouring, ManyDiscsOnOneWallShareAColour) {
    // Wall features take no colour: one wall's contacts are all independent.
    std::vector<Contact> contacts;
    for (std::uint32_t disc = 0; disc < 100; ++disc) contacts.push_back(contact(disc, 100));
    const std::vector<std::uint8_t> colour_of = colour(contacts, 100);
    for (const std::uint8_t c : colour_of) EXPECT_EQ(c, 0);
}

TEST(Colouring, ADiscInMoreContactsThanColoursOverflows) {
    // Disc 0 touches 100 others: its first 64 contacts take the 64 colours, the rest go to the
    // overflow group, whose rows the solver runs one at a time.
    std::vector<Contact> contacts;
    for (std::uint32_t other = 1; other <= 100; ++other) contacts.push_back(contact(0, other));
    contacts.push_back(contact(1, 2));  // disc 1 has colour 0, disc 2 colour 1: it takes 2
    const std::vector<std::uint8_t> colour_of = colour(contacts, 101);
    expect_valid_colouring(contacts, 101, colour_of);
    for (std::size_t k = 0; k < 100; ++k) {
        EXPECT_EQ(std::size_t{colour_of[k]}, std::min<std::size_t>(k, overflow_colour)) << k;
    }
    EXPECT_EQ(colour_of[100], 2);
}

}  // namespace
}  // namespace discreel::physics::detail
