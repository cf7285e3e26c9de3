// The reference method's reflected sun (issue 6, point 1; Bruneton, Neyret & Holzschuch 2010,
// sec. 7.2: "several normal samples per pixel - up to 512 - to correctly sample the Sun, which
// occupies only 1/8000th of the hemisphere"), scattered from a lattice of the sea into the pixels
// that see it. One pass per reference image, before its samples: the result does not depend on
// where a sample falls in its pixel, so the sun adds no sampling noise at all, and its accuracy
// is the lattice's (checked by refining it: ocean_node.cpp, lattice_row_change).
//
// Why not point samples. A mirror reflects the sun's 0.27 degree disc toward the eye only where
// the slope lies in a disc of radius ~2.3e-3 around the mirror slope: about 7e-5 of a 10 m/s
// sea's slopes. Averaging point-sampled normals converges as 1 / sqrt(hits): 256 samples per
// pixel still changed an image row's sun by 96 % per doubling (stop 13).
//
// Why not gathered per pixel (stops 14-18). Integrating the sun over each sample's footprint on
// the sea at rest (taken from the rasterised grid under the sample) puts every glint in the
// pixel whose rest footprint holds it, not in the pixel where its displaced point is seen, and
// the footprints of a pixel's samples neither tile the sea exactly nor stay put between sample
// counts: the rows' totals still moved by 7.7 % per doubling at 32 samples (docs/validation.md).
//
// The lattice. Every pixel of the image, grown by `margin` pixels on each side, has a footprint
// on the sea at rest: the quadrilateral of the sea at rest under its four corners' rays (a
// corner whose ray misses the sea is put at the horizon's distance along it). Adjacent pixels
// share their corners, so the footprints tile the sea in view exactly. Each footprint is cut
// bilinearly into kx x ky cells no wider than `reference_spacing` (a fraction of the shortest
// wave's length: every wave resolved, its slope nearly linear across a cell), at most
// reference_max_cells^2 in all, in whatever shape (the cap: past it the cells are wider and the
// pixel is counted as unresolved). On each cell, every wave (w_n = w_p = 1, calm areas and wakes
// included) gives the four corners' displaced positions and exact normals; the slopes spread over
// the parallelogram of slope space the corners span, and the sun the cell reflects is eq. 15 with
// that parallelogram's density convolved with the sun's disc (OceanCellReflectedSun,
// ocean/cell_slope_density.glsl: the cells' parallelograms tile slope space as the cells tile the
// sea, so the sum over cells is the integral of delta(slope(x) - mirror slope) over the sea,
// seen through the sun's disc).
//
// The scatter. Each cell adds (solid angle x its sun) to the pixel in which its glint's displaced
// point is seen (the centroid over its bilinear patch of the weight with which each point
// reflects the sun's disc, ReferenceGlintCentroid: the point whose slope is the mirror slope
// where the cell is wider than the glint, its centre where it is much narrower), and its solid
// angle to the pixel of its displaced centre. A pixel's sun is then sum(omega sun) / sum(omega):
// the solid-angle weighted mean of the sun over the sea it sees, a box filter over the pixel.
// The lighting pass reads it (ocean_lighting.frag, REFERENCE_SUN) and applies the sun's
// transmitted irradiance at each sample.
//
// Visibility. A cell facing away from the eye is hidden (omega = 0). Within a cell, Smith's
// masking by its own slopes is in OceanCellReflectedSun. Between cells, the reference's grid (a
// vertex per pixel, every wave displaced) has drawn its depth before this pass: a cell farther
// than the farthest surface that grid shows in the cell's pixel is behind a crest and hidden.
// That farthest depth is the pixel centre's plus half the way to any farther neighbour (the
// pixel then straddles a crest's silhouette or a slope away from the eye) plus the heights of
// the waves the grid cannot draw (shorter than 2 footprints), seen along the view. So crests of
// waves longer than a pixel hide the sea behind them as they did for the gathered sun (stop 18);
// the shorter waves' masking is Smith's within the cell only. Not hiding them made rows 10 to
// 20 degrees below the horizon 10-30 % brighter (docs/validation.md): the glint's facets there
// tilt away from the eye, onto the backs of the waves.
//
// Output: per pixel (window coordinates, row-major from the bottom row), four floats in `sums`:
// sum omega sun, sum omega, the part of sum omega from footprints over the cap (unresolved), and
// the solid angle of the cells hidden behind the grid's crests (not in sum omega). Added by the
// float atomics of GL_NV_shader_atomic_float where the context has them
// (REFERENCE_FLOAT_ATOMICS), else by compare-and-swap on their bits (core GL has no float
// atomics): the same float additions, in an order that neither fixes.
#ifdef REFERENCE_FLOAT_ATOMICS
#extension GL_NV_shader_atomic_float : require
#endif
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "ocean/trochoids.glsl"
#ifdef CALM_AREAS
#include "ocean/calm_area.glsl"
#endif
#ifdef KELVIN_WAKES
#include "ocean/local_waves.glsl"
#endif
#include "ocean/cell_slope_density.glsl"
#include "ocean/reference_cell.glsl"

