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
uniform float sun_angular_radius;     // rad (the same disc; a small angle, exact from the CPU)

#ifdef SUN_DISC
// The share of the area a sample stands for that the sun's disc covers: the square of
// frame_pixel_offset.z pixels (the whole pixel, or a supersampled render's stratum) centred on
// the sample's window position. Testing the pixel's centre alone lost the disc wherever it fell
// between centres: at 128x72 and a 45 degree field (0.63 degree a pixel) the 0.53 degree disc
// was drawn by no method but the supersampled reference. The share is area(square and disc) /
// area(square), estimated with SUN_COVERAGE_POINTS points: while the disc is at least 4 squares
// wide in area, the square's points tested against the disc; below, the disc's points (a
// golden-angle spiral, uniform in solid angle) located in the square, times the disc's solid
// angle over the square's. Summed over the pixels the second counts each disc point once, so
// that the disc's energy, L T Omega_sun, is conserved exactly where the first's edge pixels
// would each be off by up to one point in a share of the disc that matters; the first keeps a
// disc many pixels wide smooth (tests/gpu/golden_test.cpp,
// Orientation.SunDiscKeepsItsEnergyAtEveryResolution: within 1 % from 1 degree to 0.05 degree
// a pixel).
#define SUN_COVERAGE_SIDE 16
#define SUN_COVERAGE_POINTS (SUN_COVERAGE_SIDE * SUN_COVERAGE_SIDE)
float SunDiscCoverage(vec2 frag_coord, vec3 view, vec3 sun) {
  const float side = frame_pixel_offset.z > 0.0 ? frame_pixel_offset.z : 1.0;  // pixels
  // The square's extent in the image plane at unit distance, and its solid angle (a pinhole
  // pixel of area A seen at angle theta off the axis subtends A cos^3 theta).
  const vec2 pixel_size = 2.0 * vec2(frame_camera_right.w, frame_camera_up.w) * frame_viewport.zw;
  const float cos_axis = max(dot(view, frame_camera_forward.xyz), 1e-6);
  const float square_solid_angle =
      side * side * pixel_size.x * pixel_size.y * cos_axis * cos_axis * cos_axis;
  // Nothing to do far from the disc: the chord to the sun against the disc's radius plus the
  // square's half diagonal (an angle at most its size on the axis).
  const float reach = sun_angular_radius + 0.75 * side * max(pixel_size.x, pixel_size.y);
  if (length(view - sun) > reach) return 0.0;
  // 2 pi (1 - cos r), written without the cancellation of 1 - cos r in float (0.5 % at the
  // sun's 4.65e-3 rad).
  const float half_radius_sine = sin(0.5 * sun_angular_radius);
  const float disc_solid_angle = 4.0 * PI * half_radius_sine * half_radius_sine;
  if (4.0 * square_solid_angle <= disc_solid_angle) {
    int inside = 0;
    for (int i = 0; i < SUN_COVERAGE_SIDE; ++i)
      for (int j = 0; j < SUN_COVERAGE_SIDE; ++j) {
        const vec2 at = side * ((vec2(i, j) + 0.5) / float(SUN_COVERAGE_SIDE) - 0.5);
        if (dot(FrameViewRay(frag_coord + at), sun) > sun_cos_angular_radius) ++inside;
      }
    return float(inside) / float(SUN_COVERAGE_POINTS);
  }
  // The disc's points, located in window coordinates (FrameViewRay's inverse): the square is
  // centred on frag_coord + the sample's offset.
  const vec3 tangent = normalize(abs(sun.z) < 0.9 ? cross(sun, vec3(0.0, 0.0, 1.0))
                                                  : cross(sun, vec3(1.0, 0.0, 0.0)));
  const vec3 bitangent = cross(sun, tangent);
  const vec2 centre = frag_coord + frame_pixel_offset.xy;
  int inside = 0;
  for (int k = 0; k < SUN_COVERAGE_POINTS; ++k) {
    const float rho = sun_angular_radius * sqrt((float(k) + 0.5) / float(SUN_COVERAGE_POINTS));
    const float phi = float(k) * GOLDEN_ANGLE;
    const vec3 d = cos(rho) * sun + sin(rho) * (cos(phi) * tangent + sin(phi) * bitangent);
    const float along = dot(d, frame_camera_forward.xyz);
    if (!(along > 0.0)) continue;
    const vec2 ndc = vec2(dot(d, frame_camera_right.xyz) / frame_camera_right.w,
                          dot(d, frame_camera_up.xyz) / frame_camera_up.w) / along;
    const vec2 window = (ndc + 1.0) * 0.5 * frame_viewport.xy;
    const vec2 off = abs(window - centre);
    if (off.x < 0.5 * side && off.y < 0.5 * side) ++inside;
  }
  return float(inside) / float(SUN_COVERAGE_POINTS) * disc_solid_angle / square_solid_angle;
}
#endif

void main() {
  vec3 view = FrameViewRay(gl_FragCoord.xy);
  vec3 transmittance;
  vec3 sky = SkyBackgroundRadiance(camera_position, view, FrameSunDirection(), transmittance);
#ifdef SUN_DISC
  const float coverage = SunDiscCoverage(gl_FragCoord.xy, view, FrameSunDirection());
  if (coverage > 0.0) sky += transmittance * sun_disc_radiance * coverage;
#endif
  radiance = vec4(sky, 1.0);
}
