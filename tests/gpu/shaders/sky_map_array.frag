// Evaluates the sky provider's map fetches per pixel for tests/gpu/sky_provider_test.cpp, from
// inputs the CPU wrote exactly: texel (x, y) of `lookup_u` holds (u, du_dx) and of
// `lookup_layer` (du_dy, layer, cos_sun_zenith) for pixel (x, y); u and its gradients are
// stereographic map coordinates (u units), the layer is fractional, the cosine dimensionless.
// FUNCTION 1: the array's SkyMapArrayRadianceGrad (rgb) and SkyMapArrayLayer (a);
// FUNCTION 2: the single map's SkyMapRadianceGrad (rgb), a = 0.
#include "atmosphere/sky_provider.glsl"
#include "common/definitions.glsl"

layout(binding = 0) uniform sampler2D lookup_u;
layout(binding = 1) uniform sampler2D lookup_layer;
layout(location = 0) out vec4 result;

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 a = texelFetch(lookup_u, pixel, 0);
  const vec4 b = texelFetch(lookup_layer, pixel, 0);
#if FUNCTION == 1
  result = vec4(SkyMapArrayRadianceGrad(a.xy, a.zw, b.xy, b.z), SkyMapArrayLayer(b.w));
#else
  result = vec4(SkyMapRadianceGrad(a.xy, a.zw, b.xy), 0.0);
#endif
}