// One invocation per segment of reference_segment cells of a block of REFERENCE_ROWS rows of
// cells of one footprint (a row until stop 41), numbered without gaps (stop 34): footprint f's
// ceil(ky / REFERENCE_ROWS) x ceil(kx / reference_segment) invocations start at
// footprint_starts[f], counted from its batch's first, and within it consecutive invocations
// take consecutive blocks of one segment. The CPU (ocean_node.cpp, run_scatter) reads
// the footprints' kx and ky back after pass 1 and cuts the lattice into batches of whole
// footprints [first_footprint, footprint_end) whose invocations a 32-bit index counts; a
// dispatch is whole work groups of 64, and those past its count (id >= invocation_end) do
// nothing. Until stop 33 every footprint had cap x ceil(cap / reference_segment) slots whatever
// its cells, which held each side to the cap (a footprint of 50,000 x 1,000 cells would have
// needed 50,000^2 / reference_segment slots) and spent most invocations on slots past a small
// footprint's cells; in pass 2 the last work group's spare invocations once took the next
// batch's first footprint's rows, which that batch deposited again (stops 24-25: rows moved by
// up to 3 %).
//
// Why segments. llvmpipe (Mesa's CPU renderer, the tests' and CI's) ends every loop of a shader
// invocation once the invocation has run 65535 loop iterations in all (gallivm's
// LP_MAX_TGSI_LOOP_ITERATIONS, one counter shared by every loop), silently: a corner then sums
// a few of its waves, and a row of hundreds of cells, or a refined cell's subcells, came out
// wrong (stop 22 measured 20-70 % of the far rows' sun lost, and garbage, at 5 x 5 to 8 x 8
// subcells with 60 waves). The CPU (ocean_node.cpp, scatter_iterations) sizes the segments so
// that an invocation's worst case stays within half that budget there. An invocation evaluates
// every corner of its cells, (rows + 1)(segment + 1) for rows x segment cells. Until stop 41 the
// worst case was every cell refined in place: with 8 x 8 subcells, 4 cells at 60 waves and 2 at
// 120, a row at a time, 2.5 and 3.0 corners a cell, on every renderer. Stop 41 gave a renderer
// without the limit (a GPU) blocks of 4 rows of 64 cells (kScatterFreeBlockRows,
// kScatterFreeSegment; 1.27 a cell). Since stop 42 the refined cells go to a pass of their own
// (the refined cells' queue, below). Where a cell refined in place would not fit llvmpipe's
// budget beside a block's (the suite's 8 x 8 subcells with 60 waves or more), its worst case is
// then every cell unrefined, and it takes blocks too: 4 rows of 64 cells at 60 waves, of 32 at
// 120.
layout(local_size_x = 64) in;

// Rows of cells per invocation of pass 2 (the CPU's define: ocean_node.cpp,
// scatter_block_rows_): an invocation evaluates (REFERENCE_ROWS + 1) (segment + 1) corners for
// REFERENCE_ROWS x segment cells.
#ifndef REFERENCE_ROWS
#define REFERENCE_ROWS 1
#endif

// Two vec4 per wave, longest first (see ocean_geometry.frag).
layout(std430, binding = 1) readonly buffer Waves { vec4 waves[]; };
// 4 per pixel of the image (see above): the bits of floats.
#ifdef REFERENCE_FLOAT_ATOMICS
layout(std430, binding = 7) coherent buffer ReferenceSunSums { float sums[]; };
#else
layout(std430, binding = 7) coherent buffer ReferenceSunSums { uint sums[]; };
#endif

uniform int wave_count;
uniform vec2 downwind;  // unit, east-north-up
uniform float fresnel_r;  // R of Schlick's Fresnel (eq. 14), as in ocean_lighting.frag
// m: the widest cell on the sea at rest that counts as resolved (ocean_node.cpp:
// the shortest wavelength / cells per wavelength).
uniform float reference_spacing;
// The cap: most cells per footprint, reference_max_cells^2, in whatever shape its footprint
// needs (see the footprints' pass).
uniform int reference_max_cells;
// Subcells per side of a cell whose slopes come near the mirror slope (1: none; see
// ScatterCell), at most REFERENCE_MAX_REFINE.
uniform int reference_refine;
// 1/m^2: a bound on the second derivatives of the slope field (sum over the waves of h k^3),
// for how far a cell's slopes can stray from the bilinear patch of its corners' (ScatterCell).
uniform float slope_curvature;
uniform int margin;               // pixels added beyond each edge of the image
uniform uint first_invocation;    // of this dispatch (the CPU dispatches in batches)
uniform uint invocation_end;      // and one past its last (first_invocation + its count)
uniform uint first_footprint;     // pass 2: the batch's first footprint
uniform uint footprint_end;       // and one past its last
uniform int reference_segment;    // most cells of a row per invocation (see above)
// m: a bound on the displacement of every wave together (sum of amplitudes), for the margin's
// test below.
uniform float max_displacement;
// m: where a corner ray that misses the sea is put (the horizon's distance, as the lighting's).
uniform float horizon_distance;
// The grid's depth (reversed-Z, infinite far plane: OCEAN_NEAR_PLANE / forward distance; 0 where
// it drew nothing) at the pixels' centres.
layout(binding = 14) uniform sampler2D grid_depth;
const float OCEAN_NEAR_PLANE = 0.01;  // m, ocean.vert's
#ifdef KELVIN_WAKES
uniform float n_min;  // of the wakes' filter weights (every wake wave resolved here)
uniform float n_max;
#endif

// Deposits are summed in registers before they are added to `sums`: a float atomic add of one
// cell's share (1e-12 of a pixel's sun at the lattice's finest) to a pixel's running total
// (many thousand cells) would round it away. Two slots, because a cell's solid angle goes to
// the pixel of its centre and its sun to the pixel of its glint: with one slot, every glint in
// another pixel flushed both, and the refined cells' subcells (their glints mostly in one pixel)
// were added one by one - up to 72 % of a far row's sun lost at 8 x 8 subcells (stop 22,
// docs/validation.md). Slot 0 holds a pixel's sun (component 0), slot 1 its solid angles
// (components 1 to 3); consecutive cells of an invocation's row mostly share both.
int held_pixel[2] = int[2](-1, -1);
vec4 held[2] = vec4[2](vec4(0.0), vec4(0.0));

#ifdef REFERENCE_FLOAT_ATOMICS
void AtomicAdd(uint index, float value) {
  if (value != 0.0) atomicAdd(sums[index], value);
}
#else
// Under contention each round lets one invocation through (the H200 took 6-30 s per sun term
// with this version, stop 26, not profiled). Its rounds count toward llvmpipe's loop limit.
void AtomicAdd(uint index, float value) {
  if (value == 0.0) return;
  uint expected = sums[index];
  for (;;) {  // every round, one of the contending invocations succeeds
    const uint previous =
        atomicCompSwap(sums[index], expected, floatBitsToUint(uintBitsToFloat(expected) + value));
    if (previous == expected) return;
    expected = previous;
  }
}
#endif

