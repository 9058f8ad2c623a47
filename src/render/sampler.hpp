#pragma once
// Internal to the renderer: the numbers every estimator of a pixel draws (the position in the
// pixel, light, emitter and environment samples, BRDF samples, lobe choices, Russian roulette,
// the microfacet walk, occlusion and shadow rays).
#include <cstdint>

#include <glm/vec2.hpp>

#include "ibl/math/sampling.hpp"

namespace ibl {

// Low-discrepancy in every dimension: Burley 2020, "Practical Hash-based Owen Scrambling",
// JCGT 9(4), section 4. Sample `s` of a pixel takes its d-th pair of numbers from the first two
// dimensions of the Sobol sequence, the index shuffled and the point Owen-scrambled with a seed
// hashed from (seed, stream, d): each pair is a (0,2)-sequence over the pixel's samples (any
// prefix of 2^k samples is stratified in every elementary interval), and different pairs and
// pixels are decorrelated by their independent shuffles ("padding"). Each draw is uniform on
// [0, 1)^2, so every estimator stays unbiased; a path that draws more numbers than another
// (a deeper bounce, a walk) just reaches further dimensions.
//
// Without startSample() the index stays 0 and each draw is an independent, uniformly
// scrambled point: a plain random stream (what the walk's tests use).
class Sampler {
 public:
  // `seed` is the render's, `stream` the pixel's (or any other independent stream).
  Sampler(std::uint64_t seed, std::uint64_t stream)
      : key_(hash32(static_cast<std::uint32_t>(seed) ^
                    hash32(static_cast<std::uint32_t>(seed >> 32u)) ^
                    hash32(static_cast<std::uint32_t>(stream) + 0x632be5abu) ^
                    hash32(static_cast<std::uint32_t>(stream >> 32u) + 0x85157af5u))) {}

  // Starts the sample of index `index` at the first dimension.
  void startSample(std::uint32_t index) {
    index_ = index;
    dimension_ = 0;
    spare_ = false;
  }

  // The next dimension pair, in [0, 1)^2.
  glm::vec2 uniform2() { return sobolOwen2D(index_, hash32(key_ + 0x9e3779b9u * ++dimension_)); }
  // A sampler of its own for a computation that draws a varying count of numbers (the
  // microfacet walk: as many as its bounces), at the same sample index and keyed by where this
  // sampler stands, which it does not advance: this sampler's later draws keep their dimensions,
  // and the branch's first draws are low-discrepancy over the pixel's samples too.
  Sampler branch() const {
    Sampler b = *this;
    b.key_ = hash32(key_ ^ hash32(2u * dimension_ + (spare_ ? 1u : 0u) + 0x5bd1e995u));
    b.dimension_ = 0;
    b.spare_ = false;
    return b;
  }

  // The next dimension, in [0, 1): the first of a new pair, or the second of the pair the
  // previous call opened.
  float uniform() {
    if (spare_) {
      spare_ = false;
      return second_;
    }
    const glm::vec2 pair = uniform2();
    second_ = pair.y;
    spare_ = true;
    return pair.x;
  }

 private:
  std::uint32_t key_;
  std::uint32_t index_ = 0, dimension_ = 0;
  float second_ = 0.0f;  // the unused half of the last pair uniform() opened
  bool spare_ = false;
};

}  // namespace ibl
