#pragma once
// API: stable
// Pinhole and orthographic cameras, and physically based exposure (Lagarde & de Rousiers
// 2014, section 5.1): EV100, exposure, tone curves, sRGB output.
#include <glm/vec3.hpp>

#include "ibl/core/image.hpp"

namespace ibl {

// World space, in scene units (meters for glTF).
struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;  // unit
};

// The camera's orthonormal frame (right-handed: right = forward x up).
struct CameraFrame {
  glm::vec3 forward, right, up;
};

struct Camera {
  bool perspective = true;           // false: orthographic
  float yfovDegrees = 40.0f;         // perspective: vertical field of view
  float orthoWidth = 4.0f;           // orthographic: width of the view in world units
  glm::vec3 from{0.0f, 0.0f, 4.0f};  // the eye, world units
  glm::vec3 at{0.0f};                // the point looked at, world units
  glm::vec3 up{0.0f, 1.0f, 0.0f};    // any length (see frame())
  int width = 512, height = 512;     // of the image, pixels

  // The frame: forward toward `at`; right and up from `up` made orthogonal to it. When `up`
  // is zero or (nearly) parallel to the view, the world axis least aligned with the view stands
  // in for it, as other renderers do (looking straight down with +Y up works).
  // checkCamera() has rejected what has no frame (from == at, non-finite values).
  CameraFrame frame() const;

  // Ray through image point (px, py) in pixels, (0, 0) the top-left corner of pixel (0, 0):
  // the center of pixel (i, j) is (i + 0.5, j + 0.5).
  Ray generateRay(float px, float py) const;

  // Whether `other` is the same camera, field by field (exactly: the viewer redraws its shadow
  // maps and light clusters when the camera changes at all).
  bool operator==(const Camera& other) const = default;
};

// Throws Error("camera: ...") when the camera cannot form an image: `from` equal to `at`,
// non-finite or absurdly large coordinates (beyond 1e8), a field of view outside (0, 180)
// degrees, an orthographic width <= 0, an empty image.
void checkCamera(const Camera& camera);

// EV100 of camera settings: log2(N^2 / t * 100 / S) (aperture N as f-number, shutter time t in
// seconds, ISO S), all > 0 (not checked).
float ev100FromSettings(float aperture, float shutterSeconds, float iso);
// EV100 that exposes an average luminance L (cd/m^2, > 0) for middle gray: log2(L * 100 / 12.5).
float ev100FromAverageLuminance(float averageLuminance);
// Scale from luminance to normalized pixel values for EV100: 1 / (1.2 * 2^EV100)
// (saturation-based sensitivity, the sensor's maximum at 78 % of saturation). Multiply
// luminance in cd/m^2 by it; 1.0 is then the sensor's maximum.
float exposureFromEv100(float ev100);
// Log-average luminance (exp of the mean of log(L + 1e-4)) over all pixels, L the Rec.709
// luminance in the image's units (cd/m^2 for a render); 0 for an empty image.
float averageLogLuminance(const Image& image);

enum class ToneMap { None = 0, Aces = 1, Filmic = 2 };  // the curve numbers of shared::toneMap
// Tone curves: none (clamp to [0, 1]), ACES fitted (Narkowicz 2015), filmic (Hable 2010,
// "Uncharted 2", white point 11.2). c: exposed linear Rec.709; returns linear values in [0, 1]
// (apply the sRGB curve for display).
glm::vec3 toneMap(glm::vec3 c, ToneMap curve);

}  // namespace ibl