void Flush(int slot) {
  if (held_pixel[slot] >= 0)
    for (int c = 0; c < 4; ++c) AtomicAdd(4u * uint(held_pixel[slot]) + uint(c), held[slot][c]);
  held_pixel[slot] = -1;
  held[slot] = vec4(0.0);
}

// Adds value (the pixel's four sums, see Output above) to pixel `pixel` (-1: none) through slot
// `slot` (0: the sun, 1: the solid angles).
void Deposit(int slot, int pixel, vec4 value) {
  if (pixel < 0) return;
  if (pixel != held_pixel[slot]) {
    Flush(slot);
    held_pixel[slot] = pixel;
  }
  held[slot] += value;
}

// The image's pixel (row-major from the bottom row) in which the point p (m, nadir frame) is
// seen, or -1 outside the image or behind the eye.
int PixelOf(vec3 p) {
  const vec3 d = p - FrameCameraPosition();
  const float along = dot(d, frame_camera_forward.xyz);
  if (!(along > 0.0)) return -1;
  const vec2 ndc = vec2(dot(d, frame_camera_right.xyz) / frame_camera_right.w,
                        dot(d, frame_camera_up.xyz) / frame_camera_up.w) / along;
  const vec2 window = (ndc + 1.0) * 0.5 * frame_viewport.xy;
  if (!(window.x >= 0.0 && window.y >= 0.0 && window.x < frame_viewport.x &&
        window.y < frame_viewport.y))
    return -1;
  const ivec2 pixel = min(ivec2(window), ivec2(frame_viewport.xy) - 1);
  return pixel.y * int(frame_viewport.x) + pixel.x;
}

// The forward distance (m) of the grid's surface at the pixel (x, y) of the image, clamped to
// the image; +inf where the grid drew nothing.
float GridAlong(ivec2 pixel) {
  const float depth =
      texelFetch(grid_depth, clamp(pixel, ivec2(0), ivec2(frame_viewport.xy) - 1), 0).r;
  return depth > 0.0 ? OCEAN_NEAR_PLANE / depth : 1.0 / 0.0;
}

// m: a forward distance past every cell, for a neighbour beyond the sea's horizon.
const float BEYOND_HORIZON = 1e30;

// The forward distance (m) of the grid's surface at the pixel xy + offset, a neighbour of the
// image's pixel xy; +inf where the grid drew nothing there. Beyond the image, where the grid's
// depth was not kept, it is extrapolated from xy and its neighbour on the other side: linearly in
// the depth, which is linear on the screen over a plane (1 / forward distance, as perspective
// interpolates), so that over a calm sea an edge pixel's half beyond its centre is not hidden
// (clamped to the edge, the top row of a view pitched below the horizon lost that half:
// tests/gpu/method_test.cpp, ScatteredSunsSolidAnglesAreThePixels); BEYOND_HORIZON where the
// extrapolation passes the horizon, +inf (nothing known) where xy or that neighbour drew nothing.
float NeighbourAlong(ivec2 xy, ivec2 offset) {
  const ivec2 size = ivec2(frame_viewport.xy);
  const ivec2 neighbour = xy + offset;
  if (all(greaterThanEqual(neighbour, ivec2(0))) && all(lessThan(neighbour, size)))
    return GridAlong(neighbour);
  const ivec2 inward = xy - offset;
  if (!(all(greaterThanEqual(inward, ivec2(0))) && all(lessThan(inward, size)))) return 1.0 / 0.0;
  const float edge = texelFetch(grid_depth, xy, 0).r;
  const float inner = texelFetch(grid_depth, inward, 0).r;
  if (!(edge > 0.0 && inner > 0.0)) return 1.0 / 0.0;
  const float depth = 2.0 * edge - inner;
  return depth > 0.0 ? OCEAN_NEAR_PLANE / depth : BEYOND_HORIZON;
}

// Whether the displaced point p (m, nadir frame), seen in pixel `pixel` (PixelOf), lies no
// farther than the farthest surface the grid shows in that pixel, give or take `unresolved_height`
// (m: the heights of the waves the grid cannot draw) along the view.
bool GridShows(vec3 p, int pixel, float unresolved_height) {
  const vec3 d = p - FrameCameraPosition();
  const float along = dot(d, frame_camera_forward.xyz);
  const ivec2 xy = ivec2(pixel % int(frame_viewport.x), pixel / int(frame_viewport.x));
  const float centre = GridAlong(xy);
  if (isinf(centre)) return true;
  float farthest = centre;
  for (int k = 0; k < 4; ++k) {
    const ivec2 o = k == 0 ? ivec2(1, 0) : k == 1 ? ivec2(-1, 0) : k == 2 ? ivec2(0, 1) : ivec2(0, -1);
    const float neighbour = NeighbourAlong(xy, o);
    if (!isinf(neighbour)) farthest = max(farthest, 0.5 * (centre + neighbour));
  }
  // A height h moves the surface along the view by h / sin(elevation of the view).
  const float sine = max(-d.z / max(length(d), 1e-6), 0.05);
  return along <= farthest + unresolved_height / sine;
}

// The rest point (m, nadir frame) seen through the window position w (pixels, unshifted by the
// frame's pixel offset: the lattice is the same for every sample), and whether the ray met the
// sea (false: the point at the horizon's distance along it, dropped onto the sea at rest).
vec3 RestCorner(vec2 w, out bool hit) {
  const vec2 ndc = w * frame_viewport.zw * 2.0 - 1.0;
  const vec3 ray = normalize(frame_camera_forward.xyz +
                             ndc.x * frame_camera_right.w * frame_camera_right.xyz +
                             ndc.y * frame_camera_up.w * frame_camera_up.xyz);
  const float distance = FrameSeaDistance(ray);
  hit = distance >= 0.0;
  const vec3 p = FrameCameraPosition() + (hit ? distance : horizon_distance) * ray;
  return vec3(p.x, p.y, ReferenceRestHeight(frame_sea_curvature, vec2(p.x, p.y)));
}

