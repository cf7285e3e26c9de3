// The ocean seen from space (Bruneton, Neyret & Holzschuch 2010, sec. 6, "Planet-scale
// rendering"; issue 5, point 2): "for space views we do not need a projected grid nor
// transitions between levels of details. Instead, we render a sphere with the Ross BRDF
// directly" -- here the planet's own surface (the WGS84 ellipsoid or the sphere: the frame's sea
// quadric, exact), met per pixel by the view ray, shaded with the Ross BRDF whose slope variance
// holds every wave of the scene (eq. 4 with w_r = 1: the wave set's total), no normal
// perturbation. Each point is lit as Algorithm 5.1 lights a pixel, with its own sun: the sun's
// transmittance and the irradiance at the point, and "the 2D map corresponding to the local Sun
// elevation" from the provider's sun-zenith-indexed array, turned so that the sun is at the map's
// north. Then the aerial perspective between the camera and the point.
//
// Frames and units: the nadir frame of common/frame.glsl (m); the point's light and atmosphere as
// ocean/sea_point_light.glsl gives them. Radiance in W m^-2 sr^-1 nm^-1.
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/sky_provider.glsl"
#include "ocean/ross_brdf.glsl"
#include "ocean/effective_fresnel.glsl"
#include "ocean/sky_array_reflection.glsl"
#include "ocean/sea_point_light.glsl"
#include "ocean/pixel_mirror_slopes.glsl"
#if defined(CALM_AREAS) || defined(KELVIN_WAKES)
#include "planet/space_local_features.glsl"
#endif

layout(location = 0) out vec4 radiance;

uniform vec2 downwind;            // unit, the nadir frame's (east, north)
uniform vec2 slope_variance;      // every wave's: along, across the wind (dimensionless)
uniform float fresnel_r;          // R of Schlick's Fresnel (eq. 14)
uniform vec3 deep_reflectance;    // irradiance reflectance of the water body, per channel
// Distance of the near plane, m (the depth written is OCEAN_NEAR_PLANE / view-axis distance,
// reversed-Z with an infinite far plane, as the projected grid's).
const float OCEAN_NEAR_PLANE = 0.01;

void main() {
  const vec3 ray = FrameViewRay(gl_FragCoord.xy);
  const float distance = FrameSeaDistance(ray);
  if (distance < 0.0) discard;  // space or the limb: the sky pass's pixel
  const vec3 x = FrameCameraPosition() + distance * ray;
  const vec3 n = FrameSeaNormal(x);
#if defined(CALM_AREAS) || defined(KELVIN_WAKES)
  // Issue 9: this point's slope variance, hiding the uniform's (its scope starts after the
  // initializer): the sea's times s^2 in a calm area, plus the wakes' (w_r = 1).
  const vec2 slope_variance = SpaceLocalSlopeVariance(x.xy, slope_variance, downwind);
#endif
  const vec3 sun = FrameSunDirection();
  const vec3 v = -ray;

  // Algorithm 5.1's tangent frame: the wind along t_x.
  const vec3 t_x = OceanTangentToward(n, vec3(downwind, 0.0), sun);
  const vec3 t_y = cross(n, t_x);
  const vec3 v_t = OceanToTangentFrame(v, t_x, t_y, n);

  // The sun, the irradiance and the atmosphere at the point itself (ocean/sea_point_light.glsl).
  const OceanPointLight light = OceanLightAtPoint(x, n, sun);

  vec2 lobe_centre;  // the sky's, in slope space (ocean/effective_fresnel.glsl)
  const float fresnel = OceanSceneEffectiveFresnel(v_t, slope_variance, fresnel_r, lobe_centre);
  vec3 sea = vec3(0.0);
#ifdef SKY_TERM
  const vec2 sigma = sqrt(OceanClampedSlopeVariance(slope_variance));
  sea += fresnel * OceanSkyArrayReflection(n, v, t_x, t_y, n, lobe_centre, sigma, sun);
#endif
#ifdef SEA_TERM
  sea += (1.0 - fresnel) * OceanDeepRadiance(deep_reflectance, light.irradiance);
#endif
#ifdef SUN_GLINT
  // Eq. 15 averaged over the pixel, as the surface's methods draw it
  // (ocean/pixel_mirror_slopes.glsl): from afar the planet's curvature turns the normal across a
  // pixel's footprint as much as the view ray turns.
  sea += light.sun_irradiance * OceanSunOverPixel(gl_FragCoord.xy, t_x, t_y, n, n, v_t,
                                                  OceanToTangentFrame(sun, t_x, t_y, n),
                                                  slope_variance, fresnel_r);
#endif

  vec3 transmittance;
  vec3 in_scattered = SkyAerialPerspective(light.camera, light.ground, sun, transmittance);
#ifndef AIR_TERM
  in_scattered = vec3(0.0);
#endif
  radiance = vec4(sea * transmittance + in_scattered, 1.0);
  gl_FragDepth = OCEAN_NEAR_PLANE / max(distance * dot(ray, frame_camera_forward.xyz), 1e-30);
}
