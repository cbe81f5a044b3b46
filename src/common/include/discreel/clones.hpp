#pragma once
// DISCREEL_CLONES, before a function: it is built twice, for AVX2 and for baseline x86-64, and
// the loader picks the version the CPU can run. Only for code whose results do not depend on
// the instructions (integer arithmetic, or IEEE operations in a fixed order without FMA, which
// -ffp-contract=off ensures), so that both versions give the same bits.
//
// Only on x86-64 with GCC or Clang, and only while the build's DISCREEL_AVX2_CLONES option is
// on (the default); elsewhere the function is built once, for the target's baseline.
#if defined(DISCREEL_AVX2_CLONES) && defined(__x86_64__) && defined(__GNUC__)
#define DISCREEL_CLONES [[gnu::target_clones("avx2", "default")]]
#else
#define DISCREEL_CLONES
#endif