// m, nadir frame: the horizontal rest position of the footprint the invocation scatters (its
// corner q00), from which its corners' positions are given (Corner.rest, ReferenceCorner).
vec2 footprint_origin = vec2(0.0);

// Why the corners are given from the footprint's origin (stop 31). A wave's argument, theta =
// Phi - k.x (trochoids.glsl, TrochoidArgument), reaches k |x| = 157 rad/m x 25 m = 3,900 rad
// for the 4 m cases' shortest wave (0.04 m) 25 m ahead, where a float's step is 2.4e-4 rad; the
// corner's own xy, rounded to float at 25 m, adds 2e-6 m x 157. At 128 cells per wavelength and
// 8 x 8 subcells a subcell's edge is 3.9e-5 m, 6e-3 rad of that wave, so the slope differences
// across it, which make its parallelogram, carried a rounding noise of 1.5 % rms and its
// determinant 3.4 % (1.1 % at 8 m; measured in float against double on the 30-wave 20 m/s sea;
// 0.16-0.40 % at 16 per wavelength; docs/validation.md, stop 31). Near a fold of the slope map, where det is small and the brightest glints are,
// that noise is a large part of det, and it grows as the cells shrink: stop 30's H200 saw that
// reference move rows by 2.2, 3.2 and 5.1 % at 16, 45 and 128 per wavelength. Split as theta =
// Phi_o - k.(x - o) (TrochoidArgumentFrom), Phi_o the same float for every corner of the
// footprint, and x - o the corner's offset in the footprint (bilinear in the footprint's edges,
// so exact to the footprint's size), the noise is 0.05-0.06 % of det at 128 (the same measure).
// Phi_o's own rounding (up to 2.4e-4 rad) is common to the footprint: it moves each footprint's
// waves by at most 2 micrometres, and no corner relative to its neighbours.
//
// One lattice corner at the offset `local` (m, nadir frame's axes) from footprint_origin: its
// displaced position (m, nadir frame), its displaced area vector per unit rest area d_dx x d_dy
// (nadir frame) and that vector in its own tangent frame scaled to unit z (the facet normal f of
// ReferenceCellFrameSlope: (-zeta, 1) in the rest tangent frame), turned into the nadir frame.
struct Corner {
  vec3 position;
  vec3 area;
  vec3 facet;
  vec2 rest;  // m: the offset `local` from footprint_origin it was computed at
};

Corner ReferenceCorner(vec2 local) {
  const vec2 xy = footprint_origin + local;
  const vec3 x = vec3(xy, ReferenceRestHeight(frame_sea_curvature, xy));
  vec3 displacement = vec3(0.0);
  vec3 d_dx = vec3(0.0), d_dy = vec3(0.0);
  for (int i = 0; i < wave_count; ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
    const vec2 direction = vec2(a.x, a.y);
    const float argument = TrochoidArgumentFrom(a.z * direction, b.x, footprint_origin, local);
    displacement += TrochoidDisplacement(direction, a.w, argument);
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(direction, a.z, a.w, argument, wave_dx, wave_dy);
    d_dx += wave_dx;
    d_dy += wave_dy;
  }
#ifdef CALM_AREAS
  const float calm = CalmAmplitudeScale(xy);  // issue 9: every wave's h scaled by s
  displacement *= calm;
  d_dx *= calm;
  d_dy *= calm;
#endif
  d_dx += vec3(1.0, 0.0, 0.0);
  d_dy += vec3(0.0, 1.0, 0.0);
#ifdef KELVIN_WAKES
  // The wakes' waves, every one resolved (a vanishing cell gives w_p = w_n = 1, w_r = 0).
  displacement += LocalWavesDisplacement(xy, 1e-6, n_min, n_max, 1.0);
  vec2 no_variance = vec2(0.0);
  LocalWavesNormals(xy, 1e-6, n_min, n_max, 1.0, vec2(1.0, 0.0), d_dx, d_dy, no_variance);
#endif
  const mat3 frame = FrameSeaTangentFrame(x);
  const vec3 n_local = cross(d_dx, d_dy);
  Corner corner;
  corner.position = x + frame * displacement;
  corner.area = frame * n_local;
  corner.facet = frame * vec3(n_local.xy / max(n_local.z, 1e-6), 1.0);
  corner.rest = local;
  return corner;
}

// What one cell of corners c00, c10 (along u), c01 (along v), c11 reflects of the sun toward
// the eye at `eye_from` (a point of the cell, m, nadir frame): the sun per unit solid angle
// (OceanCellReflectedSun, in the tangent frame of the cell's mean facet normal), the displaced
// point its glint's light comes from (the centroid of the sun's weight over its bilinear patch:
// ReferenceGlintCentroid), and for the refinement test the mirror slope and the box of the
// corners' slopes in that frame, grown by a quarter of the patch's twist (z00 - z10 - z01 + z11),
// which then holds the parallelogram OceanCellReflectedSun integrates over (its vertices are the
// corners' slopes moved by +-twist / 4).
struct CellGlint {
  float sun;
  vec3 point;
  vec2 mirror;
  vec2 low, high;
};

