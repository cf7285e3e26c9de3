// thalassa — the ocean's shading methods (issue 6; Bruneton, Neyret & Holzschuch 2010, sec. 7.2
// and fig. 10), so that the paper's hierarchy can be measured against simpler methods and a
// reference, and so that users can render each.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace thalassa::ocean {

enum class OceanMethod {
  // The paper's hierarchy: positions filtered by w_p (eq. 2), normals by w_n (eq. 3), and the
  // Ross BRDF of the unresolved waves (eq. 4) with the pixel's own normal variation.
  full,
  // Fig. 10's "basic" method: the same filtered positions and normals, with a constant BRDF: the
  // slope variance the full method has in the image's foreground (its smallest footprint),
  // everywhere, not adapted to the sub-pixel details farther away.
  basic,
  // The full method without the BRDF: filtered positions and normals, and a mirror (the slope
  // variance 0; the sun keeps the width of its disc).
  normals,
  // Every wave as geometry and normals (w_p = w_n = 1, 1-pixel grid cells) and a mirror, each
  // pixel averaged over many samples (the renderer supersamples it: planet/renderer.hpp).
  reference,
};

std::string_view method_name(OceanMethod method);
// "full", "basic", "normals", "reference" -> the method; nullopt otherwise.
std::optional<OceanMethod> parse_method(std::string_view name);

}  // namespace thalassa::ocean
