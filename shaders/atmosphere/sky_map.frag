// One stereographic sky map (issue 4, point 3a): the radiance arriving at `observer` from the
// direction of each texel's u (shaders/atmosphere/sky_provider.glsl gives the layout), with the
// ocean paper's below-horizon radiance (sec. 6) outside the horizon circle |u| = 1. Texels the
// horizon circle crosses are averaged over 4 x 4 sub-samples, so the sky-to-below-horizon step is
// area-weighted as the mipmaps will assume; elsewhere the sky is smooth at the texel scale and
// one sample at the centre is its average to second order.
#include "common/definitions.glsl"
#include "atmosphere/sky_provider.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1

uniform vec3 observer;                // planet-centred, m (ENU-parallel frame)
uniform vec3 sun_direction;           // unit, ENU
uniform vec3 below_horizon_radiance;  // W m^-2 sr^-1 nm^-1
uniform float map_size;               // texels per side

const int SUBSAMPLES = 4;

vec3 RadianceAt(vec2 u) {
  float uu = dot(u, u);
  if (uu > 1.0) return below_horizon_radiance;
  // Inverse of u = (r_x, r_y) / (1 + r_z).
  vec3 r = vec3(2.0 * u.x, 2.0 * u.y, 1.0 - uu) / (1.0 + uu);
  vec3 transmittance;
  return SkyBackgroundRadiance(observer, r, sun_direction, transmittance);
}

void main() {
  float texel = 2.0 * SKY_MAP_EXTENT / map_size;  // u units per texel
  vec2 u = (gl_FragCoord.xy / map_size * 2.0 - 1.0) * SKY_MAP_EXTENT;
  // Distance of the texel's farthest corner from its centre.
  float half_diagonal = 0.7072 * texel;
  if (abs(length(u) - 1.0) > half_diagonal) {
    radiance = vec4(RadianceAt(u), 1.0);
    return;
  }
  vec3 sum = vec3(0.0);
  for (int j = 0; j < SUBSAMPLES; ++j) {
    for (int i = 0; i < SUBSAMPLES; ++i) {
      vec2 offset = (vec2(float(i), float(j)) + 0.5) / float(SUBSAMPLES) - 0.5;
      sum += RadianceAt(u + offset * texel);
    }
  }
  radiance = vec4(sum / float(SUBSAMPLES * SUBSAMPLES), 1.0);
}
