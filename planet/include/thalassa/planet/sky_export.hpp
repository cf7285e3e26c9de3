// thalassa — the sky as images for other tools (`thalassa sky`, DESIGN section 5): the sky
// provider's stereographic sky map, the very map the ocean reflects, and an equirectangular
// panorama of the sky radiance around the camera. This header exposes no GL types.
//
// Frames and units: directions in the east-north-up frame at the camera's nadir (x east,
// y north, z up); spectral radiance in W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "thalassa/engine/context.hpp"
#include "thalassa/engine/image.hpp"
#include "thalassa/engine/scene.hpp"
#include "thalassa/planet/renderer.hpp"

namespace thalassa {

// The largest map side and panorama width, texels (the scene's image limit: 8192 x 8192 RGBA
// floats is 1 GiB, the most one GL read returns).
constexpr int kSkyExportMaxSize = 8192;

struct SkyExportOptions {
  int map_size = 512;      // texels per side of the stereographic map, [1, kSkyExportMaxSize]
  int panorama_width = 0;  // texels, even, [2, kSkyExportMaxSize]; 0: no panorama
};

struct SkyExportStats {
  std::string backend;       // "egl", "osmesa", "glfw", "host"
  std::string renderer;      // GL_RENDERER
  std::string sky_provider;  // "atmosphere" or "environment_map"
  int map_size = 0;          // texels per side
  int panorama_width = 0;    // texels; 0 when none was asked for
  int panorama_height = 0;
  // Wall-clock ms: "sky.provider" (creating it, the atmosphere's tables computed or loaded
  // included), "atmosphere.precompute" / "atmosphere.load", "sky.map", "sky.panorama".
  std::vector<std::pair<std::string, double>> setup_ms;
  std::vector<std::string> built;  // what was created, as RenderStats::built
};

struct SkyExport {
  // The provider's stereographic sky map seen from the sea surface (height 0) at the camera's
  // nadir: map_size x map_size, rows top first. Texel (i, j) (column i, row j) covers
  // u_x in [-E + 2 E i / N, -E + 2 E (i + 1) / N] and u_y in [E - 2 E (j + 1) / N,
  // E - 2 E j / N], E = atmosphere::kSkyMapExtent (1.25), N = map_size, where
  // u = (r_x, r_y) / (1 + r_z) for the ENU direction r the light comes from: row 0 is north,
  // column 0 west, the horizon is the circle |u| = 1 and outside it the map holds the
  // provider's below-horizon radiance (a constant). No sun disc (the ocean draws the sun
  // itself). Alpha 1.
  Image map;
  double map_extent = 0.0;  // E above (atmosphere::kSkyMapExtent), u units
  // The sky radiance around the camera, seen from max(camera.height, 0): width x width / 2,
  // equirectangular, rows top first; texel (x, y) is the radiance along the direction of
  // azimuth 2 pi (x + 0.5) / width (clockwise from north: the left edge looks north, east is
  // a quarter of the way right) and zenith angle pi (y + 0.5) / height (the top edge is the
  // zenith), the layout EnvironmentMap reads (so a panorama can serve as a scene's sky.exr).
  // The sun's disc is drawn, its light (the disc's radiance times the transmittance along the
  // sun's direction times its solid angle) spread over the texels its area covers, so that the
  // panorama holds the sun's irradiance at any width (the disc, 0.53 deg across, is 3 texels
  // wide at 2048, a fraction of one at 64). Below the horizon: the provider's background (for
  // the atmosphere, the light scattered between the camera and the sea; for a photograph, its
  // ground). Empty (0 x 0) when no panorama was asked for.
  Image panorama;
  std::array<double, 3> sun_direction{};  // the sun used, unit, ENU
  bool sun_from_provider = false;         // it is the photograph's sun, not the scene's
  double panorama_height = 0.0;           // m above the sea, the panorama's viewpoint
  SkyExportStats stats;
};

// Renders the sky of `scene` in `context` (current; it must stay alive during the call) with
// the provider the Renderer would create for it (options.cache_dir and options.shader_roots
// apply; options.terms do not). The sun is the scene's sun (sun.zenith, sun.azimuth, or
// sun.utc's), or the photograph's when `sky.exr` is set and a sun was found in it. Throws
// std::invalid_argument for sizes outside the ranges above, EnvironmentMapError for a
// photograph that cannot serve as a sky, GlError or ShaderError for GL failures. The GL state
// it changes is restored, as Renderer::render() does.
SkyExport render_sky(GlContext& context, const Scene& scene, const SkyExportOptions& options = {},
                     const RendererOptions& renderer_options = {});

}  // namespace thalassa
