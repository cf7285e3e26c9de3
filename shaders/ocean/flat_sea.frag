// The foundation's placeholder sea (ocean/flat_sea.glsl): a flat sea at z = 0 below a camera at
// FrameCameraHeight() metres, seen along each pixel's view ray. Pixels whose ray does not meet
// the sea are left to the sky pass. Below the surface the water body's light fills the view.
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/analytic_sky.glsl"
#include "ocean/flat_sea.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm

uniform float wind_speed;             // m/s
uniform vec3 deep_reflectance;        // irradiance reflectance of the water body, per channel
uniform vec3 horizontal_irradiance;   // sun + sky on a horizontal surface, W m^-2 nm^-1

void main() {
  const vec3 ray = FrameViewRay(gl_FragCoord.xy);
  if (FrameCameraHeight() < 0.0) {
    radiance = vec4(FlatSeaDeepRadiance(deep_reflectance, horizontal_irradiance), 1.0);
    return;
  }
  if (ray.z >= 0.0) discard;
  const vec3 view = -ray;  // from the surface toward the eye
  const vec3 sun = FrameSunDirection();
  const float fresnel = FlatSeaFresnel(view.z);
  vec3 sea = fresnel * AnalyticSkyRadiance(reflect(ray, vec3(0.0, 0.0, 1.0)), sun) +
             (1.0 - fresnel) * FlatSeaDeepRadiance(deep_reflectance, horizontal_irradiance);
#ifdef SUN_GLINT
  sea += FlatSeaSunGlint(view, sun, wind_speed);
#endif
  radiance = vec4(sea, 1.0);
}
