// The split-sum shading of a surface point: shadeSplitSum in src/render.cpp, line for line.
// Needs common.glsl and frame.glsl.

vec3 sampleDfgLut(float NoV, float roughness) {
  return textureLod(dfgLut, vec2(NoV, roughness), 0.0).rgb;  // bilinear, clamped: sampleDfgLut
}

// specularLodForRoughness in src/prefilter.cpp.
float specularLodForRoughness(float roughness) {
  float t = frame.lods.y > 0.5 ? sqrt(max(roughness, 0.0)) : roughness;
  return t * frame.lods.x;
}

// irradianceSh9 / pi (src/sh.cpp); the host folded A_l / pi into the coefficients.
vec3 irradianceSh9OverPi(vec3 n) {
  float basis[9];
  shBasis9(n, basis);
  vec3 sum = vec3(0.0);
  for (int k = 0; k < 9; ++k) sum += frame.sh[k].rgb * basis[k];
  return sum;
}

vec3 shadeSplitSum(vec3 n, vec3 view, vec3 baseColor, float metallic, float roughness,
                   float occlusion, vec3 emissive) {
  float NoV = max(dot(n, view), 1e-4);
  float r = roughness, alpha = r * r;
  vec3 diffuseColor = baseColor * (1.0 - metallic);
  vec3 f0 = mix(vec3(0.04), baseColor, metallic);
  vec3 dfg = sampleDfgLut(NoV, r);
  vec3 color = emissive;
  if (frame.terms.x != 1) {
    vec3 dir = 2.0 * dot(n, view) * n - view;
    if (frame.terms.z != 0) {
      // Frostbite listing 22: the lobe's peak leans toward the normal as roughness grows.
      float smoothness = 1.0 - alpha;
      dir = normalize(mix(n, dir, smoothness * (sqrt(smoothness) + alpha)));
    }
    vec3 specular = textureLod(specularMap, dir, specularLodForRoughness(r)).rgb *
                    (f0 * dfg.x + dfg.y);
    if (frame.terms.y != 0) specular *= 1.0 + f0 * (1.0 / (dfg.x + dfg.y) - 1.0);
    if (frame.terms.w != 0 && occlusion < 1.0)  // Frostbite listing 26
      specular *= clamp(pow(NoV + occlusion, exp2(-16.0 * alpha - 1.0)) - 1.0 + occlusion, 0.0, 1.0);
    color += specular;
  }
  if (frame.terms.x != 2) {
    vec3 dir = n;
    if (frame.terms.z != 0 && frame.models.x == 0) {
      // Frostbite listing 23: Disney's diffuse lobe leans toward the view at grazing angles.
      float a = 1.02341 * alpha - 1.51174, b = -0.511705 * alpha + 0.755868;
      dir = normalize(mix(n, view, clamp((NoV * a + b) * alpha, 0.0, 1.0)));
    }
    vec3 irradiance = frame.models.y == 0 ? textureLod(irradianceMap, dir, 0.0).rgb
                                          : irradianceSh9OverPi(dir);
    float fd = frame.models.x == 0 ? dfg.z : 1.0;
    color += diffuseColor * irradiance * fd * occlusion;
  }
  return color;
}