CellGlint ReferenceCellGlint(Corner c00, Corner c10, Corner c01, Corner c11, vec3 v) {
  CellGlint g;
  const vec3 l = FrameSunDirection();
  vec3 n = normalize(c00.facet + c10.facet + c01.facet + c11.facet);
  if (dot(n, v) < 0.0) n = normalize(n - 2.0 * dot(n, v) * v);
  const vec3 wind = vec3(downwind, 0.0);
  const vec3 t_x = normalize(wind - dot(wind, n) * n);
  const vec3 t_y = cross(n, t_x);
  const vec2 z00 = ReferenceCellFrameSlope(c00.facet, t_x, t_y, n);
  const vec2 z10 = ReferenceCellFrameSlope(c10.facet, t_x, t_y, n);
  const vec2 z01 = ReferenceCellFrameSlope(c01.facet, t_x, t_y, n);
  const vec2 z11 = ReferenceCellFrameSlope(c11.facet, t_x, t_y, n);
  const vec2 c = 0.25 * (z00 + z10 + z01 + z11);
  const vec2 d_u = 0.5 * ((z10 - z00) + (z11 - z01));
  const vec2 d_v = 0.5 * ((z01 - z00) + (z11 - z10));
  const vec3 v_t = OceanToTangentFrame(v, t_x, t_y, n);
  const vec3 l_t = OceanToTangentFrame(l, t_x, t_y, n);
  g.sun = OceanCellReflectedSun(v_t, l_t, c, d_u, d_v, fresnel_r);
  // The mirror slope: that of the half vector, (-h_x, -h_y) / h_z.
  const vec3 h = normalize(v_t + l_t);
  g.mirror = -vec2(h.x, h.y) / max(h.z, 1e-6);
  g.point = ReferenceBilinear(
      c00.position, c10.position, c01.position, c11.position,
      ReferenceGlintCentroid(c, d_u, d_v, g.mirror, sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE)));
  const vec2 twist = 0.25 * abs(z00 - z10 - z01 + z11);
  g.low = min(min(z00, z10), min(z01, z11)) - twist;
  g.high = max(max(z00, z10), max(z01, z11)) + twist;
  return g;
}

// The most subcells per side of a refined cell (the corner rows ScatterCell keeps).
#define REFERENCE_MAX_REFINE 8
// The share per side of the cells wanted that a footprint just past the cap takes (fewer beyond):
// its pixel is reported unresolved and compared nowhere, so its lattice only draws the
// reference's picture of the far glitter (see the footprints' pass).
#define REFERENCE_UNRESOLVED_SHARE 0.25
// 2^24: the most cells a side may have, the largest float below which every whole number is one.
const float FLOAT_WHOLE_NUMBERS = 16777216.0;
// A cell's slopes within this many sigma of the sun's disc (sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE))
// of the mirror slope are refined: beyond it the disc's Gaussian is below exp(-8) = 3e-4 of its
// peak, and the cell reflects nothing a finer cut would change.
const float REFERENCE_REFINE_SIGMAS = 4.0;

// The refined cells' queue (stop 42). A cell near the mirror slope costs its (refine + 1)^2 - 4
// subcells' corners, 77 at 8 x 8 against the 1.27 an unrefined cell costs in a block of 4 x 64,
// and few cells are refined (ScatterCell). Refined where the cells' pass meets them, every lane
// of a GPU's warp (or llvmpipe's 8 in lockstep) waited on each lane's refined cells in turn, and
// llvmpipe's loop budget sized every invocation for all of its cells refined. So the cells' pass
// puts each refined cell's place into this queue (the footprint, the cell's column and row) and
// the refined cells' pass (REFERENCE_REFINE_PASS) refines one cell an invocation. The CPU
// dispatches the cells' pass in chunks and the refined cells' pass after each, indirectly from
// the header: [0] its work groups, [1], [2] 1, [3] the refined cells met in the chunk (those
// past refined_capacity are refined in place: the queue is full), [4] the lattice's refined
// cells, [5] those refined in place. refined_capacity 0: every refined cell is refined in place,
// as before stop 42. [3] counts at most a chunk's cells (the CPU's scatter_chunk_, under 2^27);
// [4] and [5] are the statistics' alone and would wrap past 2^32 refined cells in one lattice
// (2^34 cells a quarter refined, far past the suite's 2.4e7 at 0.07 %).
layout(std430, binding = 10) coherent buffer ReferenceRefinedCells {
  uint refined_header[8];
  uvec4 refined_cells[];
};
uniform uint refined_capacity;
// This invocation's refined cells and those of them refined in place, added to the header's [4]
// and [5] once at its end (FlushRefinedCounts) rather than by an atomic each.
uint refined_count = 0u, refined_in_place = 0u;

void FlushRefinedCounts() {
  if (refined_count > 0u) atomicAdd(refined_header[4], refined_count);
  if (refined_in_place > 0u) atomicAdd(refined_header[5], refined_in_place);
}

// The sun of the refined cell of corners c00, c10 (along u), c01 (along v), c11 and rest area
// rest_area (m^2): each of its refine x refine subcells with its own exact corners (every wave),
// a row of corners at a time (rest positions bilinear in the cell's), deposited to the pixel of
// its glint.
void RefineCell(Corner c00, Corner c10, Corner c01, Corner c11, float rest_area, int refine) {
  Corner below[REFERENCE_MAX_REFINE + 1], above[REFERENCE_MAX_REFINE + 1];
  const float sub_area = rest_area / float(refine * refine);
  for (int j = 0; j <= refine; ++j) {
    const float t = float(j) / float(refine);
    for (int i = 0; i <= refine; ++i) {
      const float u = float(i) / float(refine);
      if ((i == 0 || i == refine) && (j == 0 || j == refine)) {
        above[i] = j == 0 ? (i == 0 ? c00 : c10) : (i == 0 ? c01 : c11);
      } else {
        above[i] = ReferenceCorner(mix(mix(c00.rest, c10.rest, u), mix(c01.rest, c11.rest, u), t));
      }
    }
    if (j > 0) {
      for (int i = 0; i < refine; ++i) {
        const Corner s00 = below[i], s10 = below[i + 1], s01 = above[i], s11 = above[i + 1];
        const vec3 sub_centre = 0.25 * (s00.position + s10.position + s01.position + s11.position);
        const vec3 sub_to_eye = FrameCameraPosition() - sub_centre;
        const float sub_omega = ReferenceCellSolidAngle(
            0.25 * (s00.area + s10.area + s01.area + s11.area), sub_area, sub_to_eye);
        if (!(sub_omega > 0.0)) continue;
        const CellGlint sub = ReferenceCellGlint(s00, s10, s01, s11, normalize(sub_to_eye));
        if (sub.sun > 0.0) Deposit(0, PixelOf(sub.point), vec4(sub_omega * sub.sun, 0.0, 0.0, 0.0));
      }
    }
    for (int i = 0; i <= refine; ++i) below[i] = above[i];
  }
}

