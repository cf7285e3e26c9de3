// Evaluates shaders/ocean/kelvin_wake.glsl's KelvinWake at one point (b, y) per pixel, for
// tests/gpu/local_waves_test.cpp: texel (x, y) of `inputs` holds (b, y) in m (ship frame).
// OUTPUT 1: (h_T, theta_T, h_D, theta_D); OUTPUT 2: (k_T, k_D), rad/m, ship frame.
#include "ocean/kelvin_wake.glsl"

layout(binding = 0) uniform sampler2D inputs;
uniform vec4 params;  // ocean::kelvin_wake_gpu_params
layout(location = 0) out vec4 result;

void main() {
  const vec4 p = texelFetch(inputs, ivec2(gl_FragCoord.xy), 0);
  KelvinWakeWave transverse, divergent;
  KelvinWake(params, p.x, p.y, transverse, divergent);
#if OUTPUT == 1
  result = vec4(transverse.amplitude, transverse.argument, divergent.amplitude, divergent.argument);
#else
  result = vec4(transverse.wave_vector, divergent.wave_vector);
#endif
}
