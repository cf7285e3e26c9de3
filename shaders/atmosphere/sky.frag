// The sky behind the scene: the foundation's placeholder sky (atmosphere/analytic_sky.glsl)
// seen along each pixel's view ray. Below the horizon the ray is laid onto the horizon, so the
// sky pass stays finite wherever the sea pass does not cover it.
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/analytic_sky.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm

void main() {
  vec3 view = FrameViewRay(gl_FragCoord.xy);
  if (view.z < 0.0) view = normalize(vec3(view.x, view.y, 0.0) + vec3(0.0, 0.0, 1e-6));
  vec3 sky = AnalyticSkyRadiance(view, FrameSunDirection());
#ifdef SUN_DISC
  sky += AnalyticSunDiscRadiance(view, FrameSunDirection());
#endif
  radiance = vec4(sky, 1.0);
}