// One cell of corners c00, c10 (along u), c01 (along v), c11, rest area rest_area (m^2) and
// longer rest side `size` (m), at `place` (its footprint, column and row: the refined cells'
// queue): its deposits. unresolved: 1 if its footprint is over the cap, else 0.
//
// Refinement. The parallelogram a cell's corners span is a linearisation of its slope field:
// each glint it holds is counted with the secant's 1 / |det dzeta/dx| instead of the tangent's at
// the glint, an error of the order of the cell's size (its bias, averaged over many glints, of
// its square: tests/unit/cell_slope_density_test.cpp). Only the few cells whose slopes come near
// the mirror slope reflect the sun at all (0.07 % of wind10_100m_low_sun's at 16 cells per
// wavelength, 2 % of the tests' small view at 4, a quarter at 2: stop 42), so those are cut
// into reference_refine x reference_refine subcells, each with its own exact corners (every
// wave) and parallelogram, as if the lattice were that much finer where it matters and no finer
// elsewhere (RefineCell, in place or from the queue). A cell's slopes are the patch of
// its corners' to within slope_curvature x size^2 / 8 (the bilinear interpolant's error for
// second derivatives below slope_curvature), which widens the test so that a glint the corners'
// box misses is refined too.
void ScatterCell(Corner c00, Corner c10, Corner c01, Corner c11, float rest_area, float size,
                 float unresolved, float unresolved_height, uvec3 place) {
  const vec3 centre = 0.25 * (c00.position + c10.position + c01.position + c11.position);
  const vec3 to_eye = FrameCameraPosition() - centre;
  const float omega =
      ReferenceCellSolidAngle(0.25 * (c00.area + c10.area + c01.area + c11.area), rest_area,
                              to_eye);
  if (!(omega > 0.0)) return;
  const int centre_pixel = PixelOf(centre);
  if (centre_pixel < 0) return;
  if (!GridShows(centre, centre_pixel, unresolved_height)) {
    Deposit(1, centre_pixel, vec4(0.0, 0.0, 0.0, omega));
    return;
  }
  const CellGlint g = ReferenceCellGlint(c00, c10, c01, c11, normalize(to_eye));
  const float margin = REFERENCE_REFINE_SIGMAS * sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE) +
                       0.125 * slope_curvature * size * size;
  const int refine = clamp(reference_refine, 1, REFERENCE_MAX_REFINE);
  // Footprints over the cap are not compared (their pixels are reported unresolved): their cells
  // are not refined either.
  if (refine > 1 && unresolved == 0.0 && all(greaterThanEqual(g.mirror, g.low - margin)) &&
      all(lessThanEqual(g.mirror, g.high + margin))) {
    ++refined_count;
    const uint index = refined_capacity > 0u ? atomicAdd(refined_header[3], 1u) : 0xffffffffu;
    if (index < refined_capacity) {
      refined_cells[index] = uvec4(place, 0u);
      // The queue's places are taken without gaps from 0, so one in 64 starts a work group.
      if (index % 64u == 0u) atomicAdd(refined_header[0], 1u);
    } else {
      ++refined_in_place;
      RefineCell(c00, c10, c01, c11, rest_area, refine);
    }
  } else if (g.sun > 0.0) {
    Deposit(0, PixelOf(g.point), vec4(omega * g.sun, 0.0, 0.0, 0.0));
  }
  Deposit(1, centre_pixel, vec4(0.0, omega, omega * unresolved, 0.0));
}

// Pass 1 (REFERENCE_FOOTPRINT_PASS), one invocation per footprint: its rest corners, cells per
// side and the heights the grid cannot draw, into `footprints` (3 vec4 per footprint: q00.xy,
// q10.xy; q01.xy, q11.xy; kx, ky (0: nothing to scatter), unresolved, unresolved_height). Pass 2
// reads them, so that its many invocations past a footprint's rows and segments cost a read.
layout(std430, binding = 8) buffer ReferenceFootprints { vec4 footprints[]; };

