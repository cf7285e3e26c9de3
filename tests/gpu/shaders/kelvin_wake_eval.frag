// Evaluates shaders/ocean/kelvin_wake.glsl's KelvinWake at one point (b, y) per pixel, for
// tests/gpu/local_waves_test.cpp: texel (x, y) of `inputs` holds (b, y) in m (ship frame).
// OUTPUT 1: (h_T, theta_T, h_D, theta_D); OUTPUT 2: (k_T, k_D), rad/m, ship frame.
// OUTPUT 3: shaders/ocean/local_waves.glsl's LocalWakeFrame for wake 0 at the nadir-frame point
// (x, y) = the texel: (present 1 or 0, b, y, angle of e = atan(e.y, e.x)).
#include "ocean/kelvin_wake.glsl"
#if OUTPUT == 3
#include "ocean/local_waves.glsl"
#endif

layout(binding = 0) uniform sampler2D inputs;
uniform vec4 params;  // ocean::kelvin_wake_gpu_params
layout(location = 0) out vec4 result;

void main() {
  const vec4 p = texelFetch(inputs, ivec2(gl_FragCoord.xy), 0);
  KelvinWakeWave transverse, divergent;
  KelvinWake(params, p.x, p.y, transverse, divergent);
#if OUTPUT == 3
  float b, y;
  vec2 e;
  const bool present = LocalWakeFrame(0, p.xy, b, y, e);
  result = vec4(present ? 1.0 : 0.0, b, y, atan(e.y, e.x));
  return;
#endif
#if OUTPUT == 1
  result = vec4(transverse.amplitude, transverse.argument, divergent.amplitude, divergent.argument);
#else
  result = vec4(transverse.wave_vector, divergent.wave_vector);
#endif
}
