#include "thalassa/ocean/gl/ocean_node.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ross_brdf_reference.hpp"
#include "scattered_sun_sums.hpp"
#include "thalassa/atmosphere/gl/sky_shrm.hpp"
#include "thalassa/ocean/gl/effective_fresnel_texture.hpp"
#include "thalassa/ocean/gl/local_features_gpu.hpp"
#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/ocean/wave_set.hpp"

namespace thalassa::ocean {

// ocean/scattered_sun_cache.hpp: one lattice's sums and everything the scatter read to make them.
class ScatteredSunCache {
 public:
  struct Key {
    // The frame, its pixel offset included: the cells were hidden by the grid's depth as drawn
    // at the first sample's offset.
    gl::FrameInputs view;
    glm::dvec2 downwind{0.0};  // unit, east-north-up
    double fresnel_r = 0.0, n_min = 0.0, n_max = 0.0;
    double planet_radius = 0.0;  // m
    std::uint64_t waves = 0;     // wave_digest
    double cells_per_wavelength = 0.0;
    int cells = 0;               // at most its square per pixel's footprint
    int refine = 0;              // subcells per side asked for
    bool float_atomics = false;  // asked for and available
  };
  struct Lattice {
    Key key;
    std::vector<float> sums;  // 4 per pixel, as reference_sun_scatter.comp leaves them
    int margin = 0;           // pixels (RenderStats::sun_lattice_margin)
    int refine = 0;           // subcells per side as run
    int segment = 0;          // cells per invocation as run (RenderStats::sun_lattice_segment)
    int block_rows = 0;       // rows per invocation as run (RenderStats::sun_lattice_block_rows)
    std::int64_t refined_queue = 0;  // the refined cells' queue as run (0: refined in place)
    double cells = 0.0, refined_cells = 0.0, refined_in_place = 0.0;  // its cells, as scattered
    double hidden_fraction = 0.0;
    double ms = 0.0;  // its own scatter's time, wall clock to its end
  };
  std::optional<Lattice> lattice;
};

std::shared_ptr<ScatteredSunCache> make_scattered_sun_cache() {
  return std::make_shared<ScatteredSunCache>();
}

namespace {

// Cells added beyond each image edge so that waves displacing the edge vertices inward do not
// uncover the border (2 cells: 16 pixels at the paper's 8-pixel cells, more than a wave moves
// an edge vertex on screen except within a few metres of the camera).
constexpr int kGridMarginCells = 2;

// The one ring of vertices beyond the margin that make_projected_grid makes the skirt
// (ocean/projected_grid.hpp): left at rest by the waves, moved out of the image by about as far
// as the waves' displacement bound (displacement_bound, the skirt's reach) moves a point there on
// screen. The reference's ring is one more cell of margin, displaced like the rest: it draws
// only the surface itself, and its backstop shades what no triangle covers.
constexpr int kGridSkirtRing = 1;
// m: a skirt vertex's cell size is sent negated, and at least this (ocean.vert's own floor of
// the cell), so that a cell rounding to 0 in float cannot hide the flag as -0.
constexpr double kSkirtFlagCell = 1e-6;

// The grid's margin beyond each image edge, pixels, at least: the 2 cells of kGridMarginCells
// at the reference's default one-pixel cells, whatever its cells (OceanNodeOptions::
// reference_grid_cell).
constexpr double kGridMarginPixels = 2.0;

// The most cells per stratum side shaders/ocean/reference_sun.glsl's row buffer holds (the
// gathered sun), and the square root of the most per pixel's footprint of the scattered sun's
// lattice (shaders/ocean/reference_sun_scatter.comp; ocean/method.hpp): 2048^2 cells per pixel,
// 8,192 times the paper's sec. 7.2 count of 512, reached only where a footprint far away needs it.
constexpr int kReferenceMaxCells = 64;
constexpr int kScatterMaxCells = kReferenceMaxSunCells;
// The most subcells per side of a scattered cell that comes near the mirror slope
// (reference_sun_scatter.comp's REFERENCE_MAX_REFINE).
constexpr int kScatterMaxRefine = 8;
// Loop iterations one shader invocation of the reference's sun may run: half of llvmpipe's limit
// per invocation (Mesa's gallivm LP_MAX_TGSI_LOOP_ITERATIONS = 65535, shared by all of an
// invocation's loops, past which every loop silently stops: reference_sun_scatter.comp, "Why
// segments"). The scatter's segments and the gathered sun's cells per stratum keep within it.
constexpr double kShaderLoopBudget = 32768.0;
// Cells per invocation of the scatter's cells' pass on a renderer without llvmpipe's loop limit
// (OceanNodeOptions::reference_sun_segment): taking one row, an invocation evaluates the
// 2 (segment + 1) corners of its two rows of corners, 2.03 a cell at 64, where llvmpipe's
// budget allowed 4 cells (2.5 a cell) at 60 waves with 8 x 8 subcells refined in place and 2
// (3.0) at 120 (stop 41). 64 keeps a footprint's last segment's idle share small for the narrow
// footprints near the camera (a few dozen cells a row) while the lattice still has millions of
// invocations to spread.
constexpr int kScatterFreeSegment = 64;
// Rows of cells per invocation of the cells' pass (OceanNodeOptions::reference_sun_block_rows;
// on llvmpipe held to its budget, where 4 fit a column of unrefined cells up to about 2,900
// waves): a column of block_rows + 1 corners serves block_rows cells, so that with
// kScatterFreeSegment an invocation evaluates 5 x 65 corners for 4 x 64 cells, 1.27 a cell
// against 2.03 a row at a time (stop 41). More rows would save less (1.13 at 8) for twice the
// corners an invocation holds.
constexpr int kScatterFreeBlockRows = 4;
// The most rows of cells an invocation may take (reference_sun_scatter.comp's REFERENCE_ROWS,
// the length of its columns of corners).
constexpr int kScatterMaxBlockRows = kReferenceMaxSunBlockRows;
// The refined cells' queue (reference_sun_scatter.comp, stop 42): its places by default (the most,
// 64 MiB), the uints of its header before them, and its storage-buffer binding.
constexpr std::int64_t kScatterRefinedQueue = kReferenceMaxSunRefinedQueue;
constexpr int kScatterRefinedHeader = 8;
constexpr GLuint kScatterRefinedBinding = 10;
// On a renderer whose invocations may refine in place (no loop limit, or a segment small enough
// for its budget), a chunk of the cells' pass takes as many cells as the queue times this: the
// queue overflows only where more than 1 in 16 of a chunk's cells are refined (0.07 % are on
// wind10_100m_low_sun at 16 cells per wavelength, stop 42), and those are refined in place. At
// the default queue a GPU's chunk is then about 2^26 cells, 262,140 invocations of 4 x 64, about as
// many as the H200 holds at once (132 multiprocessors of 2,048). Elsewhere a chunk takes no more
// cells than the queue holds.
constexpr std::int64_t kScatterRefinedShare = 16;

// Whether the renderer ends long shader loops silently (llvmpipe's gallivm: "Why segments" in
// reference_sun_scatter.comp; softpipe shares Mesa's TGSI limits), so that the scatter's
// invocations must stay within kShaderLoopBudget.
bool renderer_limits_loops() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  return name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos;
}

// A digest of a wave set (FNV-1a over the bits of every wave's parameters and the shortest
// wavelength), for ScatteredSunCache's key: equal sets give equal digests; a collision between
// two seas of one validation case is the only way unequal ones would match.
std::uint64_t wave_digest(const WaveSet& set) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a's 64-bit offset basis
  const auto add = [&](double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) {
      hash ^= (bits >> (8 * byte)) & 0xffu;
      hash *= 1099511628211ull;  // FNV's 64-bit prime
    }
  };
  add(set.lambda_min);
  add(double(set.waves.size()));
  for (const Wave& wave : set.waves)
    for (const double value : {wave.wavenumber, wave.angular_frequency, wave.amplitude,
                               wave.direction.x, wave.direction.y, wave.phase})
      add(value);
  return hash;
}

// The scatter's loop iterations per invocation (an upper estimate of the shader's loops: each
// corner's wave loop and the features' loops, the segment's fixed work and first column of
// corners, and per column of cells its new corners and the loops over its rows, and per cell its
// neighbour test and its deposits, and when refined its subcells' corners and loops), for
// `waves` waves, `feature` iterations per point of the wakes' loops, `refine` subcells per side,
// `columns` cells of a row per invocation (its segment) and `rows` rows of cells (its block).
double scatter_iterations(int waves, int feature, int refine, int columns, int rows = 1) {
  const double corner = waves + 1.0 + feature;
  const double fixed = waves + (rows + 1.0) * (corner + 1.0) + 32.0;
  double cell = 32.0;
  if (refine > 1) {
    const double side = refine + 1.0;
    cell += (side * side - 4.0) * corner + 2.0 * side * side + 12.0 * refine * refine;
  }
  const double column = (rows + 1.0) * (corner + 2.0) + rows * (cell + 1.0);
  return fixed + columns * column;
}

// The solid angle (sr) of the sea at rest in the camera's image: each pixel's solid angle (its
// area on the image plane at unit distance over |ray|^3) times the share of its kSubsamples^2
// points whose rays meet the sea. For the check of the scattered sun's coverage
// (scattered_sun_coverage_fault), which needs it to a few per cent.
double sea_solid_angle(const GridCamera& camera) {
  constexpr int kSubsamples = 4;
  const double du = 2.0 / camera.width, dv = 2.0 / camera.height_px;
  // The image plane's area per subsample at unit distance along `forward`.
  const double area = (du * camera.tan_half_fov_y * camera.aspect) * (dv * camera.tan_half_fov_y) /
                      (kSubsamples * kSubsamples);
  double total = 0.0;
  for (int y = 0; y < camera.height_px * kSubsamples; ++y)
    for (int x = 0; x < camera.width * kSubsamples; ++x) {
      const glm::dvec2 image(-1.0 + (x + 0.5) * du / kSubsamples,
                             -1.0 + (y + 0.5) * dv / kSubsamples);
      glm::dvec3 point;
      if (!sea_point(camera, image, point)) continue;
      const double length = glm::length(grid_ray(camera, image));
      total += area / (length * length * length);
    }
  return total;
}

