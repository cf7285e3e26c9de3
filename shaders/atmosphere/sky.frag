// The sky behind the scene (issue 4, point 3f), from the ground or from space: the provider's
// sky radiance along each pixel's view ray from the camera, and the sun's disc seen through the
// same transmittance. From space the atmosphere's shell and the planet's limb follow from the
// model (rays that miss the atmosphere are black; rays that hit the planet carry the light
// scattered before they reach it).
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/sky_provider.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm

uniform vec3 camera_position;         // planet-centred, m: (0, 0, planet radius + height)
uniform vec3 sun_disc_radiance;       // W m^-2 sr^-1 nm^-1, before the view ray's transmittance
uniform float sun_cos_angular_radius;

void main() {
  vec3 view = FrameViewRay(gl_FragCoord.xy);
  vec3 transmittance;
  vec3 sky = SkyBackgroundRadiance(camera_position, view, FrameSunDirection(), transmittance);
#ifdef SUN_DISC
  if (dot(view, FrameSunDirection()) > sun_cos_angular_radius) {
    sky += transmittance * sun_disc_radiance;
  }
#endif
  radiance = vec4(sky, 1.0);
}
