// Shared by the compute shaders; mirrors src/sampling.cpp and include/ibl/brdf.hpp (the CPU
// definitions), so that both paths integrate with the same points and formulas.
const float kPi = 3.14159265358979;

// Van der Corput radical inverse in base 2 (bit reversal): radicalInverse2 in sampling.cpp.
float radicalInverse2(uint i) { return float(bitfieldReverse(i)) * 2.3283064365386963e-10; }
vec2 hammersley(uint i, uint n) { return vec2(float(i) / float(n), radicalInverse2(i)); }

vec2 uniformDiskPoint(vec2 xi) {
  float r = sqrt(xi.x);
  float phi = 2.0 * kPi * xi.y;
  return vec2(r * cos(phi), r * sin(phi));
}

vec3 sampleCosineHemisphere(vec2 xi) {
  vec2 d = uniformDiskPoint(xi);
  return vec3(d, sqrt(max(0.0, 1.0 - xi.x)));
}

// Heitz 2018, listing 1 (isotropic): GgxVisibleNormalSampler in sampling.hpp.
vec3 sampleGgxVisibleNormal(vec3 v, vec2 disk, float alpha) {
  vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) / sqrt(lensq) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = cross(vh, t1);
  float s = 0.5 * (1.0 + vh.z);
  float p1 = disk.x;
  float p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * disk.y;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}

float smithGgxCorrelatedVisibility(float NoV, float NoL, float alpha) {
  float a2 = alpha * alpha;
  float lambdaV = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
  float lambdaL = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
  return 0.5 / (lambdaV + lambdaL);
}

float schlickWeight(float VoH) {
  float m = clamp(1.0 - VoH, 0.0, 1.0);
  float m2 = m * m;
  return m2 * m2 * m;
}

float disneyDiffuseRenormalized(float NoV, float NoL, float LoH, float roughness) {
  float energyBias = 0.5 * roughness;
  float energyFactor = 1.0 + (1.0 / 1.51 - 1.0) * roughness;
  float fd90 = energyBias + 2.0 * LoH * LoH * roughness;
  float lightScatter = 1.0 + (fd90 - 1.0) * schlickWeight(NoL);
  float viewScatter = 1.0 + (fd90 - 1.0) * schlickWeight(NoV);
  return lightScatter * viewScatter * energyFactor;
}

// Real SH basis up to band 2 (shBasis9 in src/sh.cpp).
void shBasis9(vec3 d, out float basis[9]) {
  basis = float[9](0.282095, 0.488603 * d.y, 0.488603 * d.z, 0.488603 * d.x, 1.092548 * d.x * d.y,
                   1.092548 * d.y * d.z, 0.315392 * (3.0 * d.z * d.z - 1.0), 1.092548 * d.x * d.z,
                   0.546274 * (d.x * d.x - d.y * d.y));
}

// sRGB transfer functions (srgbToLinear / linearToSrgb in src/color.cpp).
float srgbToLinear(float e) {
  e = clamp(e, 0.0, 1.0);
  return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}
vec3 srgbToLinear(vec3 e) { return vec3(srgbToLinear(e.r), srgbToLinear(e.g), srgbToLinear(e.b)); }
float linearToSrgb(float l) {
  if (!(l > 0.0)) return 0.0;
  if (l >= 1.0) return 1.0;
  return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
}