// The scattered sun's lattice: invocations per dispatch (65535 work groups of 64, GL's smallest
// guaranteed work-group count) and the most pixels added beyond each image edge.
constexpr std::uint64_t kScatterBatch = 65535ull * 64ull;
constexpr int kScatterMaxMargin = 256;
// How many times a lattice whose sums hold what no scatter writes (scattered_sun_sums.hpp) is
// scattered again before the render fails.
constexpr int kScatterRetries = 2;
// Its convergence measure's rows: not below this fraction of the brightest row's total (as the
// renderer's kNegligibleRow), and resolved by both lattices to at least this fraction of their
// sea (a row past the cap changes with the cap, not with the lattice).
constexpr double kScatterNegligibleRow = 1e-3;
constexpr double kScatterResolvedRow = 0.99;
// Nor below this mean sun factor per pixel (sr^-1; the lighting multiplies it by the sun's
// transmitted spectral irradiance, at most about 2 W m^-2 nm^-1): radiance under 2e-8
// W m^-2 sr^-1 nm^-1, a tenth of what the PNG shows as its first step at the default exposure
// (docs/validation.md, "A black reference"). A sun whose glints miss the view leaves only the
// sun disc's Gaussian tail (1e-25), whose rows' ratios between lattices are float noise (9.8e6
// in stop 24's wind10_8km_high_sun) and would have the lattice double to its most for nothing.
constexpr double kScatterBlackFactor = 1e-8;
// The storage-buffer binding of the scattered sun (reference_sun_scatter.comp and
// ocean_lighting.frag), clear of the waves' (1, 2) and the wakes' (3, 4), and the texture unit of
// the grid's depth it reads, clear of the sky provider's (4-11) and the calm areas' (12).
constexpr GLuint kReferenceSunBinding = 7;
// The scattered sun's footprints (reference_sun_scatter.comp, pass 1 to pass 2).
constexpr GLuint kScatterFootprintBinding = 8;
constexpr GLuint kScatterFootprintStartBinding = 9;
constexpr GLuint kGridDepthUnit = 14;

// The scatter's programs: the footprints' pass, the cells' and the refined cells'
// (reference_sun_scatter.comp).
using ScatterPrograms = std::array<GLuint, 3>;

// Per image row (top first), the cells along x and y of a scattered lattice's footprint with the
// most in that row (OceanNode::run_scatter).
struct ScatterRowCells {
  std::vector<double> x, y;
};

class OceanNode final : public gl::Node {
 public:
  explicit OceanNode(const OceanNodeOptions& options)
      : options_(options),
        provider_(options.provider),
        waves_(make_wave_set(options.settings)),
        wave_buffer_(gl::make_buffer()),
        tail_buffer_(gl::make_buffer()),
        vertex_array_(gl::make_vertex_array()) {
    // Wave parameters change only with the scene; phases change every frame (uploaded in draw).
    const std::size_t n = waves_.waves.size();
    glNamedBufferStorage(wave_buffer_.get(), static_cast<GLsizeiptr>(n * 8 * sizeof(float)),
                         nullptr, GL_DYNAMIC_STORAGE_BIT);
    std::vector<float> tails;
    for (const SlopeVariance& variance : waves_.tail_variance) {
      tails.push_back(static_cast<float>(variance.along));
      tails.push_back(static_cast<float>(variance.across));
    }
    glNamedBufferStorage(tail_buffer_.get(), static_cast<GLsizeiptr>(tails.size() * sizeof(float)),
                         tails.data(), 0);
    // The glossy sky maps and the SH irradiance exist only when the scene asks for them.
    if (options_.sky_shrm && (options_.sky || options_.sea))
      glossy_sky_ = std::make_unique<atmosphere::GlossySkyMaps>();
    if (options_.features && !options_.features->empty())
      local_features_ = std::make_unique<LocalFeatureBuffers>(*options_.features);
    // Eq. 24's table where the scene asks for it and a term reads it.
    effective_fresnel_ = EffectiveFresnelTexture::make_if_used(
        options_.settings, options_.sky || options_.sea, options_.sky);
  }

