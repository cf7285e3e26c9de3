// The light terms' names (renderer.hpp): what `--terms` and a suite's terms are written in.
#include <algorithm>
#include <string>
#include <string_view>

#include "thalassa/planet/renderer.hpp"

namespace thalassa {

std::string parse_light_terms(std::string_view text, LightTerms& terms) {
  terms = {false, false, false, false};
  int count = 0;
  // Items between commas; a comma at the end closes the last item and opens none.
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string_view item = text.substr(begin, end - begin);
    begin = end + 1;
    if (item == "sun")
      terms.sun = true;
    else if (item == "sky")
      terms.sky = true;
    else if (item == "sea")
      terms.sea = true;
    else if (item == "air")
      terms.air = true;
    else
      return "expected a comma-separated subset of sun, sky, sea, air, got \"" + std::string(item) +
             "\"";
    ++count;
  }
  if (count == 0) return "expected at least one of sun, sky, sea, air";
  return "";
}

}  // namespace thalassa