#ifdef REFERENCE_FOOTPRINT_PASS
void main() {
  const int cap = max(reference_max_cells, 1);
  const uint footprint = first_invocation + gl_GlobalInvocationID.x;
  if (footprint >= invocation_end) return;
  const int columns = int(frame_viewport.x) + 2 * margin;
  const int rows = int(frame_viewport.y) + 2 * margin;
  if (footprint >= uint(columns * rows)) return;
  footprints[3u * footprint + 2u] = vec4(0.0);  // nothing, unless it is kept below
  const vec2 pixel = vec2(float(int(footprint) % columns - margin),
                          float(int(footprint) / columns - margin));
  bool h00, h10, h01, h11;
  const vec3 q00 = RestCorner(pixel, h00);
  const vec3 q10 = RestCorner(pixel + vec2(1.0, 0.0), h10);
  const vec3 q01 = RestCorner(pixel + vec2(0.0, 1.0), h01);
  const vec3 q11 = RestCorner(pixel + vec2(1.0, 1.0), h11);
  if (!(h00 || h10 || h01 || h11)) return;  // the sky's pixel
  // A margin pixel whose sea no wave can move into the image: the farthest a point at forward
  // distance `along` moves on screen is about max_displacement / along / (the image's tan per
  // pixel), doubled for the projection's change with depth.
  const vec2 outside = max(max(-pixel - 1.0, pixel - frame_viewport.xy), vec2(0.0));
  if (outside.x > 0.0 || outside.y > 0.0) {
    const vec3 eye = FrameCameraPosition();
    const float along = max(min(min(dot(q00 - eye, frame_camera_forward.xyz),
                                    dot(q10 - eye, frame_camera_forward.xyz)),
                                min(dot(q01 - eye, frame_camera_forward.xyz),
                                    dot(q11 - eye, frame_camera_forward.xyz))),
                            1e-3);
    const float reach = 2.0 * max_displacement / along * 0.5 * frame_viewport.y / frame_camera_up.w;
    if (max(outside.x, outside.y) > reach + 1.0) return;
  }
  // Cells per side: no wider than the spacing, at most cap^2 in all, whatever the footprint's
  // shape (stop 34: until then at most the cap per side, which the long and narrow footprints
  // near the horizon, 10,000 x 500 cells 3 rows below it on the suite's 100 m views, could not
  // fit at any cap: docs/validation.md, "The sun's far rows"). A footprint past the cap (it is
  // reported unresolved, and not compared) keeps its shape with REFERENCE_UNRESOLVED_SHARE^2
  // cap^2 sqrt(cap^2 / want) cells (want: the cells it would need): a sixteenth of the cap past
  // the cap, then fewer with distance, so that the far rows, which no affordable cap resolves,
  // stop costing the cap's lattice each (they were most of the reference's time). On a square
  // footprint that is the rule of stops 22-33, REFERENCE_UNRESOLVED_SHARE cap sqrt(cap /
  // side) per side; measured on wind10_100m_low_sun (stop 22): cap sqrt(cap / want) halved the
  // time (rows past the cap moved by a few per cent, the two nearest the horizon by 30-40 %),
  // and the quarter of it 248 to 143 s more (the unresolved rows by up to 50 %); the resolved
  // rows did not change at all, bit for bit (docs/validation.md). A side's count stays within
  // 2^24, a float's whole numbers (the horizon's row wants 333,000 along the view at 16 per
  // wavelength), and a footprint's within cap^2 <= 16384^2, which one batch's 32-bit
  // invocation index counts.
  const float spacing = max(reference_spacing, 1e-6);
  const float budget = float(cap) * float(cap);
  const float want_x = max(ceil(max(distance(q00, q10), distance(q01, q11)) / spacing), 1.0);
  const float want_y = max(ceil(max(distance(q00, q01), distance(q10, q11)) / spacing), 1.0);
  const float want = want_x * want_y;
  const float unresolved = want <= budget ? 0.0 : 1.0;
  // Per side: the fraction of the cells wanted, REFERENCE_UNRESOLVED_SHARE (budget / want)^(3/4).
  const float scale =
      unresolved == 0.0 ? 1.0 : REFERENCE_UNRESOLVED_SHARE * pow(budget / want, 0.75);
  const float kx = clamp(ceil(want_x * scale), 1.0, min(budget, FLOAT_WHOLE_NUMBERS));
  const float ky = clamp(ceil(want_y * scale), 1.0, min(budget, FLOAT_WHOLE_NUMBERS));
  // The heights of the waves the grid (a vertex per pixel) cannot draw: shorter than 2
  // footprints (the wakes' are not counted).
  const float footprint_size = max(max(distance(q00, q10), distance(q01, q11)),
                                   max(distance(q00, q01), distance(q10, q11)));
  float unresolved_height = 0.0;
  for (int i = 0; i < wave_count; ++i)
    if (waves[2 * i + 1].y < 2.0 * footprint_size) unresolved_height += waves[2 * i].w;
  footprints[3u * footprint] = vec4(q00.xy, q10.xy);
  footprints[3u * footprint + 1u] = vec4(q01.xy, q11.xy);
  footprints[3u * footprint + 2u] = vec4(kx, ky, unresolved, unresolved_height);
}
#else
// A block of pass 2 (REFERENCE_ROWS rows of cells from row j, the segment's cells from column
// first, of one footprint) and its corners' rest offsets from footprint_origin, which
// StartBlock sets to the block's first corner. Each corner is given from that corner by
// differences that stay as small as the block: a corner's offset from the footprint's q00
// reaches the footprint's length, 64,000 cells one row below the horizon on the suite's views,
// where a float's rounding is 1.5e-3 rad of the shortest wave's argument (2 pi 64,000 / 16 x
// 6e-8), 3 % of the 0.049 rad across a subcell at 16 cells per wavelength and 8 x 8 subcells;
// the arguments' differences across a subcell, from which its parallelogram is made, would carry
// that rounding (stop 31's noise; 0.1 % at the 2,048 cells a side that were the most until stop
// 34). Row v's corner at u is a(v) + u (b(v) - a(v)), a(v) = v q01, b(v) = q10 + v (q11 - q10)
// (q.. the footprint's corners from its q00). From row j's corner at u0, row j + r's at u0 + du
// is r (q01 + u0 twist) / ky + du edge_r, with twist = q11 - q10 - q01 and edge_r = edge_0 + r
// twist / ky its edge along u. The refined cells' pass (REFERENCE_REFINE_PASS) starts the block
// of its cell's place again with the same expressions, so that its corners are the cells'
// pass's to the float's rounding (two programs may contract them into fused multiply-adds
// otherwise; a subcell's edges then miss its neighbour's by about 1e-7 of the block).
struct Block {
  int kx, ky;               // the footprint's cells along u and v
  int first, j;             // the block's first column and row of cells
  float unresolved;         // 1: the footprint is over the cap
  float unresolved_height;  // m: the waves the grid cannot draw (GridShows)
  vec2 step;                // m: along v, per row of cells times ky, at u0
  vec2 edge0, twist;        // m: row j's edge along u, and the footprint's twist
};

// footprint's block from column `first` and row j of cells; sets footprint_origin.
Block StartBlock(uint footprint, int first, int j) {
  Block b;
  const vec4 cells = footprints[3u * footprint + 2u];
  b.kx = int(cells.x);
  b.ky = int(cells.y);
  b.first = first;
  b.j = j;
  b.unresolved = cells.z;
  b.unresolved_height = cells.w;
  const vec4 q0 = footprints[3u * footprint], q1 = footprints[3u * footprint + 1u];
  // The footprint's corners from its q00 (m, nadir frame's axes).
  const vec2 q10 = q0.zw - q0.xy, q01 = q1.xy - q0.xy, q11 = q1.zw - q0.xy;
  const float v0 = float(j) / float(b.ky);
  const vec2 a0 = v0 * q01, b0 = mix(q10, q11, v0);
  b.edge0 = b0 - a0;
  b.twist = q11 - q10 - q01;
  const float u0 = float(first) / float(b.kx);
  footprint_origin = q0.xy + (a0 + u0 * b.edge0);
  b.step = q01 + u0 * b.twist;
  return b;
}

