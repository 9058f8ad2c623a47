// API: internal (may change without notice; math shared with the shaders)
// The reference's numbers, for the CPU path tracer (src/render/sampler.hpp) and the GPU's
// (shaders/render/path_trace.comp) alike: the same seed, pixel and sample index give the same
// numbers on both. C++ and GLSL (see lang.h).
//
// Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4): sample s of a pixel takes its
// d-th pair of numbers from the first two dimensions of the Sobol sequence, the index shuffled
// and the point Owen-scrambled with a seed hashed from (key, d), the key hashed from the render's
// seed and the pixel (section 4, "padding" by independent shuffles).
#ifndef IBL_SHARED_PATH_SAMPLER_H
#define IBL_SHARED_PATH_SAMPLER_H
#include "ibl/shared/lang.h"
#include "ibl/shared/sampling.h"

#ifdef __cplusplus
namespace ibl {
// sobolDimension1Reversed from four byte tables (src/math/sampling.cpp): the same numbers, the
// CPU's samples 10-20 % faster.
std::uint32_t sobolDimension1ReversedFromTables(std::uint32_t index);
}  // namespace ibl
#define IBL_SOBOL_DIMENSION1_REVERSED(i) ::ibl::sobolDimension1ReversedFromTables(i)
#else
#define IBL_SOBOL_DIMENSION1_REVERSED(i) sobolDimension1Reversed(i)
#endif

IBL_BEGIN

// Burley 2020, listing 1: a permutation of the high bits that depends only on lower bits.
IBL_FN uint laineKarrasPermutation(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// A 32-bit integer hash (Wellons' "lowbias32").
IBL_FN uint hash32(uint x) {
  x ^= x >> 16u;
  x *= 0x7feb352du;
  x ^= x >> 15u;
  x *= 0x846ca68bu;
  x ^= x >> 16u;
  return x;
}

// Nested uniform scrambling of the bits of x read from the top (Burley 2020, listing 3).
IBL_FN uint owenScramble(uint x, uint seed) {
  return reverseBits(laineKarrasPermutation(reverseBits(x), seed));
}

// Point `index` of Sobol's dimension 1 (primitive polynomial x + 1), bit-reversed: the XOR of
// the direction numbers of the index's set bits, v_1 = 2^31 and v_k = v_(k-1) ^ (v_(k-1) >> 1),
// which reversed read r_1 = 1, r_k = r_(k-1) ^ (r_(k-1) << 1). (The CPU reads the same numbers
// from byte tables: sobolOwen2D in src/math/sampling.cpp.)
IBL_FN uint sobolDimension1Reversed(uint index) {
  uint r = 1u;
  uint result = 0u;
  for (int bit = 0; bit < 32 && index != 0u; ++bit) {
    if ((index & 1u) != 0u) result ^= r;
    r ^= r << 1u;
    index >>= 1u;
  }
  return result;
}

// The shuffled index of point `index`: an Owen scramble of the index keeps every aligned block
// of 2^k indices together, so that prefixes of 2^k points stay (0,k,2)-nets. Written so that no
// bits are reversed twice: its reversal is the point's dimension 0 (van der Corput), unscrambled.
IBL_FN uint sobolShuffledIndex(uint index, uint seed) {
  return reverseBits(laineKarrasPermutation(reverseBits(index), hash32(seed)));
}

// A float in [0, 1) from the top 24 bits (exact, never 1).
IBL_FN float unitFromBits(uint bits) {
  return float(bits >> 8u) * (1.0f / 16777216.0f);
}

// The scrambled pair of shuffled index i, given dimension 1's point (bit-reversed) at i.
IBL_FN vec2 sobolOwenScrambledPair(uint i, uint dimension1Reversed, uint seed) {
  return vec2(unitFromBits(reverseBits(laineKarrasPermutation(i, hash32(seed ^ 0x9e3779b9u)))),
              unitFromBits(reverseBits(
                  laineKarrasPermutation(dimension1Reversed, hash32(seed ^ 0x85ebca6bu)))));
}

// Point `index` of the first two Sobol dimensions, index-shuffled and Owen-scrambled by `seed`.
IBL_FN vec2 sobolOwenPair(uint index, uint seed) {
  uint i = sobolShuffledIndex(index, seed);
  return sobolOwenScrambledPair(i, IBL_SOBOL_DIMENSION1_REVERSED(i), seed);
}

// --- A pixel's numbers ---

struct PathSampler {
  uint key;        // hashed from the render's seed and the stream (pixel)
  uint index;      // the sample's index in the pixel's sequence
  uint dimension;  // pairs drawn so far in this sample
  float second;    // the unused half of the last pair pathUniform opened
  bool spare;
};

// The key of stream `stream` (a pixel) of the render of seed `seed`, each 64 bits in halves.
IBL_FN uint pathSamplerKey(uint seedLow, uint seedHigh, uint streamLow, uint streamHigh) {
  return hash32(seedLow ^ hash32(seedHigh) ^ hash32(streamLow + 0x632be5abu) ^
                hash32(streamHigh + 0x85157af5u));
}

// Sample `index` of the stream of `key`, at its first dimension.
IBL_FN PathSampler pathSamplerAt(uint key, uint index) {
  PathSampler s;
  s.key = key;
  s.index = index;
  s.dimension = 0u;
  s.second = 0.0f;
  s.spare = false;
  return s;
}

// The next pair of numbers, in [0, 1)^2.
IBL_FN vec2 pathUniform2(IBL_INOUT(PathSampler) s) {
  s.dimension += 1u;
  return sobolOwenPair(s.index, hash32(s.key + 0x9e3779b9u * s.dimension));
}

// The next number, in [0, 1): the first of a new pair, or the second of the pair the previous
// call opened.
IBL_FN float pathUniform(IBL_INOUT(PathSampler) s) {
  if (s.spare) {
    s.spare = false;
    return s.second;
  }
  vec2 pair = pathUniform2(s);
  s.second = pair.y;
  s.spare = true;
  return pair.x;
}

// A sampler of its own for a computation that draws a varying count of numbers (the microfacet
// walk: as many as its bounces), at the same sample index and keyed by where `s` stands, which
// it does not advance: the later draws of `s` keep their dimensions.
IBL_FN PathSampler pathSamplerBranch(PathSampler s) {
  uint position = 2u * s.dimension + (s.spare ? 1u : 0u);
  return pathSamplerAt(hash32(s.key ^ hash32(position + 0x5bd1e995u)), s.index);
}

IBL_END

#endif
