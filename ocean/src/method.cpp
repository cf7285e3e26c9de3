#include "thalassa/ocean/method.hpp"

namespace thalassa::ocean {

std::string_view method_name(OceanMethod method) {
  switch (method) {
    case OceanMethod::full:
      return "full";
    case OceanMethod::basic:
      return "basic";
    case OceanMethod::normals:
      return "normals";
    case OceanMethod::reference:
      return "reference";
  }
  return "full";
}

std::optional<OceanMethod> parse_method(std::string_view name) {
  for (OceanMethod m :
       {OceanMethod::full, OceanMethod::basic, OceanMethod::normals, OceanMethod::reference})
    if (method_name(m) == name) return m;
  return std::nullopt;
}

}  // namespace thalassa::ocean