// m, from footprint_origin: the block's corner r rows above its first and `column` columns
// right of its first.
vec2 BlockCornerOffset(Block b, int r, int column) {
  const vec2 row_start = float(r) * b.step / float(b.ky);
  const vec2 row_edge = b.edge0 + float(r) * b.twist / float(b.ky);
  return row_start + (float(column) / float(b.kx)) * row_edge;
}

// The rest point (m, from footprint_origin, with the rest height at it) of a block's corner.
vec3 BlockCornerRest(vec2 offset) {
  return vec3(offset, ReferenceRestHeight(frame_sea_curvature, footprint_origin + offset));
}

// The rest area (m^2) of the cell of rest corners r00, r10 (along u), r01, r11: its bilinear
// patch's, |e_u x e_v| with the mean edges; and its longer mean edge (m).
vec2 RestCellSize(vec3 r00, vec3 r10, vec3 r01, vec3 r11) {
  const vec3 e_u = 0.5 * ((r10 - r00) + (r11 - r01));
  const vec3 e_v = 0.5 * ((r01 - r00) + (r11 - r10));
  return vec2(length(cross(e_u, e_v)), max(length(e_u), length(e_v)));
}

#ifdef REFERENCE_REFINE_PASS
// Pass 3: one invocation per refined cell queued by the chunk of pass 2 just run (the queue
// above): its block started again, its four corners, and its subcells.
void main() {
  const uint index = gl_GlobalInvocationID.x;
  if (index >= min(refined_header[3], refined_capacity)) return;
  const uvec4 place = refined_cells[index];
  const int segment_cells = max(reference_segment, 1);
  const int column = int(place.y), row = int(place.z);
  const Block b = StartBlock(place.x, (column / segment_cells) * segment_cells,
                             (row / REFERENCE_ROWS) * REFERENCE_ROWS);
  const int r = row - b.j, i = column - b.first;
  const vec2 o00 = BlockCornerOffset(b, r, i), o10 = BlockCornerOffset(b, r, i + 1);
  const vec2 o01 = BlockCornerOffset(b, r + 1, i), o11 = BlockCornerOffset(b, r + 1, i + 1);
  const vec2 size = RestCellSize(BlockCornerRest(o00), BlockCornerRest(o10), BlockCornerRest(o01),
                                 BlockCornerRest(o11));
  RefineCell(ReferenceCorner(o00), ReferenceCorner(o10), ReferenceCorner(o01),
             ReferenceCorner(o11), size.x, clamp(reference_refine, 1, REFERENCE_MAX_REFINE));
  Flush(0);
}
#else
// Pass 2: one invocation per segment of a block of rows of cells of a footprint (see above).
layout(std430, binding = 9) readonly buffer ReferenceFootprintStarts { uint footprint_starts[]; };

void main() {
  const int segment_cells = max(reference_segment, 1);
  const uint id = first_invocation + gl_GlobalInvocationID.x;
  if (id >= invocation_end) return;
  // The footprint: the last of the batch whose first invocation is not past id (footprints with
  // no cells share their start with the next, and are passed over).
  uint low_footprint = first_footprint, high_footprint = footprint_end;
  while (high_footprint - low_footprint > 1u) {
    const uint middle = (low_footprint + high_footprint) / 2u;
    if (footprint_starts[middle] <= id)
      low_footprint = middle;
    else
      high_footprint = middle;
  }
  const uint footprint = low_footprint;
  const vec4 cells = footprints[3u * footprint + 2u];
  const int kx = int(cells.x), ky = int(cells.y);
  if (ky < 1) return;
  // Consecutive invocations take consecutive blocks of REFERENCE_ROWS rows of one segment: the
  // SIMD lanes of a work group (llvmpipe runs 8 in lockstep) are then active or idle together.
  const uint local_id = id - footprint_starts[footprint];
  const int blocks = (ky + REFERENCE_ROWS - 1) / REFERENCE_ROWS;
  const int first = int(local_id / uint(blocks)) * segment_cells;
  if (first >= kx) return;
  const Block b = StartBlock(footprint, first, int(local_id % uint(blocks)) * REFERENCE_ROWS);
  const int rows = min(REFERENCE_ROWS, ky - b.j);
  const int last = min(kx, first + segment_cells);
  // The column of corners (and their rest points, m, from footprint_origin) at the left of the
  // cells being scattered, then at their right.
  Corner left[REFERENCE_ROWS + 1], right[REFERENCE_ROWS + 1];
  vec3 left_rest[REFERENCE_ROWS + 1], right_rest[REFERENCE_ROWS + 1];
  for (int r = 0; r <= REFERENCE_ROWS; ++r) {
    if (r > rows) break;
    const vec2 offset = BlockCornerOffset(b, r, 0);
    left[r] = ReferenceCorner(offset);
    left_rest[r] = BlockCornerRest(offset);
  }
  for (int i = first + 1; i <= last; ++i) {
    for (int r = 0; r <= REFERENCE_ROWS; ++r) {
      if (r > rows) break;
      const vec2 offset = BlockCornerOffset(b, r, i - first);
      right[r] = ReferenceCorner(offset);
      right_rest[r] = BlockCornerRest(offset);
    }
    for (int r = 0; r < REFERENCE_ROWS; ++r) {
      if (r >= rows) break;
      const vec2 size =
          RestCellSize(left_rest[r], right_rest[r], left_rest[r + 1], right_rest[r + 1]);
      ScatterCell(left[r], right[r], left[r + 1], right[r + 1], size.x, size.y, b.unresolved,
                  b.unresolved_height, uvec3(footprint, uint(i - 1), uint(b.j + r)));
    }
    for (int r = 0; r <= REFERENCE_ROWS; ++r) {
      left[r] = right[r];
      left_rest[r] = right_rest[r];
    }
  }
  Flush(0);
  Flush(1);
  FlushRefinedCounts();
}
#endif
#endif
