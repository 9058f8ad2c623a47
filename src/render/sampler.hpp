#pragma once
// Internal to the renderer: the numbers every estimator of a pixel draws (the position in the
// pixel, light, emitter and environment samples, BRDF samples, lobe choices, Russian roulette,
// the microfacet walk, occlusion and shadow rays).
#include <cstdint>

#include <glm/vec2.hpp>

#include "ibl/math/sampling.hpp"
#include "ibl/shared/path_sampler.h"

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
//
// The state and the draws are ibl/shared/path_sampler.h's, which the GPU reference draws too:
// the same seed, pixel and sample index give the same numbers on both.
class Sampler : public shared::PathSampler {
 public:
  // `seed` is the render's, `stream` the pixel's (or any other independent stream).
  Sampler(std::uint64_t seed, std::uint64_t stream)
      : shared::PathSampler(shared::pathSamplerAt(
            shared::pathSamplerKey(
                static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32u),
                static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(stream >> 32u)),
            0u)) {}

  // Starts the sample of index `index` at the first dimension.
  void startSample(std::uint32_t i) { *this = Sampler(shared::pathSamplerAt(key, i)); }

  // The next dimension pair, in [0, 1)^2.
  glm::vec2 uniform2() { return shared::pathUniform2(*this); }
  // A sampler of its own for a computation that draws a varying count of numbers (the
  // microfacet walk: as many as its bounces), at the same sample index and keyed by where this
  // sampler stands, which it does not advance: this sampler's later draws keep their dimensions,
  // and the branch's first draws are low-discrepancy over the pixel's samples too.
  Sampler branch() const { return Sampler(shared::pathSamplerBranch(*this)); }

  // The next dimension, in [0, 1): the first of a new pair, or the second of the pair the
  // previous call opened.
  float uniform() { return shared::pathUniform(*this); }

 private:
  explicit Sampler(const shared::PathSampler& state) : shared::PathSampler(state) {}
};

}  // namespace ibl
