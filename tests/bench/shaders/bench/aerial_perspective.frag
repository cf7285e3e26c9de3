// Benchmark pass (tests/bench/atmosphere_bench.cpp): the aerial perspective alone, once per
// pixel, toward points of the sea from 50 m to 50 km away across the image, as the ocean's
// lighting pass evaluates it per pixel (which the renderer times together with the lighting).
#include "common/definitions.glsl"
#include "atmosphere/sky_provider.glsl"

in vec2 screen_uv;
layout(location = 0) out vec4 radiance;  // in-scattered radiance + transmittance (kept alive)

uniform vec3 camera_position;  // planet-centred, m: (0, 0, planet radius + height)
uniform vec3 sun_direction;    // unit, ENU at the camera's nadir
uniform float planet_radius;   // m

void main() {
  const float distance = mix(50.0, 50000.0, screen_uv.y);  // m, along the sea
  const float azimuth = (screen_uv.x - 0.5) * 1.5;          // rad
  const float angle = distance / planet_radius;             // at the planet's centre
  const vec3 point = planet_radius * vec3(sin(angle) * sin(azimuth), sin(angle) * cos(azimuth),
                                          cos(angle));
  vec3 transmittance;
  const vec3 in_scattered = SkyAerialPerspective(camera_position, point, sun_direction,
                                                 transmittance);
  radiance = vec4(in_scattered + transmittance, 1.0);
}
