// The reference method's running sums (issue 6, point 1): one sample's image added, in double
// precision, to each pixel's sums, on the GPU, so that the samples of a reference image follow
// each other without a read-back between them (planet/src/reference_accumulator.hpp; the host
// reads the sums once per doubling of the samples, to test the rows' convergence).
//
// What a sample's pixel holds (ocean_lighting.frag, REFERENCE_SEA_ALPHA): RGB its radiance
// (W m^-2 sr^-1); alpha 1 where it saw the sky, +-(2 + w) where it saw the sea, w >= 0 the
// sample's visible-area weight (visible_area_weight.glsl), negative where the sun's lattice did
// not resolve every wave under it. The host's twin, add_reference_sample in
// reference_accumulator.cpp, is the same function operation for operation, and
// ReferenceAccumulator.GpuSumsAreTheHostsSums checks the two bit for bit, non-finite input
// included: finiteness is read from the bits, not with isnan / isinf, which a driver may
// compile away, and every sum is `precise` (no fused multiply-add the host would not do).

layout(local_size_x = 8, local_size_y = 8) in;

// The sample: RGBA32F, the image's size, GL's rows (from the bottom).
uniform sampler2D sample_image;
uniform ivec2 image_size;  // pixels

// ReferencePixelSums, std430: 96 bytes a pixel, the image's rows from the top.
struct PixelSums {
  double sky[3];       // sum of the sky's samples' radiance
  double weighted[3];  // sum of w L over the sea's samples
  double plain[3];     // sum of L over the sea's samples
  double weight;       // sum of w
  int sea;             // the sea's samples
  int resolved;        // samples whose sun resolved every wave (each of the sky's)
  int nonfinite;       // samples whose radiance was not finite
  int unused;
};
layout(std430, binding = 1) buffer ReferenceSums { PixelSums sums[]; };

// The sea's samples carry |alpha| >= this (ocean_lighting.frag: 2 + the sample's weight).
const double REFERENCE_SEA_ALPHA = 2.0;

// IEEE 754: a float is NaN or infinite where its exponent's bits are all set.
bool Finite(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= image_size.x || pixel.y >= image_size.y) return;
  const vec4 p = texelFetch(sample_image, pixel, 0);
  const uint i = uint(image_size.y - 1 - pixel.y) * uint(image_size.x) + uint(pixel.x);
  const dvec3 radiance = dvec3(p.rgb);
  if (!(Finite(p.r) && Finite(p.g) && Finite(p.b))) sums[i].nonfinite += 1;
  // A NaN alpha is the sky's (the host's comparisons with NaN are false); an infinite one the
  // sea's, with weight 0.
  const double code = abs(double(p.a));
  const bool alpha_nan = !Finite(p.a) && (floatBitsToUint(p.a) & 0x007fffffu) != 0u;
  if (!alpha_nan && code >= REFERENCE_SEA_ALPHA) {
    const double w = Finite(p.a) ? code - REFERENCE_SEA_ALPHA : 0.0lf;
    for (int c = 0; c < 3; ++c) {
      precise double weighted = sums[i].weighted[c] + w * radiance[c];
      precise double plain = sums[i].plain[c] + radiance[c];
      sums[i].weighted[c] = weighted;
      sums[i].plain[c] = plain;
    }
    precise double weight = sums[i].weight + w;
    sums[i].weight = weight;
    sums[i].sea += 1;
    if (p.a > 0.0) sums[i].resolved += 1;
  } else {
    for (int c = 0; c < 3; ++c) {
      precise double sky = sums[i].sky[c] + radiance[c];
      sums[i].sky[c] = sky;
    }
    sums[i].resolved += 1;
  }
}
