#version 450
// The multiple-scattering table, one texel (r, mu_s) per invocation, every band: Hillaire 2020,
// section 5.5 (SkyModel::Tables::multipleScatteringAt, step for step).
layout(local_size_x = 64) in;
#include "sky/atmosphere.glsl"

void main() {
  int k = int(gl_GlobalInvocationID.x);
  if (k >= kMultipleTableMu * kMultipleTableR) return;
  AtmosphereShape a = atmosphereShape();
  float albedo = sky.shape1.z;
  vec2 rmS = multipleTableRadiusAndCosine(a, float(k % kMultipleTableMu) / float(kMultipleTableMu - 1),
                                          float(k / kMultipleTableMu) / float(kMultipleTableR - 1));
  float r = rmS.x, muS = rmS.y;
  const int kDirections = 8;
  const int kSteps = 20;
  float l2[kSkyBands], fms[kSkyBands], throughput[kSkyBands], sunT[kSkyBands];
  for (int i = 0; i < kSkyBands; ++i) {
    l2[i] = 0.0f;
    fms[i] = 0.0f;
  }
  vec3 sunDir = vec3(sqrt(max(1.0f - muS * muS, 0.0f)), muS, 0.0f);
  for (int da = 0; da < kDirections; ++da)
    for (int db = 0; db < kDirections; ++db) {
      vec3 d = sphereStratumDirection(da, db, kDirections);
      float mu = d.y, nu = dot(d, sunDir);
      bool ground = rayMeetsGround(r, mu, a.bottomRadius);
      float len = ground ? distanceToGround(r, mu, a.bottomRadius)
                         : distanceToSphereFar(r, mu, a.topRadius);
      for (int i = 0; i < kSkyBands; ++i) throughput[i] = 1.0f;
      float dt = len / float(kSteps);
      for (int s = 0; s < kSteps; ++s) {
        float t = (float(s) + 0.5f) * dt;
        vec2 rm = radiusAndCosineAfter(r, mu, t);
        float muSt = sunCosineAfter(r, muS, nu, t, rm.x);
        vec3 rho = constituentDensities(a, rm.x - a.bottomRadius);
        transmittanceToTop(a, rm.x, muSt, sunT);
        for (int i = 0; i < kSkyBands; ++i) {
          BandCoefficients c = bandCoefficients(i);
          float extinction = bandExtinction(c, rho);
          float stepT = exp(-extinction * dt);
          float scattered =
              throughput[i] * bandScattering(c, rho) * stepIntegral(extinction, dt, stepT);
          l2[i] += scattered * sunT[i] / (4.0f * kPi);
          fms[i] += scattered;
          throughput[i] *= stepT;
        }
      }
      if (ground && albedo > 0.0f) {
        vec2 rm = radiusAndCosineAfter(r, mu, len);
        float muSg = sunCosineAfter(r, muS, nu, len, rm.x);
        transmittanceToTop(a, a.bottomRadius, muSg, sunT);
        for (int i = 0; i < kSkyBands; ++i)
          l2[i] += throughput[i] * sunT[i] * max(muSg, 0.0f) * albedo / kPi;
      }
    }
  float n = float(kDirections * kDirections);
  for (int i = 0; i < kSkyBands; ++i)
    multiple[k * kSkyBands + i] =
        sky.flags.y > 0.5f ? (l2[i] / n) / (1.0f - min(fms[i] / n, 0.999f)) : 0.0f;
}