  std::string name() const override { return "ocean"; }
  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"ocean.waves." + std::to_string(waves_.waves.size()),
                                     "ocean.projected_grid", "ocean.backstop", "ocean.ross_brdf"};
    if (options_.method != OceanMethod::full)
      list.push_back("ocean.method." + std::string(method_name(options_.method)));
    if (parallax())
      list.push_back("ocean.parallax." + std::to_string(options_.settings.parallax_iterations));
    if (options_.sun_glint) list.push_back("ocean.sun_glint");
    if (options_.sky)
      list.push_back(options_.sky_shrm           ? "ocean.sky_reflection.shrm"
                     : options_.sky_nine_samples ? "ocean.sky_reflection.nine_samples"
                                                 : "ocean.sky_reflection.texture_grad");
    if (glossy_sky_)
      for (const std::string& item : glossy_sky_->built()) list.push_back(item);
    if (options_.sea) list.push_back("ocean.refracted_light");
    if (effective_fresnel_)
      for (const std::string& item : effective_fresnel_->built()) list.push_back(item);
    if (options_.air) list.push_back("ocean.aerial_perspective");
    if (local_features_)
      for (const std::string& item : local_features_->built()) list.push_back(item);
    return list;
  }

  void draw(const gl::FrameInputs& inputs, Context& context) override {
    const bool underwater = inputs.camera_height < 0.0;
    gl::Defines lighting_defines = provider_->defines();
    if (options_.sun_glint) lighting_defines["SUN_GLINT"] = "1";
    if (options_.sky) lighting_defines["SKY_TERM"] = "1";
    if (options_.sky && options_.sky_nine_samples) lighting_defines["SKY_NINE_SAMPLES"] = "1";
    if (options_.sky && options_.sky_shrm) lighting_defines["SKY_SHRM"] = "1";
    if (options_.sea) lighting_defines["SEA_TERM"] = "1";
    if (effective_fresnel_) effective_fresnel_->add_defines(lighting_defines);
    if (options_.method == OceanMethod::reference) lighting_defines["METHOD_REFERENCE"] = "1";
    if (reference_sun()) lighting_defines["REFERENCE_SUN"] = "1";
    if (reference_sun_scatter()) lighting_defines["REFERENCE_SUN_SCATTER"] = "1";
    if (options_.air) lighting_defines["AIR_TERM"] = "1";
    if (underwater) lighting_defines["UNDERWATER"] = "1";
    // Above kResolvedFadeStart the sky's reflection hands over to the view from space's array,
    // whatever the filter (shrm's glossy maps too, since stop 39; the view from space has no
    // shrm), so that the switch at 20 km shows no seam; not under water.
    const double array_weight = 1.0 - resolved_wave_scale(inputs.camera_height);
    const bool sky_array = options_.sky && !underwater && array_weight > 0.0;
    if (sky_array) {
      lighting_defines["SKY_MAP_ARRAY"] = "1";
      provider_->sky_map_array(context.shaders, &context.timer);
    }
    const GLuint lighting = context.shaders.program({.vertex = "engine/fullscreen.vert",
                                                     .fragment = "ocean/ocean_lighting.frag",
                                                     .defines = lighting_defines});
    // The sea's sky map, seen from the sea surface at the camera's nadir (rebuilt only when the
    // sun moves), and the per-frame constants of the lighting, in double from the provider.
    const glm::dvec3 sun = inputs.sun_direction;
    // (Not with shrm, whose glossy maps replace it: they are built below, for the same sky.)
    if (options_.sky && !options_.sky_shrm)
      provider_->sky_map(0.0, sun, context.shaders, &context.timer);
    glm::dvec3 sky_irradiance = provider_->sky_irradiance(0.0, sun);
    if (glossy_sky_) {
      // With shrm, the sky's irradiance of L_sea comes from the SH projection the glossy maps are
      // made of (E(up) with all its bands, not the order-2 truncation: see GlossySky), so the
      // reflected and the refracted sky share one sky; the sun stays analytic (sun_irradiance
      // below).
      const atmosphere::GlossySky& glossy =
          glossy_sky_->update(*provider_, 0.0, sun, &context.timer);
      sky_irradiance = glossy.horizontal_irradiance;
      const glm::dvec2 levels = glossy_sky_->level_mapping();
      glProgramUniform2f(lighting, glGetUniformLocation(lighting, "sky_shrm_levels"),
                         float(levels.x), float(levels.y));
    }
    const glm::dvec3 irradiance = provider_->sun_irradiance(0.0, sun) + sky_irradiance;
    const double sun_solid_angle =
        2.0 * glsl::PI * (1.0 - std::cos(provider_->sun_angular_radius()));
    // The sun's irradiance before the atmosphere (the shader applies the transmittance to each
    // point); a photograph's sun is what it is.
    const glm::dvec3 sun_disc_irradiance = provider_->sun_disc_radiance() * sun_solid_angle;
    const double radius = provider_->planet_radius();
    const double height = std::max(inputs.camera_height, 0.0);
    const glm::dvec3 reflectance(options_.settings.deep_reflectance_r,
                                 options_.settings.deep_reflectance_g,
                                 options_.settings.deep_reflectance_b);
    auto location = [](GLuint program, const char* name) {
      return glGetUniformLocation(program, name);
    };
    const glm::dvec2 downwind = chart_direction_in_frame(inputs.wave_axes, waves_.downwind);
    glProgramUniform2f(lighting, location(lighting, "downwind"), float(downwind.x),
                       float(downwind.y));
    glProgramUniform1f(lighting, location(lighting, "fresnel_r"),
                       float(options_.settings.fresnel_r));
    glProgramUniform3f(lighting, location(lighting, "deep_reflectance"), float(reflectance.x),
                       float(reflectance.y), float(reflectance.z));
    glProgramUniform3f(lighting, location(lighting, "horizontal_irradiance"), float(irradiance.x),
                       float(irradiance.y), float(irradiance.z));
    glProgramUniform3f(lighting, location(lighting, "sun_disc_irradiance"),
                       float(sun_disc_irradiance.x), float(sun_disc_irradiance.y),
                       float(sun_disc_irradiance.z));
    glProgramUniform1f(lighting, location(lighting, "atmosphere_radius"), float(radius));
    if (provider_->kind() == "environment_map") {
      // A photograph's sky irradiance, the same everywhere (ocean/sea_point_light.glsl).
      const glm::dvec3 sky = provider_->sky_irradiance(0.0, sun);
      glProgramUniform3f(lighting, location(lighting, "environment_sky_irradiance"), float(sky.x),
                         float(sky.y), float(sky.z));
    }
    glProgramUniform1f(lighting, location(lighting, "horizon_distance"),
                       float(std::sqrt(height * (2.0 * radius + height))));
    if (sky_array)
      glProgramUniform1f(lighting, location(lighting, "sky_array_weight"), float(array_weight));
    provider_->bind();
    if (glossy_sky_) glossy_sky_->bind();
    if (underwater) {
      glUseProgram(lighting);
      gl::draw_fullscreen_pass();
      context.timer.end_pass("ocean");
      resolved_waves_ = 0;
      return;
    }

    // Pass 1, positions + normals + variances (sec. 7.3's first part), into the G-buffer.
    const gl::Defines geometry_defines = geometry_pass_defines();
    const GLuint geometry = context.shaders.program({.vertex = "ocean/ocean.vert",
                                                     .fragment = "ocean/ocean_geometry.frag",
                                                     .defines = geometry_defines});
    upload_phases(inputs);
    glProgramUniform1i(geometry, location(geometry, "wave_count"),
                       static_cast<GLint>(waves_.waves.size()));
    glProgramUniform2f(geometry, location(geometry, "downwind"), float(downwind.x),
                       float(downwind.y));
    glProgramUniform1f(geometry, location(geometry, "n_min"), float(options_.settings.n_min));
    glProgramUniform1f(geometry, location(geometry, "n_max"), float(options_.settings.n_max));
    const float scale = float(resolved_wave_scale(inputs.camera_height));
    glProgramUniform1f(geometry, location(geometry, "resolved_wave_scale"), scale);
    set_reference_sun_uniforms(geometry);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, wave_buffer_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, tail_buffer_.get());
    if (local_features_) {
      local_features_->set_uniforms(geometry);
      local_features_->bind();
    }
    ensure_gbuffer(context.target);
    glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_.get());
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(gbuffer_.get(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(gbuffer_.get(), GL_COLOR, 1, zero);
    glUseProgram(geometry);
    const GridCamera camera = make_grid_camera(
        inputs.camera_right, inputs.camera_up, inputs.camera_forward, inputs.tan_half_fov_y,
        inputs.camera_height, inputs.width, inputs.height, SeaSurface{inputs.sea_curvature});
    const double footprint = smallest_footprint(camera);
    if (options_.method == OceanMethod::basic) {
      // Fig. 10's constant BRDF: the full method's unresolved variance where the pixels' footprint
      // is smallest (the foreground), for every pixel.
      const SlopeVariance constant =
          std::isfinite(footprint) && scale > 0.0f
              ? unresolved_slope_variance(waves_, std::max(footprint / scale, 1e-6),
                                          options_.settings.n_min, options_.settings.n_max)
              : waves_.tail_variance.front();
      constant_variance_ = {constant.along, constant.across};
      glProgramUniform2f(geometry, location(geometry, "constant_variance"),
                         float(constant_variance_.x), float(constant_variance_.y));
    }
    draw_grid(camera);
    draw_backstop(context.shaders, downwind, scale);
    context.timer.end_pass("ocean.geometry");

    // The reference's sun, once per lattice (not per sample).
    if (reference_sun_scatter()) {
      scatter_reference_sun(inputs, camera, downwind, context);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kReferenceSunBinding, reference_sun_buffer_.get());
    }

    // Pass 2, lighting (sec. 7.3's second part), into the HDR target where the grid drew.
    glBindFramebuffer(GL_FRAMEBUFFER, context.target.framebuffer());
    glUseProgram(lighting);
    glBindTextureUnit(0, normal_texture_.get());
    glBindTextureUnit(1, variance_texture_.get());
    if (effective_fresnel_) effective_fresnel_->bind();
    gl::draw_fullscreen_pass();
    context.timer.end_pass("ocean.lighting");
    resolved_waves_ = count_resolved(footprint, resolved_wave_scale(inputs.camera_height));
  }

  int resolved_waves() const override { return resolved_waves_; }

  std::vector<std::pair<std::string, double>> measurements() const override {
    if (!reference_sun_scatter() || scatter_ms_ < 0.0) return {};
    return {{"reference_sun.ms", scatter_ms_},
            {"reference_sun.lattice_row_change", lattice_row_change_},
            {"reference_sun.lattice_rows", double(lattice_rows_)},
            {"reference_sun.hidden_fraction", hidden_fraction_},
            {"reference_sun.margin_px", double(scatter_margin_)},
            {"reference_sun.refine", double(scatter_refine_)},
            {"reference_sun.segment", double(scatter_segment_)},
            {"reference_sun.block_rows", double(scatter_block_rows_)},
            {"reference_sun.refined_queue", double(refined_queue_)},
            {"reference_sun.scattered_cells", lattice_scattered_cells_},
            {"reference_sun.refined_cells", lattice_refined_cells_},
            {"reference_sun.refined_in_place", lattice_refined_in_place_},
            {"reference_sun.cells_per_wavelength", lattice_cells_per_wavelength_},
            {"reference_sun.cells", double(lattice_cap_)},
            {"reference_sun.doublings", double(lattice_doublings_)},
            {"reference_sun.float_atomics", float_atomics_ ? 1.0 : 0.0},
            {"reference_sun.rescatters", double(rescatters_)},
            {"reference_sun.reused", lattice_reused_ ? 1.0 : 0.0}};
  }

  std::vector<std::string> warnings() const override {
    if (!reference_sun_scatter()) return {};
    std::vector<std::string> warnings;
    if (rescatters_ > 0)
      warnings.push_back("the reference's sun: " + std::to_string(rescatters_) + " lattice" +
                         (rescatters_ == 1 ? "" : "s") +
                         " scattered again, whose sums held what no scatter writes (the last: " +
                         scatter_fault_ + ")");
    if (reuploads_ > 0)
      warnings.push_back("the reference's sun: the kept lattice sent again " +
                         std::to_string(reuploads_) + " time" + (reuploads_ == 1 ? "" : "s") +
                         ", since it read back otherwise than it was sent");
    return warnings;
  }

  std::vector<std::pair<std::string, std::vector<double>>> row_measurements() const override {
    if (!reference_sun_scatter() || scatter_ms_ < 0.0) return {};
    std::vector<std::pair<std::string, std::vector<double>>> rows;
    if (!lattice_row_changes_.empty())
      rows.emplace_back("reference_sun.lattice_row_changes", lattice_row_changes_);
    if (!lattice_row_cells_.x.empty()) {
      rows.emplace_back("reference_sun.row_cells_x", lattice_row_cells_.x);
      rows.emplace_back("reference_sun.row_cells_y", lattice_row_cells_.y);
    }
    return rows;
  }

  // "reference_sun.sums": the scattered sun's per-pixel sums as the lighting pass read them
  // (reference_sun_scatter.comp, Output): sum omega sun (sr), sum omega (sr), the part of sum
  // omega from footprints over the cell cap (sr), the solid angle hidden behind the grid's
  // crests (sr); rows top first like every Image.
  std::vector<std::pair<std::string, Image>> pixel_measurements() const override {
    if (!reference_sun_scatter() || scatter_ms_ < 0.0 || !has_scatter_key_) return {};
    const int width = scatter_key_.width, height = scatter_key_.height;
    std::vector<float> sums(4 * std::size_t(width) * std::size_t(height));
    if (sums.size() != reference_sun_floats_) return {};
    glGetNamedBufferSubData(reference_sun_buffer_.get(), 0,
                            static_cast<GLsizeiptr>(sums.size() * sizeof(float)), sums.data());
    Image image{width, height, std::vector<float>(sums.size())};
    for (int y = 0; y < height; ++y)  // the buffer's rows are window rows, from the bottom
      std::copy_n(&sums[4 * std::size_t(height - 1 - y) * width], 4 * std::size_t(width),
                  image.pixel(0, y));
    return {{"reference_sun.sums", std::move(image)}};
  }

 private:
  // Phases wrapped in double on the CPU (issue 3, point 7) at the nadir's place in the waves'
  // chart, and wave vectors turned from the chart's axes into the nadir frame's
  // (planet/nadir_frame.hpp): k_nadir = wave_axes^T k_chart. The shader sees only small arguments.
  void upload_phases(const gl::FrameInputs& inputs) {
    const std::vector<double> phases = wrapped_phases(waves_, inputs.time, inputs.wave_origin);
    std::vector<float> packed;
    packed.reserve(waves_.waves.size() * 8);
    for (std::size_t i = 0; i < waves_.waves.size(); ++i) {
      const Wave& w = waves_.waves[i];
      const glm::dvec2 direction = chart_direction_in_frame(inputs.wave_axes, w.direction);
      for (double value :
           {direction.x, direction.y, w.wavenumber, w.amplitude, phases[i], w.wavelength, 0.0, 0.0})
        packed.push_back(static_cast<float>(value));
    }
    glNamedBufferSubData(wave_buffer_.get(), 0,
                         static_cast<GLsizeiptr>(packed.size() * sizeof(float)), packed.data());
  }

  // The G-buffer between the two passes: the unit normal (+ coverage) and the unresolved slope
  // variances, float, with the HDR target's own depth buffer so the grid's triangles occlude
  // each other and later passes can test against the sea.
  void ensure_gbuffer(const gl::HdrTarget& target) {
    if (gbuffer_ && gbuffer_width_ == target.width() && gbuffer_height_ == target.height()) return;
    normal_texture_ = gl::make_texture(GL_TEXTURE_2D);
    variance_texture_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(normal_texture_.get(), 1, GL_RGBA32F, target.width(), target.height());
    // The reference's samples carry their weight, their sun and whether it was resolved
    // (ocean_geometry.frag).
    glTextureStorage2D(variance_texture_.get(), 1,
                       options_.method == OceanMethod::reference ? GL_RGBA32F : GL_RG32F,
                       target.width(), target.height());
    gbuffer_ = gl::make_framebuffer();
    glNamedFramebufferTexture(gbuffer_.get(), GL_COLOR_ATTACHMENT0, normal_texture_.get(), 0);
    glNamedFramebufferTexture(gbuffer_.get(), GL_COLOR_ATTACHMENT1, variance_texture_.get(), 0);
    glNamedFramebufferTexture(gbuffer_.get(), GL_DEPTH_ATTACHMENT, target.depth_texture(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(gbuffer_.get(), 2, buffers);
    if (glCheckNamedFramebufferStatus(gbuffer_.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw gl::GlError("ocean G-buffer: framebuffer incomplete");
    gbuffer_width_ = target.width();
    gbuffer_height_ = target.height();
  }

  // The projected grid (CPU, double) on the frame's sea at rest (the planet's quadric in the
  // nadir frame), uploaded as float rest positions relative to the camera's nadir (m, nadir ENU:
  // small numbers near the camera, where precision matters; z the quadric's sag, negative) and
  // drawn with depth.
  // The first pass's defines for the method (ocean.vert, ocean_geometry.frag).
  gl::Defines method_defines() const {
    switch (options_.method) {
      case OceanMethod::full:
        return {};
      case OceanMethod::basic:
        return {{"METHOD_BASIC", "1"}};
      case OceanMethod::normals:
        return {{"METHOD_NORMALS", "1"}};
      case OceanMethod::reference:
        // The scattered sun is not the first pass's (scatter_reference_sun).
        if (!reference_sun() || reference_sun_scatter()) return {{"METHOD_REFERENCE", "1"}};
        // With the sun alone its samples weigh by their strata's visible area
        // (ocean_geometry.frag).
        if (!options_.sky && !options_.sea)
          return {{"METHOD_REFERENCE", "1"}, {"REFERENCE_SUN", "1"}, {"REFERENCE_SUN_ONLY", "1"}};
        return {{"METHOD_REFERENCE", "1"}, {"REFERENCE_SUN", "1"}};
    }
    return {};
  }

  // Whether the reference draws the sun: gathered by the first pass
  // (shaders/ocean/reference_sun.glsl) or scattered from the sea's lattice
  // (shaders/ocean/reference_sun_scatter.comp).
  bool reference_sun() const {
    return options_.method == OceanMethod::reference && options_.sun_glint;
  }
  bool reference_sun_scatter() const { return reference_sun() && options_.reference_sun_scatter; }

  // The gathered sun's uniforms (shaders/ocean/reference_sun.glsl).
  void set_reference_sun_uniforms(GLuint program) const {
    if (!reference_sun() || reference_sun_scatter() || waves_.waves.empty()) return;
    glProgramUniform1f(program, glGetUniformLocation(program, "reference_spacing"),
                       float(waves_.lambda_min / std::clamp(options_.reference_cells_per_wavelength,
                                                            1.0, kReferenceMaxCellsPerWavelength)));
    // At most (cells + 1)^2 corners per fragment, each running the wave loop (and the wakes'),
    // besides the fragment's own normal: within the loop budget (31 x 31 cells at most for 30
    // waves, 22 x 22 for 60, 15 x 15 for 120; strata that need more are reported unresolved).
    const int feature = local_features_ ? local_features_->loop_iterations_per_point() : 0;
    const double corner = double(waves_.waves.size()) + 1.0 + feature;
    const int budget_cells =
        std::max(1, static_cast<int>(std::sqrt((kShaderLoopBudget - 2.0 * corner) / corner)) - 1);
    glProgramUniform1i(
        program, glGetUniformLocation(program, "reference_max_cells"),
        std::clamp(options_.reference_sun_cells, 1, std::min(kReferenceMaxCells, budget_cells)));
    glProgramUniform1f(program, glGetUniformLocation(program, "fresnel_r"),
                       float(options_.settings.fresnel_r));
  }

  // The first pass's defines: the method's, and the wakes' and calm areas' (issue 9).
  gl::Defines geometry_pass_defines() const {
    gl::Defines defines = method_defines();
    if (local_features_) local_features_->add_defines(defines);
    if (parallax())
      defines["PARALLAX_ITERATIONS"] = std::to_string(options_.settings.parallax_iterations);
    return defines;
  }

  // The parallax of the waves drawn in the normals alone (ocean/parallax.glsl): the scene's
  // fixed-point steps, for every method but the reference, whose mesh holds every wave.
  bool parallax() const {
    return options_.settings.parallax_iterations > 0 && options_.method != OceanMethod::reference;
  }

  // The grid's cell (pixels): the scene's, or the reference's (one vertex per pixel by default:
  // sec. 7.2's reference used about 5 cm triangles; its normals are exact per sample here, its
  // positions to a cell, so that a crest inside a pixel hides what it covers only for waves of
  // two cells and longer).
  double grid_cell() const {
    return options_.method == OceanMethod::reference ? options_.reference_grid_cell
                                                     : options_.settings.grid_cell;
  }

  // A bound of how far the waves move a point, m: each wave by its amplitude (calm areas only
  // scale them down), each wake by kelvin_wake_displacement_bound.
  double displacement_bound() const {
    double bound = 0.0;
    for (const Wave& wave : waves_.waves) bound += wave.amplitude;
    if (options_.features)
      for (const WakeInFrame& wake : options_.features->wakes)
        bound += kelvin_wake_displacement_bound(wake.params.speed);
    return bound;
  }

  // The grid's vertices (rest position and cell size, float; the cell size negated on the
  // outer ring, the skirt: kGridSkirtRing, at least kSkirtFlagCell so that no skirt vertex has
  // -0) and indices into the buffers.
  void upload_grid(const ProjectedGrid& grid) {
    std::vector<float> vertices;
    vertices.reserve(grid.rest.size() * 4);
    for (std::size_t k = 0; k < grid.rest.size(); ++k) {
      const bool skirt = !grid.skirt.empty() && grid.skirt[k] != 0;
      for (double value :
           {grid.rest[k].x, grid.rest[k].y, grid.rest[k].z,
            skirt ? -std::max(grid.cell_size[k], kSkirtFlagCell) : grid.cell_size[k]})
        vertices.push_back(static_cast<float>(value));
    }
    const GLsizeiptr vertex_bytes = static_cast<GLsizeiptr>(vertices.size() * sizeof(float));
    const GLsizeiptr index_bytes =
        static_cast<GLsizeiptr>(grid.indices.size() * sizeof(std::uint32_t));
    // Sizes follow the image, fixed for a renderer: allocate once, update each new grid.
    if (vertex_bytes != vertex_capacity_ || index_bytes != index_capacity_) {
      vertex_buffer_ = gl::make_buffer();
      index_buffer_ = gl::make_buffer();
      glNamedBufferStorage(vertex_buffer_.get(), vertex_bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
      glNamedBufferStorage(index_buffer_.get(), index_bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
      glVertexArrayVertexBuffer(vertex_array_.get(), 0, vertex_buffer_.get(), 0, 4 * sizeof(float));
      glVertexArrayElementBuffer(vertex_array_.get(), index_buffer_.get());
      glEnableVertexArrayAttrib(vertex_array_.get(), 0);
      glVertexArrayAttribFormat(vertex_array_.get(), 0, 4, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vertex_array_.get(), 0, 0);
      vertex_capacity_ = vertex_bytes;
      index_capacity_ = index_bytes;
    }
    glNamedBufferSubData(vertex_buffer_.get(), 0, vertex_bytes, vertices.data());
    glNamedBufferSubData(index_buffer_.get(), 0, index_bytes, grid.indices.data());
  }

  // The grid depends on the camera alone (and on the node's waves and wakes, fixed for it,
  // through the skirt's reach; not on the time, the sun or a reference sample's pixel offset,
  // which the shaders apply), so a frame that sees the sea as the last one did draws the
  // buffers it left: the reference's samples, repeated and timed frames. Making and uploading it
  // was the host's largest cost per frame, which every one of a reference's samples paid: for
  // its 1-pixel cells at 128x72, about 1.7 ms of the host thread's time per sample on
  // llvmpipe (perf, stop 29; docs/validation.md).
  void draw_grid(const GridCamera& camera) {
    const double cell = grid_cell();
    if (!(grid_key_ && grid_key_->camera == camera && grid_key_->cell_px == cell)) {
      grid_key_.reset();  // until the new grid is in the buffers
      const int margin =
          std::max(kGridMarginCells, static_cast<int>(std::ceil(kGridMarginPixels / cell))) +
          kGridSkirtRing;
      const double skirt_reach =
          options_.method == OceanMethod::reference ? 0.0 : displacement_bound();
      const ProjectedGrid grid = make_projected_grid(camera, cell, margin, skirt_reach);
      grid_index_count_ = grid.indices.size();
      if (grid.rows > 0) upload_grid(grid);
      grid_key_ = GridKey{camera, cell};
    }
    if (grid_index_count_ == 0) return;
    GLint previous_vertex_array = 0;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previous_vertex_array);
    glBindVertexArray(vertex_array_.get());
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(grid_index_count_), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(static_cast<GLuint>(previous_vertex_array));
  }

  // The pixels the grid left uncovered below the horizon get the sea at rest
  // (ocean_geometry.frag, BACKSTOP): a full-screen pass whose depth test passes only where the
  // depth is still the cleared far plane, so it costs only what the holes cover (and an early
  // discard on the sky).
  void draw_backstop(gl::ShaderLibrary& shaders, const glm::dvec2& downwind, float scale) {
    gl::Defines defines = geometry_pass_defines();
    defines["BACKSTOP"] = "1";
    const GLuint program = shaders.program({.vertex = "engine/fullscreen.vert",
                                            .fragment = "ocean/ocean_geometry.frag",
                                            .defines = defines});
    glProgramUniform1i(program, glGetUniformLocation(program, "wave_count"),
                       static_cast<GLint>(waves_.waves.size()));
    glProgramUniform2f(program, glGetUniformLocation(program, "downwind"), float(downwind.x),
                       float(downwind.y));
    glProgramUniform1f(program, glGetUniformLocation(program, "n_min"),
                       float(options_.settings.n_min));
    glProgramUniform1f(program, glGetUniformLocation(program, "n_max"),
                       float(options_.settings.n_max));
    glProgramUniform1f(program, glGetUniformLocation(program, "resolved_wave_scale"), scale);
    set_reference_sun_uniforms(program);
    glProgramUniform2f(program, glGetUniformLocation(program, "constant_variance"),
                       float(constant_variance_.x), float(constant_variance_.y));
    if (local_features_) local_features_->set_uniforms(program);
    glUseProgram(program);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
  }

  // The reference's sun (shaders/ocean/reference_sun_scatter.comp) into reference_sun_buffer_,
  // computed once per lattice: again only when the frame changes other than in its pixel offset
  // (the reference's samples share one). The same at half the cells (spacing and cap times
  // sqrt 2; unless options_.reference_measure_lattice is off) gives lattice_row_change_, the
  // issue's "doubling the samples" for the sun's normal samples: the largest change of an image
  // row's total sun factor between the two, relative to the finer's, over the rows the coarser
  // resolves (kScatterResolvedRow) that are brighter than kScatterNegligibleRow of the brightest
  // and than kScatterBlackFactor. (The lighting multiplies the factor by the smooth transmitted
  // irradiance, so the image's rows change alike.) While that change is not below
  // options_.reference_lattice_tolerance, the lattice doubles its cells, as the reference's
  // samples double, up to options_.reference_max_cells_per_wavelength.
  void scatter_reference_sun(const gl::FrameInputs& inputs, const GridCamera& camera,
                             const glm::dvec2& downwind, Context& context) {
    const std::size_t floats = 4 * std::size_t(inputs.width) * std::size_t(inputs.height);
    if (!reference_sun_buffer_ || reference_sun_floats_ != floats) {
      reference_sun_buffer_ = gl::make_buffer();
      coarse_sun_buffer_ = gl::make_buffer();
      const auto bytes = static_cast<GLsizeiptr>(floats * sizeof(float));
      // NaN rather than whatever the driver's new storage held: only a clear and a scatter that
      // reached the buffer replace it, so that scatter_checked sees one that did not.
      const std::vector<float> unwritten(floats, std::numeric_limits<float>::quiet_NaN());
      glNamedBufferStorage(reference_sun_buffer_.get(), bytes, unwritten.data(),
                           GL_DYNAMIC_STORAGE_BIT);
      glNamedBufferStorage(coarse_sun_buffer_.get(), bytes, unwritten.data(),
                           GL_DYNAMIC_STORAGE_BIT);
      reference_sun_floats_ = floats;
      has_scatter_key_ = false;
    }
    gl::FrameInputs key = inputs;
    key.pixel_offset = glm::dvec2(0.0);
    if (has_scatter_key_ && same_lattice(scatter_key_, key)) return;
    const auto start = std::chrono::steady_clock::now();
    rescatters_ = 0;
    reuploads_ = 0;
    scatter_fault_.clear();
    float_atomics_ = options_.reference_float_atomics && GLAD_GL_NV_shader_atomic_float;
    const double radius = provider_->planet_radius();
    // The first lattice asked for, and everything else the scatter reads.
    const double first_cells_per_wavelength =
        std::clamp(options_.reference_cells_per_wavelength, 1.0, kReferenceMaxCellsPerWavelength);
    const int first_cap = std::clamp(options_.reference_sun_cells, 1, kScatterMaxCells);
    ScatteredSunCache::Key cache_key{.view = inputs,
                                     .downwind = downwind,
                                     .fresnel_r = options_.settings.fresnel_r,
                                     .n_min = options_.settings.n_min,
                                     .n_max = options_.settings.n_max,
                                     .planet_radius = radius,
                                     .waves = wave_digest(waves_),
                                     .cells_per_wavelength = first_cells_per_wavelength,
                                     .cells = first_cap,
                                     .refine = std::clamp(options_.reference_sun_refine, 1,
                                                          kScatterMaxRefine),
                                     .float_atomics = float_atomics_};
    // Wakes and calm areas change the slopes through buffers the key does not hold.
    ScatteredSunCache* const cache =
        local_features_ ? nullptr : options_.reference_sun_cache.get();
    lattice_reused_ = cache && !options_.reference_measure_lattice && cache->lattice &&
                      cache->lattice->sums.size() == floats &&
                      same_cache_key(cache->lattice->key, cache_key);
    if (lattice_reused_) {
      const ScatteredSunCache::Lattice& kept = *cache->lattice;
      upload_checked(kept.sums);
      lattice_cells_per_wavelength_ = kept.key.cells_per_wavelength;
      lattice_cap_ = kept.key.cells;
      lattice_doublings_ = 0;
      lattice_row_change_ = 0.0;
      lattice_rows_ = 0;
      lattice_row_changes_.clear();
      lattice_row_cells_ = {};
      scatter_margin_ = kept.margin;
      scatter_refine_ = kept.refine;
      scatter_segment_ = kept.segment;
      scatter_block_rows_ = kept.block_rows;
      refined_queue_ = kept.refined_queue;
      lattice_scattered_cells_ = kept.cells;
      lattice_refined_cells_ = kept.refined_cells;
      lattice_refined_in_place_ = kept.refined_in_place;
      hidden_fraction_ = kept.hidden_fraction;
      // What the image cost (the scatter that made the sums), as if this render had scattered
      // them: a reference's time stays its image's, whichever render spent it.
      scatter_ms_ = kept.ms;
      context.timer.end_pass("ocean.reference_sun");
      scatter_key_ = key;
      has_scatter_key_ = true;
      return;
    }
    // The refinement, the block rows and the segments within the loop budget on a renderer
    // that ends long loops (llvmpipe): the most subcells per side whose single refined cell fits
    // it (1000 waves at 8 x 8 would not), held there on every renderer so that every renderer
    // draws the same lattice; then the rows and cells per invocation, which change only the
    // float rounding: on llvmpipe the rows asked for (kScatterFreeBlockRows by default) and the
    // most cells whose worst case fits, every cell unrefined where the queue takes the refined
    // ones (else every cell refined in place); elsewhere kScatterFreeBlockRows x
    // kScatterFreeSegment (or as asked).
    const int waves = static_cast<int>(waves_.waves.size());
    const int feature = local_features_ ? local_features_->loop_iterations_per_point() : 0;
    scatter_refine_ = std::clamp(options_.reference_sun_refine, 1, kScatterMaxRefine);
    while (scatter_refine_ > 1 &&
           scatter_iterations(waves, feature, scatter_refine_, 1) > kShaderLoopBudget)
      --scatter_refine_;
    refined_queue_ =
        scatter_refine_ == 1 ? 0
        : options_.reference_sun_refined_queue < 0
            ? kScatterRefinedQueue
            : std::min(options_.reference_sun_refined_queue, kReferenceMaxSunRefinedQueue);
    const int cell_refine = refined_queue_ > 0 ? 1 : scatter_refine_;
    const bool limited = renderer_limits_loops();
    scatter_block_rows_ =
        std::clamp(options_.reference_sun_block_rows > 0 ? options_.reference_sun_block_rows
                                                         : kScatterFreeBlockRows,
                   1, kScatterMaxBlockRows);
    while (limited && scatter_block_rows_ > 1 &&
           scatter_iterations(waves, feature, cell_refine, 1, scatter_block_rows_) >
               kShaderLoopBudget)
      --scatter_block_rows_;
    int most_segment = kScatterMaxCells;
    if (limited) {
      most_segment = 1;
      while (most_segment < kScatterMaxCells &&
             scatter_iterations(waves, feature, cell_refine, 2 * most_segment,
                                scatter_block_rows_) <= kShaderLoopBudget)
        most_segment *= 2;
    }
    scatter_segment_ = options_.reference_sun_segment > 0
                           ? std::min(options_.reference_sun_segment, most_segment)
                           : (limited ? most_segment : kScatterFreeSegment);
    // A chunk of the cells' pass: where an invocation may not refine in place (llvmpipe, its
    // segment sized for unrefined cells), no more cells than the queue holds, at least one
    // invocation's (its cut made smaller where the queue is smaller than that); elsewhere
    // kScatterRefinedShare times that.
    scatter_chunk_ = 0;
    if (refined_queue_ > 0) {
      const bool in_place_fits =
          !limited || scatter_iterations(waves, feature, scatter_refine_, scatter_segment_,
                                         scatter_block_rows_) <= kShaderLoopBudget;
      while (!in_place_fits &&
             std::int64_t(scatter_segment_) * scatter_block_rows_ > refined_queue_) {
        if (scatter_segment_ > 1)
          scatter_segment_ = std::max(1, scatter_segment_ / 2);
        else
          --scatter_block_rows_;
      }
      const std::int64_t cells = std::int64_t(scatter_segment_) * scatter_block_rows_;
      scatter_chunk_ = static_cast<std::uint64_t>(std::max<std::int64_t>(
          1, refined_queue_ * (in_place_fits ? kScatterRefinedShare : 1) / cells));
    }
    gl::Defines defines;
    if (local_features_) local_features_->add_defines(defines);
    if (float_atomics_) defines["REFERENCE_FLOAT_ATOMICS"] = "1";
    gl::Defines footprint_defines = defines;
    footprint_defines["REFERENCE_FOOTPRINT_PASS"] = "1";
    defines["REFERENCE_ROWS"] = std::to_string(scatter_block_rows_);
    gl::Defines refine_defines = defines;
    refine_defines["REFERENCE_REFINE_PASS"] = "1";
    // The same source three times: the footprints' pass, the cells' and the refined cells'; each
    // takes every uniform.
    const ScatterPrograms programs = {
        context.shaders.program(
            {.compute = "ocean/reference_sun_scatter.comp", .defines = footprint_defines}),
        context.shaders.program(
            {.compute = "ocean/reference_sun_scatter.comp", .defines = defines}),
        context.shaders.program(
            {.compute = "ocean/reference_sun_scatter.comp", .defines = refine_defines})};
    const auto uniform = [&](const char* name, auto set) {
      for (const GLuint program : programs) set(program, glGetUniformLocation(program, name));
    };
    const auto uniform_f = [&](const char* name, double value) {
      uniform(name,
              [&](GLuint program, GLint at) { glProgramUniform1f(program, at, float(value)); });
    };
    const auto uniform_i = [&](const char* name, int value) {
      uniform(name, [&](GLuint program, GLint at) { glProgramUniform1i(program, at, value); });
    };
    uniform_i("wave_count", static_cast<int>(waves_.waves.size()));
    uniform("downwind", [&](GLuint program, GLint at) {
      glProgramUniform2f(program, at, float(downwind.x), float(downwind.y));
    });
    uniform_f("fresnel_r", options_.settings.fresnel_r);
    uniform_f("n_min", options_.settings.n_min);
    uniform_f("n_max", options_.settings.n_max);
    const double height = std::max(inputs.camera_height, 0.0);
    uniform_f("horizon_distance", std::sqrt(height * (2.0 * radius + height)));
    // Every wave's displacement together is at most the sum of their amplitudes (each moves a
    // point by exactly h_i; calm areas only scale them down). The wakes' are not included.
    double displacement = 0.0;
    for (const Wave& wave : waves_.waves) displacement += wave.amplitude;
    uniform_f("max_displacement", displacement);
    // A bound on the slope field's second derivatives (1/m^2) for the refinement's test: a
    // sine's slope h k sin(k x) has second derivatives up to h k^3; a trochoid's slope is
    // steeper where its crest sharpens, by up to 1 / (1 - k h)^3 (its horizontal compression
    // at the crest, to the third power: slope and its two derivatives). Calm areas only lower it.
    double curvature = 0.0;
    for (const Wave& wave : waves_.waves) {
      const double steepness = std::min(wave.wavenumber * wave.amplitude, 0.9);
      curvature += wave.amplitude * std::pow(wave.wavenumber, 3) / std::pow(1.0 - steepness, 3);
    }
    uniform_f("slope_curvature", curvature);
    uniform_i("reference_refine", scatter_refine_);
    uniform_i("reference_segment", scatter_segment_);
    uniform("refined_capacity", [&](GLuint program, GLint at) {
      glProgramUniform1ui(program, at, static_cast<GLuint>(refined_queue_));
    });
    // The refined cells' queue: its header, and its places when it has any.
    const std::size_t queue_bytes =
        (kScatterRefinedHeader + 4 * std::size_t(std::max<std::int64_t>(refined_queue_, 1))) *
        sizeof(GLuint);
    if (!refined_buffer_ || refined_buffer_bytes_ != queue_bytes) {
      refined_buffer_ = gl::make_buffer();
      glNamedBufferStorage(refined_buffer_.get(), static_cast<GLsizeiptr>(queue_bytes), nullptr,
                           GL_DYNAMIC_STORAGE_BIT);
      refined_buffer_bytes_ = queue_bytes;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kScatterRefinedBinding, refined_buffer_.get());
    // The margin: how far (pixels) the nearest sea in the image can move on screen, as the
    // shader's per-pixel test (its forward distance over the image's 5 x 5 points seeing the sea).
    double along = INFINITY;
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) {
        glm::dvec3 p;
        if (sea_point(camera, glm::dvec2(-1.0 + 0.5 * i, -1.0 + 0.5 * j), p))
          along = std::min(along, glm::dot(p - glm::dvec3(0.0, 0.0, inputs.camera_height),
                                           inputs.camera_forward));
      }
    const double reach = std::isfinite(along) ? 2.0 * displacement / std::max(along, 1e-3) * 0.5 *
                                                    inputs.height / inputs.tan_half_fov_y
                                              : 0.0;
    scatter_margin_ = static_cast<int>(std::min(std::ceil(reach) + 1.0, double(kScatterMaxMargin)));
    uniform_i("margin", scatter_margin_);
    if (local_features_) {
      for (const GLuint program : programs) local_features_->set_uniforms(program);
      local_features_->bind();
    }
    scatter_width_ = inputs.width;
    scatter_height_ = inputs.height;
    const std::size_t footprints = std::size_t(inputs.width + 2 * scatter_margin_) *
                                   std::size_t(inputs.height + 2 * scatter_margin_);
    if (!footprint_buffer_ || footprint_count_ != footprints) {
      footprint_buffer_ = gl::make_buffer();
      glNamedBufferStorage(footprint_buffer_.get(),
                           static_cast<GLsizeiptr>(footprints * 12 * sizeof(float)), nullptr, 0);
      footprint_count_ = footprints;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kScatterFootprintBinding, footprint_buffer_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, wave_buffer_.get());
    // The grid's depth, just drawn (the compute pass reads it; nothing renders meanwhile). It is
    // read as a texture while no framebuffer has it attached: the G-buffer that drew it is
    // unbound first (the lighting pass binds the target's next). GL allows a compute shader to
    // read a bound framebuffer's attachment, but a driver that keeps the attachment in its
    // compressed render-target form while it is bound may hand the shader something else; on
    // the H200 the 120-wave reference's term `all` lost every cell of its sun, as if the grid
    // hid them all (stop 26, not reproduced on llvmpipe; not yet rerun on a GPU with this).
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(kGridDepthUnit, context.target.depth_texture());
    // The lattice doubles its cells (spacing / sqrt 2) until no row moves by the tolerance
    // against the lattice before it, or the most cells per wavelength is reached. The cap grows
    // with the cells (times sqrt 2; cap^2 cells per footprint, times 2), so that every lattice
    // resolves the same footprints, hence the same rows, up to the most; from there it is held,
    // and each doubling gives up the footprints its finer cells no longer fit in the cap
    // (measure_lattice compares the rows both lattices resolve).
    double cells_per_wavelength = first_cells_per_wavelength;
    const double most_cells_per_wavelength =
        std::clamp(options_.reference_max_cells_per_wavelength, cells_per_wavelength,
                   kReferenceMaxCellsPerWavelength);
    int cap = first_cap;
    const int most_cap = std::clamp(options_.reference_max_sun_cells, first_cap, kScatterMaxCells);
    // What the check of each lattice holds its cells' solid angle to (scatter_checked).
    scatter_sea_solid_angle_ = sea_solid_angle(camera);
    // The finer lattice's own time (ms, to its end on the GPU), kept with it in the cache for a
    // render that draws it from there: the time its image cost.
    double finer_ms =
        run_scatter_timed(programs, reference_sun_buffer_.get(),
                          waves_.lambda_min / cells_per_wavelength, cap, cache != nullptr);
    const bool measure = options_.reference_measure_lattice;
    if (measure)
      scatter_checked(programs, coarse_sun_buffer_.get(),
                      waves_.lambda_min / cells_per_wavelength * std::sqrt(2.0),
                      std::max(1, static_cast<int>(std::lround(cap / std::sqrt(2.0)))), nullptr,
                      false, coarse_sums_);
    lattice_doublings_ = 0;
    for (;;) {
      measure_lattice(inputs, measure);  // from the sums scatter_checked read (after its barrier)
      // Both from the first lattice: rounding each doubling's cap would drift (32 to 129 in
      // four), and sqrt 2 times sqrt 2 is 2 + 4e-16, so four doublings of 16 by sqrt 2 gave
      // 64.00000000000001, past the 64 that ReferenceSampling allows when validate redrew that
      // lattice for its later terms (the first GPU run, stop 26). pow(2, whole) is exact.
      const double growth = std::pow(2.0, 0.5 * (lattice_doublings_ + 1));
      const int finer_cap =
          static_cast<int>(std::min<long>(std::lround(first_cap * growth), most_cap));
      // (1 + 1e-9: a most given as a printed 16 sqrt 2, 22.63, is reached.)
      const double finer_unclamped = first_cells_per_wavelength * growth;
      if (!measure || lattice_row_change_ < options_.reference_lattice_tolerance ||
          finer_unclamped > most_cells_per_wavelength * (1.0 + 1e-9))
        break;
      const double finer = std::min(finer_unclamped, most_cells_per_wavelength);
      // The finer lattice becomes the coarser one it is measured against.
      std::swap(reference_sun_buffer_, coarse_sun_buffer_);
      std::swap(finer_sums_, coarse_sums_);
      cells_per_wavelength = finer;
      cap = finer_cap;
      finer_ms = run_scatter_timed(programs, reference_sun_buffer_.get(),
                                   waves_.lambda_min / cells_per_wavelength, cap, cache != nullptr);
      ++lattice_doublings_;
    }
    lattice_cells_per_wavelength_ = cells_per_wavelength;
    lattice_cap_ = cap;
    if (cache) {
      // The lattice it ended with, under the key of a render that asks for it directly.
      cache_key.cells_per_wavelength = cells_per_wavelength;
      cache_key.cells = cap;
      ScatteredSunCache::Lattice kept{.key = cache_key,
                                      .sums = finer_sums_,
                                      .margin = scatter_margin_,
                                      .refine = scatter_refine_,
                                      .segment = scatter_segment_,
                                      .block_rows = scatter_block_rows_,
                                      .refined_queue = refined_queue_,
                                      .cells = lattice_scattered_cells_,
                                      .refined_cells = lattice_refined_cells_,
                                      .refined_in_place = lattice_refined_in_place_,
                                      .hidden_fraction = hidden_fraction_,
                                      .ms = finer_ms};
      cache->lattice = std::move(kept);
    }
    scatter_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    context.timer.end_pass("ocean.reference_sun");
    scatter_key_ = key;
    has_scatter_key_ = true;
  }

  // The lattice's convergence (lattice_row_change_, its rows and per-row changes) from the
  // finer lattice's sums (finer_sums_, of reference_sun_buffer_) and, when measured, the
  // coarser's (coarse_sums_); hidden_fraction_ from the finer.
  void measure_lattice(const gl::FrameInputs& inputs, bool measure) {
    const SunRows fine = sun_rows(finer_sums_, inputs);
    hidden_fraction_ = fine.hidden / std::max(fine.hidden + fine.omega, 1e-300);
    lattice_row_change_ = 0.0;
    lattice_rows_ = 0;
    lattice_row_changes_.clear();
    if (!measure) return;
    const SunRows coarse = sun_rows(coarse_sums_, inputs);
    const double brightest =
        fine.total.empty() ? 0.0 : *std::max_element(fine.total.begin(), fine.total.end());
    const double floor =
        std::max(kScatterNegligibleRow * brightest, kScatterBlackFactor * inputs.width);
    const std::size_t rows = fine.total.size();
    lattice_row_changes_.assign(rows, std::numeric_limits<double>::quiet_NaN());
    // Rows both lattices resolve: the same while the cap grows with the cells; once it is held,
    // the finer lattice gives up the farthest of the coarser's rows.
    for (std::size_t y = 0; y < rows; ++y)  // window rows, from the bottom
      if (coarse.resolved[y] >= kScatterResolvedRow && fine.resolved[y] >= kScatterResolvedRow &&
          fine.total[y] > floor) {
        const double change = std::abs(fine.total[y] - coarse.total[y]) / fine.total[y];
        lattice_row_changes_[rows - 1 - y] = change;  // image rows, from the top
        lattice_row_change_ = std::max(lattice_row_change_, change);
        ++lattice_rows_;
      }
  }

  // scatter_checked of the finer lattice (its footprints' cells per row into
  // lattice_row_cells_); with `timed`, its wall-clock time (ms), else 0 (a lattice no cache
  // keeps needs no time of its own).
  double run_scatter_timed(const ScatterPrograms& programs, GLuint buffer, double spacing, int cap,
                           bool timed) {
    const double ms =
        scatter_checked(programs, buffer, spacing, cap, &lattice_row_cells_, timed, finer_sums_);
    // Its cells, and its refined cells and those refined in place, which the queue's header
    // counts (the barrier before its sums were read back covers the header too).
    std::array<GLuint, kScatterRefinedHeader> header{};
    glGetNamedBufferSubData(refined_buffer_.get(), 0, sizeof header, header.data());
    lattice_scattered_cells_ = scattered_cells_;
    lattice_refined_cells_ = header[4];
    lattice_refined_in_place_ = header[5];
    return ms;
  }

  // A kept lattice's sums (ScatteredSunCache) into reference_sun_buffer_, read back and compared
  // with what was sent: the cache's copy was checked when it was scattered, and the upload is
  // the one step between it and the lighting pass. One that differs is sent again, up to
  // kScatterRetries times (reuploads_, warnings()), then the render fails (gl::GlError).
  void upload_checked(const std::vector<float>& sums) {
    const auto bytes = static_cast<GLsizeiptr>(sums.size() * sizeof(float));
    std::vector<float> back(sums.size());
    for (int attempt = 0;; ++attempt) {
      glNamedBufferSubData(reference_sun_buffer_.get(), 0, bytes, sums.data());
      inject_test_fault(reference_sun_buffer_.get());
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(reference_sun_buffer_.get(), 0, bytes, back.data());
      if (std::memcmp(back.data(), sums.data(), static_cast<std::size_t>(bytes)) == 0) return;
      ++reuploads_;
      if (attempt >= kScatterRetries)
        throw gl::GlError("the reference's scattered sun: the kept lattice sent " +
                          std::to_string(attempt + 1) +
                          " times reads back otherwise than it was sent");
    }
  }

  // For tests (OceanNodeOptions::reference_sun_test_faults): while faults are left to inject,
  // `buffer`'s sums overwritten as the H200's fault left them (scattered_sun_sums.hpp), with
  // source text, then zeros (a scatter lost after its clear), in turn.
  void inject_test_fault(GLuint buffer) {
    if (injected_faults_ >= options_.reference_sun_test_faults) return;
    const char text[] = "Tail(IN(Number) tion w (tangent ";
    std::vector<float> sums(reference_sun_floats_, 0.0f);
    if (injected_faults_ % 2 == 0)
      for (std::size_t i = 0; i < sums.size(); ++i)
        std::memcpy(&sums[i], text + 4 * (i % 8), sizeof(float));
    ++injected_faults_;
    glNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(sums.size() * sizeof(float)),
                         sums.data());
  }

  // run_scatter, then its sums read back and checked (scattered_sun_sums.hpp): a lattice whose
  // buffer holds what no scatter writes is scattered again, up to kScatterRetries times
  // (rescatters_ counts them, scatter_fault_ says what the last held), and the render fails
  // (gl::GlError) if the last is no better. The sums that passed go to `sums`, the one copy the
  // CPU uses (the lattice's convergence, the cache): a second read back would be unchecked. With
  // `timed`, the wall-clock time (ms) of the scatter that passed, waited for; else 0.
  double scatter_checked(const ScatterPrograms& programs, GLuint buffer, double spacing, int cap,
                         ScatterRowCells* row_cells, bool timed, std::vector<float>& sums) {
    for (int attempt = 0;; ++attempt) {
      const auto start = std::chrono::steady_clock::now();
      run_scatter(programs, buffer, spacing, cap, row_cells);
      if (timed) glFinish();
      const double ms =
          timed
              ? std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count()
              : 0.0;
      sums.assign(reference_sun_floats_, 0.0f);
      inject_test_fault(buffer);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(sums.size() * sizeof(float)),
                              sums.data());
      std::string fault = scattered_sun_sums_fault(sums, scatter_width_, scatter_height_);
      if (fault.empty()) fault = scattered_sun_coverage_fault(sums, scatter_sea_solid_angle_);
      if (fault.empty()) return ms;
      // A context the GPU reset (where it is told: gl::context_reset) cannot scatter again.
      const std::string reset = gl::context_reset();
      if (!reset.empty())
        throw gl::GlError("the reference's scattered sun: the GPU reset the OpenGL context (" +
                          reset + ") and the lattice holds what no scatter writes: " + fault);
      ++rescatters_;
      scatter_fault_ = fault;
      if (attempt >= kScatterRetries) {
        const GLenum error = glGetError();
        char codes[96];
        std::snprintf(codes, sizeof codes, " (%s, GL error 0x%04X)",
                      gl::context_told_of_resets() ? "no GPU reset reported"
                                                   : "the context is not told of GPU resets",
                      error);
        throw gl::GlError("the reference's scattered sun: the lattice scattered " +
                          std::to_string(attempt + 1) +
                          " times holds what no scatter writes: " + fault + codes);
      }
    }
  }

  // One lattice (spacing m, at most cap^2 cells per pixel's footprint) into buffer, cleared
  // first: the footprints' pass (programs[0]), then the cells' (programs[1]) in chunks, each
  // followed, where there is a queue, by the refined cells' pass (programs[2]) over the cells the
  // chunk queued; with row_cells, the cells along x and y of each image row's footprint with the
  // most into it.
  void run_scatter(const ScatterPrograms& programs, GLuint buffer, double spacing, int cap,
                   ScatterRowCells* row_cells = nullptr) {
    const float zero = 0.0f;
    glClearNamedBufferData(buffer, GL_R32F, GL_RED, GL_FLOAT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kReferenceSunBinding, buffer);
    for (const GLuint program : programs) {
      glProgramUniform1f(program, glGetUniformLocation(program, "reference_spacing"),
                         float(spacing));
      glProgramUniform1i(program, glGetUniformLocation(program, "reference_max_cells"), cap);
    }
    // The refined cells' queue: empty, its totals 0 (header: reference_sun_scatter.comp).
    const std::array<GLuint, kScatterRefinedHeader> empty_queue = {0, 1, 1, 0, 0, 0, 0, 0};
    glNamedBufferSubData(refined_buffer_.get(), 0, sizeof empty_queue, empty_queue.data());
    // `invocations` invocations of `program` from 0, in dispatches of at most `chunk` (the
    // shader ignores the last work group's invocations from invocation_end on); with `refine`,
    // each followed by the refined cells' pass over what it queued.
    const auto dispatch = [&](GLuint program, std::uint64_t invocations, std::uint64_t chunk,
                              bool refine) {
      const GLint first = glGetUniformLocation(program, "first_invocation");
      const GLint end = glGetUniformLocation(program, "invocation_end");
      for (std::uint64_t start = 0; start < invocations; start += chunk) {
        const std::uint64_t count = std::min(chunk, invocations - start);
        if (refine) {
          // The header reset for this chunk: the barrier after the last chunk's refined cells'
          // pass (GL_BUFFER_UPDATE_BARRIER_BIT) orders it after the cells' pass's atomic writes
          // to the header, and GL's command order after the refined pass's reads of it (barriers
          // order shaders' writes, not their reads).
          glNamedBufferSubData(refined_buffer_.get(), 0, 4 * sizeof(GLuint), empty_queue.data());
        }
        glUseProgram(program);
        glProgramUniform1ui(program, first, static_cast<GLuint>(start));
        glProgramUniform1ui(program, end, static_cast<GLuint>(start + count));
        glDispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
        if (refine) {
          // The queued cells, one invocation each, as many work groups as the cells' pass counted.
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
          glUseProgram(programs[2]);
          glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, refined_buffer_.get());
          glDispatchComputeIndirect(0);
          glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
          glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        }
        // Handed to the GPU dispatch by dispatch, rather than as one submission of many seconds
        // (a lattice at 128 per wavelength takes 17 s on the H200; stop 40's lost sums came from
        // scatters of 8 s and more, cause unknown).
        glFlush();
      }
    };
    // Footprints' pass: one invocation per footprint.
    dispatch(programs[0], footprint_count_, kScatterBatch, false);
    // Cells' pass: ceil(ky / block rows) x ceil(kx / segment) invocations per footprint,
    // numbered without gaps (reference_sun_scatter.comp, pass 2), in batches of whole
    // footprints whose invocations a 32-bit index counts (the whole lattice's passed 2^32 on the 20
    // m/s sea at 4 m with 8 x 8 subcells: 6.1e9 slots as they were laid out until stop 33). A
    // footprint's cells are at most cap^2 <= 2048^2, so one always fits.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> footprints(12 * footprint_count_);
    glGetNamedBufferSubData(footprint_buffer_.get(), 0,
                            static_cast<GLsizeiptr>(footprints.size() * sizeof(float)),
                            footprints.data());
    const int columns = scatter_width_ + 2 * scatter_margin_;
    if (row_cells) {
      row_cells->x.assign(scatter_height_, 0.0);
      row_cells->y.assign(scatter_height_, 0.0);
    }
    std::vector<GLuint> starts(footprint_count_);
    struct Batch {
      std::uint64_t first = 0, end = 0, invocations = 0;
    };
    std::vector<Batch> batches{Batch{}};
    scattered_cells_ = 0.0;
    const std::uint64_t segment = static_cast<std::uint64_t>(scatter_segment_);
    const std::uint64_t batch_invocations =
        std::clamp<std::uint64_t>(options_.reference_sun_batch, 1, kReferenceMaxSunBatch);
    for (std::size_t f = 0; f < footprint_count_; ++f) {
      const auto kx = static_cast<std::uint64_t>(std::max(footprints[12 * f + 8], 0.0f));
      const auto ky = static_cast<std::uint64_t>(std::max(footprints[12 * f + 9], 0.0f));
      const std::uint64_t block_rows = static_cast<std::uint64_t>(scatter_block_rows_);
      const std::uint64_t invocations =
          ((ky + block_rows - 1) / block_rows) * ((kx + segment - 1) / segment);
      scattered_cells_ += double(kx) * double(ky);
      const int x = static_cast<int>(f % columns) - scatter_margin_;
      const int y = static_cast<int>(f / columns) - scatter_margin_;  // window row, from the bottom
      if (row_cells && x >= 0 && x < scatter_width_ && y >= 0 && y < scatter_height_) {
        const int row = scatter_height_ - 1 - y;
        if (double(kx) * double(ky) > row_cells->x[row] * row_cells->y[row]) {
          row_cells->x[row] = double(kx);
          row_cells->y[row] = double(ky);
        }
      }
      // A new batch where this footprint would take the batch past its most (a footprint with
      // more than the most, possible only below kReferenceMaxSunBatch, is a batch alone).
      if (batches.back().invocations > 0 &&
          batches.back().invocations + invocations > batch_invocations)
        batches.push_back(Batch{.first = f, .end = f, .invocations = 0});
      starts[f] = static_cast<GLuint>(batches.back().invocations);
      batches.back().invocations += invocations;
      batches.back().end = f + 1;
    }
    if (!footprint_start_buffer_ || footprint_start_count_ != footprint_count_) {
      footprint_start_buffer_ = gl::make_buffer();
      glNamedBufferStorage(footprint_start_buffer_.get(),
                           static_cast<GLsizeiptr>(footprint_count_ * sizeof(GLuint)), nullptr,
                           GL_DYNAMIC_STORAGE_BIT);
      footprint_start_count_ = footprint_count_;
    }
    glNamedBufferSubData(footprint_start_buffer_.get(), 0,
                         static_cast<GLsizeiptr>(starts.size() * sizeof(GLuint)), starts.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kScatterFootprintStartBinding,
                     footprint_start_buffer_.get());
    const GLint first_footprint = glGetUniformLocation(programs[1], "first_footprint");
    const GLint footprint_end = glGetUniformLocation(programs[1], "footprint_end");
    for (const Batch& batch : batches) {
      if (batch.invocations == 0) continue;
      glProgramUniform1ui(programs[1], first_footprint, static_cast<GLuint>(batch.first));
      glProgramUniform1ui(programs[1], footprint_end, static_cast<GLuint>(batch.end));
      dispatch(programs[1], batch.invocations,
               scatter_chunk_ > 0 ? std::min(scatter_chunk_, kScatterBatch) : kScatterBatch,
               refined_queue_ > 0);
    }
  }

  // Each row's total of the per-pixel sun factor sum(omega sun) / sum(omega) in `sums` (a
  // lattice's, as scatter_checked read them), and the fraction of the row's sum(omega) from
  // footprints within the cell cap; window rows, from the bottom (the scatter's pixel rows).
  struct SunRows {
    std::vector<double> total, resolved;
    double omega = 0.0, hidden = 0.0;  // the image's visible and hidden solid angles (sr)
  };
  static SunRows sun_rows(const std::vector<float>& sums, const gl::FrameInputs& inputs) {
    if (sums.size() != 4 * std::size_t(inputs.width) * std::size_t(inputs.height))
      throw std::logic_error("sun_rows: the sums are not the image's");
    SunRows rows{std::vector<double>(inputs.height, 0.0), std::vector<double>(inputs.height, 0.0)};
    for (int y = 0; y < inputs.height; ++y) {
      double omega = 0.0, unresolved = 0.0;
      for (int x = 0; x < inputs.width; ++x) {
        const float* p = &sums[4 * (std::size_t(y) * inputs.width + x)];
        if (!(p[1] > 0.0f) || !std::isfinite(p[0] / p[1])) continue;
        rows.total[y] += double(p[0]) / double(p[1]);
        omega += p[1];
        unresolved += p[2];
        rows.hidden += p[3];
        rows.omega += p[1];
      }
      rows.resolved[y] = omega > 0.0 ? 1.0 - unresolved / omega : 0.0;
    }
    return rows;
  }

  // Whether a kept lattice (ScatteredSunCache) is the one a render asks for: the same lattice of
  // the same frame, drawn at the same first sample.
  static bool same_cache_key(const ScatteredSunCache::Key& a, const ScatteredSunCache::Key& b) {
    return same_lattice(a.view, b.view) && a.view.pixel_offset == b.view.pixel_offset &&
           a.downwind == b.downwind && a.fresnel_r == b.fresnel_r && a.n_min == b.n_min &&
           a.n_max == b.n_max && a.planet_radius == b.planet_radius && a.waves == b.waves &&
           a.cells_per_wavelength == b.cells_per_wavelength && a.cells == b.cells &&
           a.refine == b.refine && a.float_atomics == b.float_atomics;
  }

  // Whether two frames share the reference's sun lattice: everything but the pixel offset.
  static bool same_lattice(const gl::FrameInputs& a, const gl::FrameInputs& b) {
    return a.width == b.width && a.height == b.height && a.camera_right == b.camera_right &&
           a.camera_up == b.camera_up && a.camera_forward == b.camera_forward &&
           a.tan_half_fov_y == b.tan_half_fov_y && a.camera_height == b.camera_height &&
           a.sun_direction == b.sun_direction && a.time == b.time &&
           a.sea_curvature == b.sea_curvature && a.wave_origin == b.wave_origin &&
           a.wave_axes == b.wave_axes;
  }

  // The smallest footprint of a pixel on the sea at rest (m): over the image corners and centre
  // that see the sea, the distance between neighbouring pixels' points (what dFdx gives the
  // shader); +inf when none does.
  static double smallest_footprint(const GridCamera& camera) {
    // Image points of pixel (px, py) (pixels, y up as in the image plane).
    auto image = [&](double px, double py) {
      return glm::dvec2(2.0 * px / camera.width - 1.0, 2.0 * py / camera.height_px - 1.0);
    };
    double smallest = INFINITY;
    for (double px : {0.5, 0.5 * camera.width, camera.width - 1.5})
      for (double py : {0.5, 0.5 * camera.height_px, camera.height_px - 1.5}) {
        glm::dvec3 p, px1, py1;
        if (!sea_point(camera, image(px, py), p) || !sea_point(camera, image(px + 1.0, py), px1) ||
            !sea_point(camera, image(px, py + 1.0), py1))
          continue;
        smallest = std::min(smallest, std::max(glm::length(px1 - p), glm::length(py1 - p)));
      }
    return smallest;
  }

  // The waves the shader sums for the pixel with the smallest footprint (m); the reference
  // sums all.
  int count_resolved(double footprint, double scale) const {
    if (options_.method == OceanMethod::reference) return static_cast<int>(waves_.waves.size());
    if (waves_.waves.empty() || !(scale > 0.0) || !std::isfinite(footprint)) return 0;
    return resolved_wave_range(waves_, std::max(footprint / scale, 1e-6), options_.settings.n_min,
                               options_.settings.n_max)
        .positive;
  }

  OceanNodeOptions options_;
  std::shared_ptr<atmosphere::SkyProvider> provider_;
  std::unique_ptr<atmosphere::GlossySkyMaps> glossy_sky_;  // only with sky_shrm
  std::unique_ptr<EffectiveFresnelTexture> effective_fresnel_;  // with the table or the lobe
  std::unique_ptr<LocalFeatureBuffers> local_features_;    // only with wakes or calm areas
  WaveSet waves_;
  gl::Buffer wave_buffer_;
  gl::Buffer tail_buffer_;
  gl::Buffer vertex_buffer_;  // created with the first grid, resized with the image
  gl::Buffer index_buffer_;
  gl::VertexArray vertex_array_;
  gl::Framebuffer gbuffer_;
  gl::Texture normal_texture_;
  gl::Texture variance_texture_;
  int gbuffer_width_ = 0;
  int gbuffer_height_ = 0;
  GLsizeiptr vertex_capacity_ = 0;
  GLsizeiptr index_capacity_ = 0;
  // The grid in the buffers (draw_grid): the camera and cell it was made for (none before the
  // first, or while a new one is being made), and its index count (0: no sea in view).
  struct GridKey {
    GridCamera camera;
    double cell_px = 0.0;
  };
  std::optional<GridKey> grid_key_;
  std::size_t grid_index_count_ = 0;
  int resolved_waves_ = 0;
  glm::dvec2 constant_variance_{0.0};  // the basic method's slope variance (along, across wind)
  // The reference's sun (scatter_reference_sun): 4 floats per pixel, at the node's lattice and
  // at half its cells; the frame they were computed for; the pixels added beyond each edge; the
  // time of both lattices (ms, wall clock to their read-back; < 0: none yet) and the lattice's
  // convergence measure.
  gl::Buffer reference_sun_buffer_;
  gl::Buffer coarse_sun_buffer_;
  std::size_t reference_sun_floats_ = 0;
  gl::FrameInputs scatter_key_;
  bool has_scatter_key_ = false;
  int scatter_margin_ = 0;
  int scatter_width_ = 0, scatter_height_ = 0;  // the image's pixels, of the lattice run last
  // Subcells per side of the cells near the mirror slope, and cells per invocation, as run
  // (within kShaderLoopBudget).
  int scatter_refine_ = 1;
  int scatter_segment_ = 1;
  int scatter_block_rows_ = 1;
  // The refined cells' queue as run (places; 0: refined in place) and its buffer, and the
  // invocations per chunk of the cells' pass (0: one chunk, as many as a dispatch takes).
  std::int64_t refined_queue_ = 0;
  gl::Buffer refined_buffer_;
  std::size_t refined_buffer_bytes_ = 0;
  std::uint64_t scatter_chunk_ = 0;
  // The cells of the lattice run last (run_scatter); of the finer lattice, and its refined
  // cells and those of them refined in place (all with no queue, else those past a full one).
  double scattered_cells_ = 0.0;
  double lattice_scattered_cells_ = 0.0, lattice_refined_cells_ = 0.0,
         lattice_refined_in_place_ = 0.0;
  gl::Buffer footprint_buffer_;  // 12 floats per footprint, between the scatter's passes
  std::size_t footprint_count_ = 0;
  // Per footprint, its first invocation of pass 2, counted from its batch's first (run_scatter).
  gl::Buffer footprint_start_buffer_;
  std::size_t footprint_start_count_ = 0;
  double scatter_ms_ = -1.0;
  double lattice_row_change_ = 0.0;
  // Per image row (top first, where the scatter's rows are the window's, from the bottom), the
  // relative change measured in it; NaN where none was (a row the coarser lattice leaves
  // unresolved, or below kScatterNegligibleRow of the brightest).
  std::vector<double> lattice_row_changes_;
  // Per image row (top first), the cells along x and y of the finer lattice's footprint with the
  // most (empty when the lattice was kept, ScatteredSunCache).
  ScatterRowCells lattice_row_cells_;
  int lattice_rows_ = 0;  // the rows it was measured on
  // The finer lattice as run (after lattice_doublings_ doublings of the options' lattice): its
  // cells per shortest wavelength and cap (at most cap^2 cells per pixel's footprint).
  double lattice_cells_per_wavelength_ = 0.0;
  int lattice_cap_ = 0;
  int lattice_doublings_ = 0;
  bool float_atomics_ = false;  // the scatter adds with GL_NV_shader_atomic_float
  bool lattice_reused_ = false;  // drawn from options_.reference_sun_cache, not scattered
  // The lattices scattered again this render because their sums held what no scatter writes
  // (scatter_checked; warnings()), and what the last such held; the faults injected so far
  // (OceanNodeOptions::reference_sun_test_faults).
  int rescatters_ = 0;
  int reuploads_ = 0;  // a kept lattice's uploads sent again (upload_checked)
  std::string scatter_fault_;
  // The sums of the finer lattice (in reference_sun_buffer_) and the coarser (coarse_sun_buffer_)
  // as scatter_checked read and checked them: the CPU's only copies.
  std::vector<float> finer_sums_, coarse_sums_;
  double scatter_sea_solid_angle_ = 0.0;  // sr, of the sea at rest in the image (the check's)
  int injected_faults_ = 0;
  double hidden_fraction_ =
      0.0;  // of the front-facing cells' solid angle, behind the grid's crests
};

}  // namespace

double resolved_wave_scale(double camera_height_m) {
  if (!(camera_height_m > kResolvedFadeStart)) return 1.0;
  if (camera_height_m >= kResolvedFadeEnd) return 0.0;
  const double x = (camera_height_m - kResolvedFadeStart) / (kResolvedFadeEnd - kResolvedFadeStart);
  return 1.0 - x * x * (3.0 - 2.0 * x);
}

std::unique_ptr<gl::Node> make_ocean_node(const OceanNodeOptions& options) {
  if (!options.provider) throw std::invalid_argument("make_ocean_node: no sky provider");
  return std::make_unique<OceanNode>(options);
}

}  // namespace thalassa::ocean
