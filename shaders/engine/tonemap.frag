// Shows the linear HDR frame on a display with the PNG's operator (engine/src/image_io.cpp,
// thalassa::tone_map): sRGB(1 - exp(-exposure * L)) per channel. The default framebuffer is
// not sRGB-encoded, so the transfer function is applied here.
in vec2 screen_uv;
layout(location = 0) out vec4 color;
layout(binding = 0) uniform sampler2D hdr_frame;  // linear radiance, W m^-2 sr^-1 nm^-1
uniform float exposure;                            // 1 / (W m^-2 sr^-1 nm^-1)

float SrgbEncode(float x) {
  x = clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

// Like thalassa::tone_map: non-finite or negative radiance shows as 0 (GLSL's max(NaN, 0) is
// undefined, so the test is explicit).
float Sanitize(float x) { return isnan(x) || isinf(x) || x <= 0.0 ? 0.0 : x; }

void main() {
  const vec3 texel = texture(hdr_frame, screen_uv).rgb;
  const vec3 radiance = vec3(Sanitize(texel.r), Sanitize(texel.g), Sanitize(texel.b));
  const vec3 v = 1.0 - exp(-exposure * radiance);
  color = vec4(SrgbEncode(v.r), SrgbEncode(v.g), SrgbEncode(v.b), 1.0);
}
