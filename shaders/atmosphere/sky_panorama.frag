// An equirectangular panorama of the sky around the camera (`thalassa sky --panorama`): the
// provider's sky radiance along each texel's direction (the sample at its centre: the sky is
// smooth at the texel scale), and the sun's disc of atmosphere/sky.frag, its light spread over
// the texels it covers. Layout (thalassa/planet/sky_export.hpp): the texel at window
// position (x, y) (pixels, origin bottom-left; the image is read back flipped, top row first)
// looks at azimuth 2 pi x / width clockwise from north and zenith angle pi (1 - y / height),
// so the image's left edge looks north and its top edge is the zenith.
#include "common/definitions.glsl"
#include "atmosphere/sky_provider.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm

uniform vec3 camera_position;    // planet-centred, m: (0, 0, planet radius + height)
uniform vec3 sun_direction;      // unit, ENU
uniform vec3 sun_disc_radiance;  // W m^-2 sr^-1 nm^-1, before the view ray's transmittance
uniform float sun_cos_angular_radius;
uniform float sun_angular_radius;  // rad
uniform vec2 panorama_size;        // texels: width, height = width / 2

// Points spread evenly over the sun's disc (a sunflower pattern): each carries 1 / N of the
// disc's light into the texel it falls in. The texels partition the sphere, so the panorama
// holds the disc's irradiance whatever the width, and a disc smaller than a texel (0.27 deg in
// radius against 0.18 deg per texel at 2048, 5.6 at 64) lights the texels it covers in
// proportion rather than all or none.
const int SUN_DISC_POINTS = 256;

// The unit ENU direction at window position p (pixels).
vec3 PanoramaDirection(vec2 p) {
  float azimuth = 2.0 * PI * p.x / panorama_size.x;  // clockwise from north
  float zenith = PI * (1.0 - p.y / panorama_size.y);
  return vec3(sin(azimuth) * sin(zenith), cos(azimuth) * sin(zenith), cos(zenith));
}

// The texel (column, row from the bottom) of the ENU direction d.
ivec2 PanoramaTexel(vec3 d) {
  float azimuth = atan(d.x, d.y);  // clockwise from north, (-pi, pi]
  float column = fract(azimuth / (2.0 * PI) + 1.0) * panorama_size.x;
  float zenith = acos(clamp(d.z, -1.0, 1.0));
  float row = (1.0 - zenith / PI) * panorama_size.y;
  return ivec2(min(ivec2(vec2(column, row)), ivec2(panorama_size) - 1));
}

void main() {
  vec3 view = PanoramaDirection(gl_FragCoord.xy);
  vec3 transmittance;
  vec3 sky = SkyBackgroundRadiance(camera_position, view, sun_direction, transmittance);
#ifdef SUN_DISC
  // A texel spans 2 pi / width rad in azimuth (less in arc away from the horizon) and
  // pi / height = 2 pi / width rad in zenith angle: every point of it lies within
  // 2 pi / width rad of its centre, so texels farther than that from the disc's edge miss it.
  float reach = min(sun_angular_radius + 2.0 * PI / panorama_size.x, PI);
  if (dot(view, sun_direction) > cos(reach)) {
    vec3 tangent = normalize(cross(abs(sun_direction.z) < 0.9 ? vec3(0.0, 0.0, 1.0)
                                                               : vec3(1.0, 0.0, 0.0),
                                   sun_direction));
    vec3 bitangent = cross(sun_direction, tangent);
    ivec2 texel = ivec2(gl_FragCoord.xy);
    int inside = 0;
    for (int k = 0; k < SUN_DISC_POINTS; ++k) {
      float rho = sun_angular_radius * sqrt((float(k) + 0.5) / float(SUN_DISC_POINTS));
      float phi = float(k) * GOLDEN_ANGLE;
      vec3 d = cos(rho) * sun_direction +
               sin(rho) * (cos(phi) * tangent + sin(phi) * bitangent);
      if (PanoramaTexel(d) == texel) ++inside;
    }
    if (inside > 0) {
      // The disc's light, L_disc T Omega_disc, spread over this texel's solid angle: exactly
      // (2 pi / width) (cos theta_top - cos theta_bottom).
      float theta_top = PI * (1.0 - float(texel.y + 1) / panorama_size.y);
      float theta_bottom = PI * (1.0 - float(texel.y) / panorama_size.y);
      float texel_solid_angle =
          2.0 * PI / panorama_size.x * (cos(theta_top) - cos(theta_bottom));
      float disc_solid_angle = 2.0 * PI * (1.0 - sun_cos_angular_radius);
      vec3 sun_transmittance;
      SkyBackgroundRadiance(camera_position, sun_direction, sun_direction, sun_transmittance);
      sky += sun_transmittance * sun_disc_radiance * disc_solid_angle *
             (float(inside) / float(SUN_DISC_POINTS)) / texel_solid_angle;
    }
  }
#endif
  radiance = vec4(sky, 1.0);
}
