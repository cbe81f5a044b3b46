#pragma once
// The lane types of the contact solver's blocks and the few shuffles it needs, by name. The
// arithmetic uses GCC/Clang vector extensions (vector_size), which every target compiles: a
// vector wider than the hardware's registers is split into several. A shuffle only moves lanes,
// so whichever instructions a target picks for it, the bits are the same.
//
// With __builtin_shufflevector (Clang, GCC 12 on) the compiler sees the whole pattern and picks
// the instructions; without it, or with DISCREEL_SIMD_GENERIC defined (the `arch` tests build
// that way to check it), each lane is copied on its own.
//
// "Half" is a 128-bit half of a 256-bit vector, as in AVX's in-lane unpack and shuffle
// instructions: unpack_low and low_pairs work within each half, which is what makes them one
// instruction there.
//
// The functions take and return 256-bit vectors by value, which GCC and Clang warn about
// (-Wpsabi) where AVX is off: such a call would pass them differently with AVX on. They are
// always inlined, so no such call exists; a file that calls them is built with -Wno-psabi.
#if !defined(DISCREEL_SIMD_GENERIC) && defined(__has_builtin)
#if __has_builtin(__builtin_shufflevector) && __has_builtin(__builtin_convertvector)
#define DISCREEL_SIMD_BUILTINS 1
#endif
#endif

#include <cstdint>

namespace discreel::physics::detail::simd {

using Double4 = double __attribute__((vector_size(32)));
using Float8 = float __attribute__((vector_size(32)));
using Float4 = float __attribute__((vector_size(16)));

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace lanes {
template <class V>
constexpr int count = static_cast<int>(sizeof(V) / sizeof(V{}[0]));

// Lane i of a and b side by side (a's lanes first).
template <int i, class V>
[[gnu::always_inline]] inline auto of_pair(const V& a, const V& b) {
    if constexpr (i < count<V>) {
        return a[i];
    } else {
        return b[i - count<V>];
    }
}

// Lanes i... of a and b side by side, as an R.
template <class R, int... i, class V>
[[gnu::always_inline]] inline R shuffle(const V& a, const V& b) {
    static_assert(sizeof...(i) == count<R>);
#ifdef DISCREEL_SIMD_BUILTINS
    return __builtin_shufflevector(a, b, i...);
#else
    return R{of_pair<i>(a, b)...};
#endif
}
}  // namespace lanes

// a0 b0 a2 b2: the low lane of each half of a and b.
[[gnu::always_inline]] inline Double4 unpack_low(const Double4& a, const Double4& b) {
    return lanes::shuffle<Double4, 0, 4, 2, 6>(a, b);
}
// a1 b1 a3 b3: the high lane of each half of a and b.
[[gnu::always_inline]] inline Double4 unpack_high(const Double4& a, const Double4& b) {
    return lanes::shuffle<Double4, 1, 5, 3, 7>(a, b);
}
// a0 a1 b0 b1: the low halves of a and b.
[[gnu::always_inline]] inline Double4 low_halves(const Double4& a, const Double4& b) {
    return lanes::shuffle<Double4, 0, 1, 4, 5>(a, b);
}
// a2 a3 b2 b3: the high halves of a and b.
[[gnu::always_inline]] inline Double4 high_halves(const Double4& a, const Double4& b) {
    return lanes::shuffle<Double4, 2, 3, 6, 7>(a, b);
}

// a0 b0 a1 b1 | a4 b4 a5 b5: the low two lanes of each half of a and b, interleaved.
[[gnu::always_inline]] inline Float8 unpack_low(const Float8& a, const Float8& b) {
    return lanes::shuffle<Float8, 0, 8, 1, 9, 4, 12, 5, 13>(a, b);
}
// a2 b2 a3 b3 | a6 b6 a7 b7: the high two lanes of each half of a and b, interleaved.
[[gnu::always_inline]] inline Float8 unpack_high(const Float8& a, const Float8& b) {
    return lanes::shuffle<Float8, 2, 10, 3, 11, 6, 14, 7, 15>(a, b);
}
// a0 a1 b0 b1 | a4 a5 b4 b5: the low pair of each half of a, then of b.
[[gnu::always_inline]] inline Float8 low_pairs(const Float8& a, const Float8& b) {
    return lanes::shuffle<Float8, 0, 1, 8, 9, 4, 5, 12, 13>(a, b);
}
// a2 a3 b2 b3 | a6 a7 b6 b7: the high pair of each half of a, then of b.
[[gnu::always_inline]] inline Float8 high_pairs(const Float8& a, const Float8& b) {
    return lanes::shuffle<Float8, 2, 3, 10, 11, 6, 7, 14, 15>(a, b);
}

// low0..3 high0..3: two four-float vectors as the halves of one.
[[gnu::always_inline]] inline Float8 join(const Float4& low, const Float4& high) {
    return lanes::shuffle<Float8, 0, 1, 2, 3, 4, 5, 6, 7>(low, high);
}
// The halves of v.
[[gnu::always_inline]] inline Float4 low_half(const Float8& v) {
    return lanes::shuffle<Float4, 0, 1, 2, 3>(v, v);
}
[[gnu::always_inline]] inline Float4 high_half(const Float8& v) {
    return lanes::shuffle<Float4, 4, 5, 6, 7>(v, v);
}

// Each lane rounded to the nearest float (IEEE, like static_cast<float>).
[[gnu::always_inline]] inline Float4 to_floats(const Double4& v) {
#ifdef DISCREEL_SIMD_BUILTINS
    return __builtin_convertvector(v, Float4);
#else
    return Float4{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]),
                  static_cast<float>(v[3])};
#endif
}

// Eight 16-byte records (a `packed` Float4 each) gathered into four vectors of eight lanes:
// lane l of x, y, z, w is record at[l]'s first to fourth float. Records l and l + 4 share a
// register and an in-lane 4x4 transpose of each half does the rest, so each record is read
// with one access of its own size.
template <class Record>
[[gnu::always_inline]] inline void gather8(const Record* base, const std::uint32_t (&at)[8],
                                           Float8& x, Float8& y, Float8& z, Float8& w) {
    const Float8 r04 = join(base[at[0]].packed, base[at[4]].packed);
    const Float8 r15 = join(base[at[1]].packed, base[at[5]].packed);
    const Float8 r26 = join(base[at[2]].packed, base[at[6]].packed);
    const Float8 r37 = join(base[at[3]].packed, base[at[7]].packed);
    const Float8 xy01 = unpack_low(r04, r15);
    const Float8 zw01 = unpack_high(r04, r15);
    const Float8 xy23 = unpack_low(r26, r37);
    const Float8 zw23 = unpack_high(r26, r37);
    x = low_pairs(xy01, xy23);
    y = high_pairs(xy01, xy23);
    z = low_pairs(zw01, zw23);
    w = high_pairs(zw01, zw23);
}

// The inverse of gather8: record at[l] gets lane l of x, y, z, w, one access each.
template <class Record>
[[gnu::always_inline]] inline void scatter8(Record* base, const std::uint32_t (&at)[8],
                                            const Float8& x, const Float8& y, const Float8& z,
                                            const Float8& w) {
    const Float8 xy01 = unpack_low(x, y);
    const Float8 zw01 = unpack_low(z, w);
    const Float8 xy23 = unpack_high(x, y);
    const Float8 zw23 = unpack_high(z, w);
    const Float8 r04 = low_pairs(xy01, zw01);
    const Float8 r15 = high_pairs(xy01, zw01);
    const Float8 r26 = low_pairs(xy23, zw23);
    const Float8 r37 = high_pairs(xy23, zw23);
    base[at[0]].packed = low_half(r04);
    base[at[1]].packed = low_half(r15);
    base[at[2]].packed = low_half(r26);
    base[at[3]].packed = low_half(r37);
    base[at[4]].packed = high_half(r04);
    base[at[5]].packed = high_half(r15);
    base[at[6]].packed = high_half(r26);
    base[at[7]].packed = high_half(r37);
}

#pragma GCC diagnostic pop

}  // namespace discreel::physics::detail::simd
